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
// The terms a case switches off (mu = 0, g = 0) are not built. Declared
// here, compiled for D = 2 and 3 in src/seed_wcsph_model.cpp (the passes'
// and terms' headers stay out of this one).
#pragma once

#include "sph/models/model.hpp"

namespace sph {

struct SeedWcsphParameters {
  Real h = 0.01;      // support radius [m]
  Real k = 2000;      // EOS stiffness
  Real rho0 = 1000;   // rest density
  Real mu = 1;        // dynamic viscosity (0: no viscosity term)
  Real g = 9.81;      // gravity along -e_up (0: no gravity term)
};

template <int D>
Model<D> makeSeedWcsph(const SeedWcsphParameters& prm);

}  // namespace sph
