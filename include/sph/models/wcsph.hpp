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
// never allocated.
#pragma once

#include <optional>

#include "sph/boundaries/boundary.hpp"
#include "sph/models/model.hpp"
#include "sph/models/wcsph_choices.hpp"

#include <string>

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
  DensityReinit reinit = DensityReinit::kNone;
  long reinitEvery = 20;       // steps between re-initialisations
  bool cspm = false;           // CSPM gradient correction in the pressure gradient
  Real surfaceTension = 0;     // sigma of the colour-field force (0: off)
  CurvatureMethod curvature = CurvatureMethod::kMorris;
  bool twoPhase = false;       // colour regions given (else a free surface)
  Real surfaceThreshold = 0.1; // |n| > threshold / h
  std::optional<SinusoidalWallMotion<D>> wallMotion = std::nullopt;  // a paddle (dummy walls read its a_w)
  OptionalTerms terms{};       // terms/optional_terms.hpp (each off by default)
};

template <int D>
Model<D> makeWcsph(const WcsphSpec<D>& s) {
  typename Model<D>::Info info;
  info.name = "wcsph";
  info.support = std::visit([](const auto& k) { return k.support(); }, s.kernel);
  info.smoothingLength = std::visit([](const auto& k) { return k.h(); }, s.kernel);
  const Real h = info.smoothingLength;
  info.restDensity = s.restDensity;
  info.eos = s.eos;
  info.bodies = s.bodies;
  const bool continuity = s.density == DensityTreatment::kContinuity;
  const Real c0 = std::visit([&](const auto& e) { return e.soundSpeed(s.restDensity); }, s.eos);
  const Vec<D> g = s.bodies.gravity ? s.bodies.gravity->vector() : Vec<D>::Zero();
  info.termNames = {continuity ? "continuity_density" : "summation_density", "equation_of_state", "symmetric_pressure"};
  if (continuity) info.needs |= fieldBit(kFieldDrho);
  if (const auto* l = std::get_if<LaplacianViscosityChoice>(&s.viscosity)) {
    info.kinematicViscosity = l->mu / s.restDensity;
    info.termNames.push_back("laplacian_viscosity");
  }
  if (const auto* m = std::get_if<MorrisViscosityChoice>(&s.viscosity)) {
    info.kinematicViscosity = m->nu;
    info.termNames.push_back("morris_viscosity");
  }
  if (std::holds_alternative<MonaghanViscosityChoice>(s.viscosity)) {
    info.needs |= fieldBit(kFieldC);
    info.termNames.push_back("monaghan_viscosity");
  }
  if (s.bodies.gravity) info.termNames.push_back("gravity");
  if (s.bodies.star) info.termNames.push_back("star_attraction");
  forEachActiveTermName(s.terms, [&](const char* name) { info.termNames.push_back(name); });
  if (s.xsphEpsilon > 0) {
    info.needs |= fieldBit(kFieldVXsph);
    info.termNames.push_back("xsph");
  }

  const WallSums walls = s.boundary.sums;
  WcsphForcePass<D> forces{s.kernel, s.viscosity, s.bodies, s.xsphEpsilon, continuity, {}, walls,
                           true, false, std::nullopt, s.terms};
  if (continuity && s.diffusion.delta > 0) {
    forces.diffusion = DensityDiffusion<D>::build(s.diffusion, h, c0, s.restDensity, g);
    info.termNames.push_back(s.diffusion.term);
  }
  forces.wallViscosity = s.noSlip;
  forces.cspm = s.cspm;

  if (s.surfaceTension > 0) {
    // The corrected method spreads kappa over the band's tails: its force acts wherever n != 0.
    const bool band = s.curvature == CurvatureMethod::kCorrected && s.twoPhase;
    forces.surfaceTension = ColourSurfaceTension<D>{s.surfaceTension, band ? 0 : s.surfaceThreshold / h};
    info.needs |= fieldBit(kFieldColour) | fieldBit(kFieldColourNormal) | fieldBit(kFieldCurvature);
    info.termNames.push_back("colour_field");
    info.termNames.push_back(s.curvature == CurvatureMethod::kMuller      ? "surface_tension_muller2003"
                             : s.curvature == CurvatureMethod::kCorrected ? "surface_tension_corrected_morris2000"
                                                                          : "surface_tension_morris2000");
  }

  std::vector<Pass<D>> passes;
  const BoundaryHooks<D>& boundary = s.boundary.template hooks<D>();
  BoundaryBuild<D> build{s, passes, info, g, c0, h};
  if (continuity) {
    passes.push_back(EquationOfStatePass<D>{s.eos, walls, s.clampNegative, s.restDensity});
  } else {
    const auto density = std::visit(
        [](const auto& k) { return DensityKernelChoice<D>(DensityKernel<std::decay_t<decltype(k)>>{k}); }, s.kernel);
    passes.push_back(
        SummationDensityPass<D>{density, s.eos, walls, s.clampNegative});
  }
  boundary.beforeForces(build);  // the walls' pre-pass (dummy walls: Adami's extrapolation)
  if (s.cspm) {
    passes.push_back(CspmCorrectionPass<D>{s.kernel, walls});
    info.needs |= fieldBit(kFieldCspmL);
    info.termNames.push_back("cspm_gradient_correction");
  }
  if (s.surfaceTension > 0) passes.push_back(ColourFieldPass<D>{s.kernel, s.curvature, s.surfaceThreshold / h, s.twoPhase});
  passes.push_back(forces);
  boundary.afterForces(build);  // repulsive walls: their force
  // The re-initialisations sum over the fluid only: between steps a dummy
  // wall's density is not its extrapolated one (that exists only inside an
  // evaluation), dynamic walls' is clamped at rho0 and repulsive walls have
  // none. Including the stale wall densities pulled the fluid at the bottom
  // of the hydrostatic tank to rho0 and let it through the floor.
  std::vector<Pass<D>> afterStep;
  if (s.reinit == DensityReinit::kShepard)
    afterStep.push_back(ShepardDensityPass<D>{s.kernel, s.reinitEvery, WallSums::fluidOnly(), s.eos, s.clampNegative});
  if (s.reinit == DensityReinit::kMls)
    afterStep.push_back(MlsDensityPass<D>{s.kernel, s.reinitEvery, WallSums::fluidOnly(), s.eos, s.clampNegative});
  if (s.reinit != DensityReinit::kNone) {
    info.needs |= fieldBit(kFieldRhoReinit);
    info.termNames.push_back(s.reinit == DensityReinit::kShepard ? "shepard_density_reinit"
                                                                 : "mls_density_reinit_colagrossi2003");
  }
  // The density rate the leap-frog and symplectic Euler integrators take
  // apart (StepContext::densityRateApart): continuity and its diffusion.
  std::vector<Pass<D>> densityRate;
  if (continuity) densityRate.push_back(DensityRatePass<D>{s.kernel, forces.diffusion, walls, s.terms});
  return Model<D>(info, std::move(passes), std::move(afterStep), std::move(densityRate));
}

}  // namespace sph
