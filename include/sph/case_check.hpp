// checkCase<D>: `sph check CASE [--KEY VALUE ...]`: what a case implies,
// before running it, and where it lies outside a method's measured stable
// range. It builds the scene as `sph run` would (nothing is written),
// prints particles, h/dx, neighbours per particle, the initial density and
// pressure range, c0 against the speed the case can reach (sqrt(2 g H) and
// the initial velocities: the Mach number), dt against the acoustic,
// viscous and body-force limits, wall layers against the support, memory,
// and a time estimate from a short timed sample of steps. Exit 0 (with a
// `warning:` line per concern), 2 for bad input.
#pragma once

#include "sph/case_config.hpp"

#include <iosfwd>

namespace sph {

template <int D>
int checkCase(const CaseConfig& c, std::ostream& out, std::ostream& err);

}  // namespace sph
