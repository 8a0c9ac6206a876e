// The checks of the probe keys (called by validateCase): counts of the
// coordinate lists, one name per point probe, names fit for a CSV header,
// and a lattice spacing for the gauges that use it.
#include "sph/case_config.hpp"
#include "sph/io/probe_files.hpp"

#include <set>
#include <string>

namespace sph {

void validateProbes(const CaseConfig& c) {
  const auto D = static_cast<std::size_t>(c.dimension);
  const std::string d = std::to_string(D), horizontal = std::to_string(D - 1);
  if (c.probePoints.size() % D != 0)
    throw CaseError("probe_points needs " + d + " values per probe (" + std::to_string(c.probePoints.size()) +
                    " given)");
  if (c.heightProbes.size() % (D - 1) != 0)
    throw CaseError("height_probes needs " + horizontal + " values per gauge in " + d + "D (" +
                    std::to_string(c.heightProbes.size()) + " given)");
  const std::size_t points = c.probePoints.size() / D;
  if (!c.probeNames.empty()) {
    if (points == 0) throw CaseError("probe_names is given but there are no probe_points");
    const auto names = probeNames(c, points);
    if (names.size() != points)
      throw CaseError("probe_names has " + std::to_string(names.size()) + " names for " + std::to_string(points) +
                      " probe_points: give one name per probe");
    std::set<std::string> seen;
    for (const auto& name : names) {
      if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") !=
                              std::string::npos)
        throw CaseError("probe_names: \"" + name + "\" is not allowed: use letters, digits, '_', '-' and '.'");
      if (!seen.insert(name).second) throw CaseError("probe_names: \"" + name + "\" is given twice");
    }
  }
  if (c.probeWindow > 0 && c.probeInterval > c.probeWindow)
    throw CaseError("probe_window = " + std::to_string(c.probeWindow) + " s is shorter than probe_interval = " +
                    std::to_string(c.probeInterval) + " s: the moving average needs several samples");
  if ((!c.heightProbes.empty() || c.frontProbe) && !(c.spacing > 0))
    throw CaseError("height_probes and front_probe need the lattice spacing: set spacing > 0");
}

}  // namespace sph
