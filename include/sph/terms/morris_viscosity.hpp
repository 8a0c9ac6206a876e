// Laminar viscosity of Morris, Fox & Zhu 1997 ("Modeling low Reynolds
// number incompressible flows using SPH", J. Comput. Phys. 136, 214-226,
// eq. 8), with a kinematic viscosity nu (mu = rho nu):
//
//   a_i = sum_j m_j (mu_i + mu_j) / (rho_i rho_j)
//                   (r_ij . grad_i W_ij) / (r_ij^2 + eta^2)  (v_i - v_j),
//   eta^2 = 1e-4 h^2 (Morris et al. write 0.01 h^2; see below),
//
// r_ij = x_i - x_j, so r_ij . grad_i W_ij = r^2 (dW/dr)/r < 0 and the term
// pulls v_i towards v_j. It is an SPH estimate of (1/rho) div(mu grad v)
// built from the first derivative of the kernel (well behaved where a
// kernel's second derivative is not), and it reproduces a linear shear flow
// exactly on a regular lattice, the property the Poiseuille and Couette
// references test.
//
// eta only keeps the term finite for two particles at one point: it also
// scales each pair by r^2 / (r^2 + eta^2). On a lattice at h = 1.5 dx the
// operator applied to u = y^2/2 gives 0.985 with 0.01 h^2 and 0.996 with
// 1e-4 h^2 (the exact Laplacian is 1; lattice sum over the Wendland C2
// kernel; tests/test_laminar.cpp checks it): the paper's value
// made the plane Poiseuille flow 1.5% too fast at steady state.
//
// Walls (kWall): j is a dummy or dynamic wall particle with the velocity it
// shows the fluid, vWall (no-slip: 2 u_w - v~_w, the velocity extrapolated
// to the wall by Adami, Hu & Adams 2012, eq. 23; free-slip: v~_w) and its
// extrapolated density, so a moving wall's velocity u_w enters here.
#pragma once

#include "sph/pair_loop.hpp"
#include "sph/terms/term_bits.hpp"

namespace sph {

template <class Kernel, bool kWall = false>
struct MorrisViscosity {
  static constexpr unsigned bit = term_bits::kMorrisViscosity;
  static constexpr unsigned writes = rates::kAcceleration;
  Kernel kernel;
  Real nu;  // kinematic viscosity [m^2/s] (0: the term adds nothing)

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    const Real h = kernel.h();
    const Real rho_i = P.rho[c.i], rho_j = P.rho[c.j];
    const Vec<D>& vj = kWall ? P.vWall[c.j] : P.v[c.j];
    // (mu_i + mu_j) / (rho_i rho_j) = nu (rho_i + rho_j) / (rho_i rho_j);
    // r . grad W = r^2 (dW/dr) / r.
    const Real r2 = c.r * c.r;
    const Real f = P.m[c.j] * nu * (rho_i + rho_j) / (rho_i * rho_j) * (r2 * c.dWdr_r) / (r2 + 1e-4 * h * h);
    r.a += f * (P.v[c.i] - vj);
  }
};

}  // namespace sph
