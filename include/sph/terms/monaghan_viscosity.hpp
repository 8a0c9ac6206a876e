// Monaghan artificial viscosity (Monaghan 1992, Annu. Rev. Astron.
// Astrophys. 30, eq. 4.1-4.2):
//
//   a_i = - sum_j m_j Pi_ij grad_i W(r_ij, h),
//   Pi_ij = (-alpha cbar_ij mu_ij + beta mu_ij^2) / rhobar_ij   if v_ij . r_ij < 0
//         = 0                                                   otherwise,
//   mu_ij = h v_ij . r_ij / (r_ij^2 + eps h^2),   eps = 0.01,
//
// with v_ij = v_i - v_j, r_ij = x_i - x_j, bar = mean of i and j. Active only
// for approaching pairs; needs the sound speed c of every particle.
#pragma once

#include "sph/terms/term_bits.hpp"

#include "sph/pair_loop.hpp"

namespace sph {

// With wall neighbours it sees their own (prescribed) velocity, as with
// dynamic boundary particles in DualSPHysics: the no-slip extrapolation of
// dummy walls is for physical viscosity, and doubled relative velocities in
// this artificial term glue free-surface particles to a vertical wall.
// (kWall is accepted for a uniform pack shape and changes nothing.)
template <class Kernel, bool kWall = false>
struct MonaghanViscosity {
  static constexpr unsigned bit = term_bits::kMonaghanViscosity;
  static constexpr unsigned writes = rates::kAcceleration;
  Kernel kernel;
  Real alpha, beta;
  static constexpr Real eps = 0.01;

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    const Real vr = (P.v[c.i] - P.v[c.j]).dot(c.rij);
    if (vr >= 0) return;
    const Real h = kernel.h();
    const Real mu = h * vr / (c.r * c.r + eps * h * h);
    const Real cBar = (Real(P.c[c.i]) + P.c[c.j]) / 2, rhoBar = (P.rho[c.i] + P.rho[c.j]) / 2;
    const Real Pi = (-alpha * cBar * mu + beta * mu * mu) / rhoBar;
    r.a += (-P.m[c.j] * Pi) * c.gradW;
  }
};

}  // namespace sph
