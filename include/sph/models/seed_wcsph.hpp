// Model "seed_wcsph": the seed 2D weakly-compressible Navier-Stokes scheme,
// as a preset of the generic passes.
//
//   rho_i = sum_j m 4/(pi h^2) (1 - q^2)^3                (self term included)
//   p_i   = k (rho_i - rho0)
//   a_i   = (F_p,i + F_v,i + F_g,i) / rho_i
//   F_p,i = - sum_{j!=i} (m/rho_j) (p_i + p_j)/2 (-30/(pi h^3)) r_ij (1-q)^2/q
//   F_v,i = - mu sum_{j!=i} (m/rho_j) v_ij 40/(pi h^4) (1 - q)
//   F_g,i = -rho_i g e_up
// with support radius h, mass scaled once so the mean density is rho0, leap-
// frog time stepping and damped reflecting walls (see the files of each part).
// v_ij is the half-step velocity v^{t-1/2} (v^0 on the first step): the seed
// document's leap-frog holds no other (docs/methods/seed-model.md).
//
// Passes: summation density with the linear EOS, then the seed forces.
// The terms a case switches off (mu = 0, g = 0) are not built.
#pragma once

#include "sph/models/model.hpp"

#include <cmath>

namespace sph {

struct SeedWcsphParameters {
  Real h = 0.01;      // support radius [m]
  Real k = 2000;      // EOS stiffness
  Real rho0 = 1000;   // rest density
  Real mu = 1;        // dynamic viscosity (0: no viscosity term)
  Real g = 9.81;      // gravity along -e_up (0: no gravity term)
};

template <int D>
Model<D> makeSeedWcsph(const SeedWcsphParameters& prm) {
  const SeedKernels kernels(prm.h);
  typename Model<D>::Info info;
  info.name = "seed_wcsph";
  info.support = info.smoothingLength = prm.h;
  info.restDensity = prm.rho0;
  info.eos = LinearEos{prm.k, prm.rho0};
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
  info.bodies = forces.bodies;
  return Model<D>(info, {SummationDensityPass<D>{kernels, info.eos}, forces});
}

}  // namespace sph
