// The wcsph model's preset, makeWcsph (models/wcsph.hpp has the model and
// its passes), compiled for D = 2 and 3: the one file outside the pass
// instantiations and the tests that includes the force pass, its terms and
// the pair loop to build a model.
#include "sph/models/wcsph.hpp"

#include "sph/passes/colour_field.hpp"
#include "sph/passes/cspm_correction.hpp"
#include "sph/passes/density_rate.hpp"
#include "sph/passes/equation_of_state.hpp"
#include "sph/passes/mls_density.hpp"
#include "sph/passes/shepard_density.hpp"
#include "sph/passes/summation_density.hpp"
#include "sph/passes/wcsph_forces.hpp"

#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace sph {

template <int D>
Model<D> makeWcsph(const WcsphSpec<D>& s) {
  typename Model<D>::Info info;
  info.name = "wcsph";
  info.support = std::visit([](const auto& k) { return k.support(); }, s.kernel);
  info.smoothingLength = std::visit([](const auto& k) { return k.h(); }, s.kernel);
  const Real h = info.smoothingLength;
  info.restDensity = s.restDensity;
  info.eos = std::make_shared<const EquationOfState>(s.eos);
  if (s.bodies.gravity || s.bodies.star) info.bodies = std::make_shared<const BodyForces<D>>(s.bodies);
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
    // Clamped pressures (negative_pressure = clamp, or an EOS that clamps):
    // the diffusion reads the density the pressure reads, max(rho, rho_c),
    // where the walls fill the support of the fluid next to them (dummy and
    // dynamic wall particles, or no walls). Against reflecting walls or a
    // repulsive layer a fluid particle at the wall sums a truncated
    // kernel, its continuity density drifts down there, and the diffusion
    // towards its neighbours is what holds it: floored, the dam break's
    // density went below zero at 0.05 s (repulsive) and 0.41 s (reflecting;
    // 0.84 s without the floor). docs/methods/boundaries.md.
    const bool clamped = !s.wallsOutsideDensity && (s.clampNegative || std::visit([](const auto& e) {
                           return std::is_same_v<std::decay_t<decltype(e)>, ClampedLinearEos>;
                         }, s.eos));
    const Real zeroPressure = clamped ? std::visit([](const auto& e) { return e.density(0); }, s.eos)
                                      : -std::numeric_limits<Real>::infinity();
    forces.diffusion = DensityDiffusion<D>::build(s.diffusion, h, c0, s.restDensity, g, zeroPressure);
    info.termNames.push_back(s.diffusion.term);
  }
  forces.wallViscosity = s.noSlip;
  forces.cspm = s.cspm;
  // Particle shifting's sums in the force loop (terms/shifting_sums.hpp),
  // unless the walls stay out of the pairs (repulsive walls: the shift's
  // own walk takes them).
  if (s.shifting && walls.inSums) {
    forces.shifting = {true, s.spacing, s.restDensity};
    info.needs |= fieldBits(kFieldShiftSum, kFieldShiftGrad);
    info.shiftSums = true;
  }

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

  PassList<D> passes;
  const BoundaryHooks<D>& boundary = s.boundary.template hooks<D>();
  // vWall is allocated only for a viscosity that reads it.
  BoundaryBuild<D> build{s.kernel,     info.eos, s.restDensity, s.noSlip, readsWallVelocity(s.viscosity), s.spacing,
                         s.wallMotion, g,     c0,            h,        passes,                         info};
  if (continuity) {
    passes.push_back(makePass(EquationOfStatePass<D>{s.eos, walls, s.clampNegative, s.restDensity}));
  } else {
    const auto density = std::visit(
        [](const auto& k) { return DensityKernelChoice<D>(DensityKernel<std::decay_t<decltype(k)>>{k}); }, s.kernel);
    passes.push_back(makePass(SummationDensityPass<D>{density, s.eos, walls, s.clampNegative}));
  }
  boundary.beforeForces(build);  // the walls' pre-pass (dummy walls: Adami's extrapolation)
  if (s.cspm) {
    passes.push_back(makePass(CspmCorrectionPass<D>{s.kernel, walls}));
    info.needs |= fieldBit(kFieldCspmL);
    info.termNames.push_back("cspm_gradient_correction");
  }
  if (s.surfaceTension > 0)
    passes.push_back(makePass(ColourFieldPass<D>{s.kernel, s.curvature, s.surfaceThreshold / h, s.twoPhase}));
  passes.push_back(makePass(forces));
  boundary.afterForces(build);  // repulsive walls: their force
  // The re-initialisations sum over the fluid only: between steps a dummy
  // wall's density is not its extrapolated one (that exists only inside an
  // evaluation), dynamic walls' is clamped at rho0 and repulsive walls have
  // none. Including the stale wall densities pulled the fluid at the bottom
  // of the hydrostatic tank to rho0 and let it through the floor.
  PassList<D> afterStep;
  if (s.reinit == DensityReinit::kShepard)
    afterStep.push_back(
        makePass(ShepardDensityPass<D>{s.kernel, s.reinitEvery, WallSums::fluidOnly(), s.eos, s.clampNegative}));
  if (s.reinit == DensityReinit::kMls)
    afterStep.push_back(
        makePass(MlsDensityPass<D>{s.kernel, s.reinitEvery, WallSums::fluidOnly(), s.eos, s.clampNegative}));
  if (s.reinit != DensityReinit::kNone) {
    info.needs |= fieldBit(kFieldRhoReinit);
    info.termNames.push_back(s.reinit == DensityReinit::kShepard ? "shepard_density_reinit"
                                                                 : "mls_density_reinit_colagrossi2003");
  }
  // The density rate the leap-frog and symplectic Euler integrators take
  // apart (StepContext::densityRateApart): continuity and its diffusion.
  PassList<D> densityRate;
  if (continuity) densityRate.push_back(makePass(DensityRatePass<D>{s.kernel, forces.diffusion, walls, s.terms}));
  return Model<D>(info, std::move(passes), std::move(afterStep), std::move(densityRate));
}

template Model<2> makeWcsph<2>(const WcsphSpec<2>&);
template Model<3> makeWcsph<3>(const WcsphSpec<3>&);

}  // namespace sph
