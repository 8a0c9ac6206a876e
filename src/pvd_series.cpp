#include "sph/io/pvd_series.hpp"

#include "sph/io/atomic_file.hpp"
#include "sph/io/number_format.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace sph {
namespace {

// The value of attribute `name` in one <DataSet .../> line, or "".
std::string attribute(const std::string& line, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const auto at = line.find(key);
  if (at == std::string::npos) return "";
  const auto begin = at + key.size(), end = line.find('"', begin);
  return end == std::string::npos ? "" : line.substr(begin, end - begin);
}

}  // namespace

PvdSeries PvdSeries::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read the series " + path);
  PvdSeries s(path);
  std::string line;
  bool collection = false;
  while (std::getline(in, line)) {
    if (line.find("<VTKFile type=\"Collection\"") != std::string::npos) collection = true;
    if (line.find("<DataSet ") == std::string::npos) continue;
    Entry e{};
    try {
      std::size_t used = 0;
      const std::string t = attribute(line, "timestep"), st = attribute(line, "step");
      e.time = std::stod(t, &used);
      if (used != t.size()) throw std::invalid_argument(t);
      e.step = std::stol(st, &used);
      if (used != st.size()) throw std::invalid_argument(st);
    } catch (const std::exception&) {
      throw std::runtime_error("the series " + path + " has a dataset without a readable time and step: " + line);
    }
    e.file = attribute(line, "file");
    if (e.file.empty()) throw std::runtime_error("the series " + path + " has a dataset without a file: " + line);
    s.entries_.push_back(e);
  }
  if (!collection) throw std::runtime_error(path + " is not a .pvd collection");
  return s;
}

void PvdSeries::add(Real time, long step, const std::string& relativeFile, bool write) {
  entries_.push_back({time, step, relativeFile});
  if (!write) return;
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const Entry& e : entries_)
    xml += "    <DataSet timestep=\"" + shortestDecimal(e.time) + "\" step=\"" + std::to_string(e.step) +
           "\" group=\"\" part=\"0\" file=\"" + e.file + "\"/>\n";
  xml += "  </Collection>\n</VTKFile>\n";
  writeFileAtomically(path_, xml);
}

}  // namespace sph
