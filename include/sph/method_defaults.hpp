// The methods a case takes when it names none (part of the registry,
// methods.hpp): the model, boundary and density treatment as CaseConfig's
// initial values; the integrator always, and the kernel, EOS and viscosity
// under a composed model, filled in by withDefaults (the one place defaults
// are applied). The key table's defaults read these too.
#pragma once

namespace sph {

inline constexpr const char* kDefaultModel = "seed_wcsph";
inline constexpr const char* kDefaultIntegrator = "leap_frog";
inline constexpr const char* kDefaultKernel = "cubic_spline";
inline constexpr const char* kDefaultEos = "linear";
inline constexpr const char* kDefaultViscosity = "laplacian";
inline constexpr const char* kDefaultBoundary = "reflecting";
inline constexpr const char* kDefaultDensity = "summation";
// The neighbour list's Verlet skin under a composed model (a fraction of the
// support; scene.hpp); the seed scheme keeps 0, a list per evaluation. 0.05
// since the water walks' SIMD rows (2026-12-06: each listed pair beyond the
// support costs a lane; docs/performance.md#neighbour-list-skin).
inline constexpr double kDefaultNeighbourSkin = 0.05;

}  // namespace sph
