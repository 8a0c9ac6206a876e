#include "sph/io/pvd_series.hpp"

#include "sph/io/atomic_file.hpp"

#include <cstdio>
#include <string>

namespace sph {

void PvdSeries::add(Real time, const std::string& relativeFile) {
  entries_.emplace_back(time, relativeFile);
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  char line[64];
  for (const auto& [t, file] : entries_) {
    std::snprintf(line, sizeof line, "%.17g", t);
    xml += "    <DataSet timestep=\"" + std::string(line) + "\" group=\"\" part=\"0\" file=\"" +
           file + "\"/>\n";
  }
  xml += "  </Collection>\n</VTKFile>\n";
  writeFileAtomically(path_, xml);
}

}  // namespace sph
