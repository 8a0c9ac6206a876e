// The seed model's preset, makeSeedWcsph (models/seed_wcsph.hpp has the
// scheme), compiled for D = 2 and 3: its passes and terms are included here
// and in the files that compile the passes, not where a model is run.
#include "sph/models/seed_wcsph.hpp"

#include "sph/passes/seed_forces.hpp"
#include "sph/passes/summation_density.hpp"

namespace sph {

template <int D>
Model<D> makeSeedWcsph(const SeedWcsphParameters& prm) {
  const SeedKernels kernels(prm.h);
  typename Model<D>::Info info;
  info.name = "seed_wcsph";
  info.support = info.smoothingLength = prm.h;
  info.restDensity = prm.rho0;
  const EquationOfState eos = LinearEos{prm.k, prm.rho0};
  info.eos = std::make_shared<const EquationOfState>(eos);
  info.termNames = {"seed_density", "linear_eos", "seed_pressure"};
  // The viscous term's v_ij at step t is the half-step v^{t-1/2}: the seed's
  // leap-frog holds no other velocity (docs/methods/seed-model.md).
  info.forcesSeeHalfStepVelocity = true;
  SeedForcePass<D> forces{SeedPressure{kernels}, std::nullopt, {}};
  if (prm.mu > 0) {
    forces.viscosity = SeedViscosity{kernels, prm.mu};
    info.kinematicViscosity = prm.mu / prm.rho0;
    info.termNames.push_back("seed_viscosity");
  }
  if (prm.g != 0) {
    forces.bodies.gravity = UniformGravity<D>::down(prm.g);
    info.termNames.push_back("gravity");
  }
  if (forces.bodies.gravity) info.bodies = std::make_shared<const BodyForces<D>>(forces.bodies);
  return Model<D>(info, {makePass(SummationDensityPass<D>{kernels, eos}), makePass(forces)});
}

template Model<2> makeSeedWcsph<2>(const SeedWcsphParameters&);
template Model<3> makeSeedWcsph<3>(const SeedWcsphParameters&);

}  // namespace sph
