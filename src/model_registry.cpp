// The factory's builders of a case's model and scene (model_registry.hpp),
// compiled for D = 2 and 3: the presets' specs are filled here from the
// method tables, so the optional terms' declarations are included here, the
// passes and the pair loop are not (src/wcsph_model.cpp builds the passes).
#include "sph/model_registry.hpp"

#include "sph/models/seed_wcsph.hpp"
#include "sph/models/wcsph.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "sph/terms/optional_terms.hpp"

#include <cmath>
#include <utility>

namespace sph {

EquationOfState makeEos(const ResolvedCase& c) { return methodRow(eosMethods(), "eos", c.eos).make(c); }

template <int D>
Model<D> makeModel(const ResolvedCase& c, std::optional<SinusoidalWallMotion<D>> wallMotion) {
  if (!composedModel(c)) return makeSeedWcsph<D>(SeedWcsphParameters{c.h, c.k, c.rho0, c.mu, c.g});
  WcsphSpec<D> spec{makeKernel<D>(c), makeEos(c), makeViscosity(c), c.rho0, {}, c.xsph};
  const Vec<D> g = gravityVector<D>(c);
  if (!g.isZero()) spec.bodies.gravity = UniformGravity<D>{g};
  if (c.starMass > 0) spec.bodies.star = StarAttraction<D>{starLambda(c)};
  spec.density = densityTreatment(c);
  spec.diffusion = densityDiffusion(c);
  spec.boundary = activeBoundary(c);
  spec.noSlip = noSlipWalls(c);
  spec.spacing = c.spacing;
  spec.clampNegative = clampNegativePressure(c);
  // (Reflecting walls on a box periodic along every axis meet no fluid.)
  const bool wallsMet = c.walls && periodicAxes(c) != (1u << c.dimension) - 1u;
  spec.wallsOutsideDensity =
      wallsMet && (spec.boundary.particles == WallLattice::kNone || !spec.boundary.sums.inSums);
  spec.reinit = methodRow(densityReinitMethods(), "density_reinit", c.densityReinit).make(c);
  spec.reinitEvery = c.densityReinitEvery;
  spec.cspm = methodRow(gradientCorrectionMethods(), "gradient_correction", c.gradientCorrection).make(c);
  spec.terms = optionalTermsOf(c);
  if (const auto curvature = surfaceTensionCurvature(c)) {
    spec.surfaceTension = c.sigma;
    spec.curvature = *curvature;
  }
  spec.twoPhase = !c.colourBoxMin.empty() || !c.colourEllipseCenter.empty();
  spec.surfaceThreshold = c.surfaceThreshold;
  spec.wallMotion = wallMotion;
  spec.shifting = shiftingOn(c);
  return makeWcsph<D>(spec);
}

template <int D>
Scene<D> makeScene(const ResolvedCase& c, InitialState<D> init, Real startTime) {
  const Vec<D> lo = toVec<D>(c.domainMin), hi = toVec<D>(c.domainMax);
  const PeriodicBox<D> periodic{lo, hi - lo, periodicAxes(c)};
  const Boundary boundary = activeBoundary(c);
  const BoundaryHooks<D>& hooks = boundary.hooks<D>();
  if (std::isnan(startTime)) startTime = init.startTime;
  StateCheck<D> check(lo, hi);
  hooks.stateCheck(check, c);
  const auto motion = makeWallMotion<D>(c, init.particles.fluidCount());
  if (motion) {
    // The paddle's velocity at the start (its particles come at rest).
    for (std::size_t i = init.particles.fluidCount(); i < init.particles.size(); ++i)
      if (motion->moves(init.particles.id[i])) init.particles.v[i] = motion->velocity(startTime);
  }
  Scene<D> scene(std::move(init.particles), makeModel<D>(c, motion), hooks.constraint(c), check, TimeStepControl{c.dt, c.cfl, c.endTime},
                 startTime, makeIntegrator<D>(c.integrator), c.neighbourSkin);
  scene.setNeighbourStorage(neighbourStorage(c));
  if (periodic.any()) scene.setPeriodic(periodic);
  if (motion) scene.setWallMotion(*motion);
  if (shiftingOn(c))
    scene.setShifting(ParticleShifting<D>(makeKernel<D>(c), c.shiftingCoefficient, c.spacing, c.rho0));
  return scene;
}

template Model<2> makeModel<2>(const ResolvedCase&, std::optional<SinusoidalWallMotion<2>>);
template Model<3> makeModel<3>(const ResolvedCase&, std::optional<SinusoidalWallMotion<3>>);
template Scene<2> makeScene<2>(const ResolvedCase&, InitialState<2>, Real);
template Scene<3> makeScene<3>(const ResolvedCase&, InitialState<3>, Real);

}  // namespace sph
