// Basic numeric types shared by every module.
//
// Real is double throughout: the seed scheme's pressure constants span many
// orders of magnitude (k ~ 1e3, h^-4 ~ 1e8) and the tests compare against
// analytic solutions to round-off.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace sph {

using Real = double;

// The type of the particle fields that tolerate single precision: the
// density rate, pressure, sound speed and mass (fields.hpp). float in a
// mixed-precision build (cmake -DSPH_PRECISION=mixed, which defines
// SPH_MIXED_PRECISION), else Real. Positions, velocities, accelerations and
// density stay in Real, and every pass sums in Real and rounds once, when
// it stores (docs/performance.md, "Mixed precision").
#ifdef SPH_MIXED_PRECISION
using Narrow = float;
inline constexpr const char* kBuildPrecision = "mixed";
#else
using Narrow = Real;
inline constexpr const char* kBuildPrecision = "double";
#endif

template <int D>
using Vec = Eigen::Matrix<Real, D, 1>;

// D x D matrix (the CSPM correction L_i).
template <int D>
using Mat = Eigen::Matrix<Real, D, D>;

template <int D>
using IVec = Eigen::Matrix<std::int64_t, D, 1>;

// An axis-aligned box [lo, hi] (an obstacle, a region).
template <int D>
struct AxisBox {
  Vec<D> lo, hi;
};

// Loops over fewer particles than this run on one thread: below it, starting
// an OpenMP team costs more than the loop (a 4-particle case ran 40x slower).
constexpr std::size_t kMinParallelSize = 512;

// The axis gravity acts along: y in 2D, z in 3D ("up" is the last axis).
template <int D>
constexpr int verticalAxis = D - 1;

}  // namespace sph
