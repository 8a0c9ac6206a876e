// The round-off of the narrow fields (sph::Narrow, types.hpp: the density
// rate, pressure, sound speed and mass; float in a mixed-precision build),
// for the tests that compare such values, or what follows from them, with
// a hand computation or an exact reference.
#pragma once

#include "sph/types.hpp"

#include <algorithm>
#include <limits>

namespace sph::test {

// Machine epsilon of the narrow fields' type (2.2e-16 in a double build,
// 1.2e-7 in a mixed one).
inline constexpr Real kNarrowEpsilon = std::numeric_limits<Narrow>::epsilon();

// A relative tolerance: the test's own (a double's round-off) or `ulps` of
// the narrow type's epsilon, whichever is larger; in a double build the
// test's own, unchanged.
inline Real storedTolerance(Real doubleTolerance, Real ulps = 4) {
  return std::max(doubleTolerance, ulps * kNarrowEpsilon);
}

}  // namespace sph::test
