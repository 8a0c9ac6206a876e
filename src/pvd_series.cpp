#include "sph/io/pvd_series.hpp"

#include "sph/io/atomic_file.hpp"

#include <cstdio>
#include <string>

namespace sph {

void PvdSeries::add(Real time, long step, const std::string& relativeFile) {
  entries_.push_back({time, step, relativeFile});
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  char line[64];
  for (const Entry& e : entries_) {
    std::snprintf(line, sizeof line, "%.17g", e.time);
    xml += "    <DataSet timestep=\"" + std::string(line) + "\" step=\"" + std::to_string(e.step) +
           "\" group=\"\" part=\"0\" file=\"" + e.file + "\"/>\n";
  }
  xml += "  </Collection>\n</VTKFile>\n";
  writeFileAtomically(path_, xml);
}

}  // namespace sph
