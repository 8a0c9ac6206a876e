// runCase<D>: one whole run of a validated case: build the particles, check
// everything that can be checked, only then create the output folder, step,
// write snapshots, the .pvd series and energy.csv, and print a summary.
//
// Exit codes: 0 success, 2 bad input (nothing written), 3 the run blew up
// (outputs written so far stay valid), 4 an output file could not be written.
#pragma once

#include "sph/case_config.hpp"

#include <iosfwd>

namespace sph {

enum ExitCode { kSuccess = 0, kBadInput = 2, kBlewUp = 3, kWriteFailed = 4 };

template <int D>
int runCase(const CaseConfig& c, std::ostream& out, std::ostream& err);

}  // namespace sph
