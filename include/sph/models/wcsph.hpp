// Model "wcsph": weakly-compressible SPH composed by name from a kernel, an
// equation of state, a viscosity, body forces and XSPH.
//
//   rho_i = sum_j m_j W(r_ij, h)                               (self term included)
//   p_i   = EOS(rho_i)                                          (equation_of_state.hpp)
//   a_i   = - sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2) grad W     (symmetric_pressure.hpp)
//           + viscosity (none | laplacian | monaghan | morris)
//           [+ the optional pair terms: artificial pressure]  (terms/optional_terms.hpp)
//           + body forces (gravity -g e_up, star -lambda x)
//           [+ the optional per-particle terms: damping -nu v]
//           [+ colour-field surface tension]                  (colour_surface_tension.hpp)
//   dx_i/dt = v_i [+ XSPH correction]
// (Monaghan 1992; Monaghan 2005, "Smoothed particle hydrodynamics", Rep. Prog. Phys. 68.)
//
// Passes: summation density with the EOS (or the EOS of the integrated
// density), the boundary's passes before the forces (boundaries/*.hpp), the CSPM correction L_i when it is on,
// the colour field when surface tension is on, then the fused force pass
// and the boundary's passes after it (repulsive walls: their force);
// after a step, the density re-initialisation (Shepard or MLS) every N
// steps when it is on. A
// viscosity set to none or a body force whose coefficient is zero is never
// constructed, and the arrays it would need (sound speed, XSPH correction)
// never allocated. The preset is declared here and compiled for D = 2 and 3
// in src/wcsph_model.cpp, the one file that builds its passes.
#pragma once

#include "sph/boundaries/boundary.hpp"
#include "sph/kernels/kernels.hpp"
#include "sph/models/model.hpp"
#include "sph/models/wcsph_choices.hpp"
#include "sph/terms/body_forces.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "sph/terms/optional_terms.hpp"
#include "sph/wall_motion.hpp"

#include <optional>

namespace sph {

// Everything a wcsph model is made of, already resolved from names.
template <int D>
struct WcsphSpec {
  Kernel<D> kernel;
  EquationOfState eos;
  ViscosityChoice viscosity = NoViscosity{};
  Real restDensity = 1000;
  BodyForces<D> bodies;
  Real xsphEpsilon = 0;
  DensityTreatment density = DensityTreatment::kSummation;
  DensityDiffusionChoice diffusion = {};  // delta-SPH (continuity; delta 0: off)
  Boundary boundary{};         // how the walls act (boundaries/boundary.hpp; none by default)
  bool noSlip = true;          // dummy/dynamic walls in the viscous term
  Real spacing = 0;            // fluid spacing dx (repulsive walls)
  bool clampNegative = false;  // negative_pressure = clamp
  // Walls that do not fill the support of the fluid next to them
  // (reflecting walls: no particles; repulsive: one layer, no support behind
  // it): the diffusion keeps no floor under clamped pressures
  // (src/wcsph_model.cpp).
  bool wallsOutsideDensity = false;
  DensityReinit reinit = DensityReinit::kNone;
  long reinitEvery = 20;       // steps between re-initialisations
  bool cspm = false;           // CSPM gradient correction in the pressure gradient
  Real surfaceTension = 0;     // sigma of the colour-field force (0: off)
  CurvatureMethod curvature = CurvatureMethod::kMorris;
  bool twoPhase = false;       // colour regions given (else a free surface)
  Real surfaceThreshold = 0.1; // |n| > threshold / h
  std::optional<SinusoidalWallMotion<D>> wallMotion = std::nullopt;  // a paddle (dummy walls read its a_w)
  OptionalTerms terms{};       // terms/optional_terms.hpp (each off by default)
  bool shifting = false;       // the scene shifts the particles: the force pass takes the shift's sums
};

template <int D>
Model<D> makeWcsph(const WcsphSpec<D>& s);

}  // namespace sph
