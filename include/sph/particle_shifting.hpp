// Particle shifting: a small displacement of each fluid particle down the
// gradient of the particle concentration, which keeps the particles of an
// internal flow evenly spread where the flow would bunch them into streaks
// and clumps (Xu, Stansby & Laurence 2009; Lind, Xu, Stansby & Rogers 2012,
// J. Comput. Phys. 231, 1499):
//
//   dr_i   = -A h U dt grad C_i,   U = max_j |v_j| over the fluid,
//   grad C_i = sum_j V_j [1 + R (W_ij / W(dx))^n] grad_i W_ij,
//   V_j = m_j / rho_j (wall particles: m_j / rho0, their lattice volume),
//   R = 0.2, n = 4 (Lind et al. 2012: the term that keeps a perfect lattice,
//   where grad C = 0, from pairing under the shift).
//
// A is the key shifting_coefficient. A = 4 is the delta+-SPH coefficient of
// Sun, Colagrossi, Marrone & Zhang 2017 (Comput. Methods Appl. Mech. Engrg.
// 315, 25): CFL Ma (2h)^2 = (c dt / h)(U / c) 4 h^2 = 4 h U dt. The global
// U, not each particle's |v_i| (Skillen et al. 2013), matters: measured on
// the Taylor-Green vortex (50 x 50, continuity density with delta), the
// local form let the particles clump at the stagnation points, where |v_i|
// is 0, and decayed the vortex 10% too fast; the global one 1.3%. The shift
// is applied once per step, at its start (x^n + dr before the drift, with
// the neighbour list of x^n), so a resumed run shifts exactly as the
// uninterrupted one. Quantities are not corrected to the shifted position
// (the first-order Taylor correction of Lind et al. is left out: the shift
// is O(A h |v| dt / h) of a spacing per step).
//
// Free surfaces: a particle whose kernel sum sum_j V_j W_ij is below 0.9 (a
// truncated support: a free surface within about a support) is not shifted;
// Lind's projection of the shift onto the surface is not implemented. Use
// shifting for internal flows (periodic boxes, channels); near a free
// surface it does nothing. apply() is compiled for D = 2 and 3 in
// src/particle_shifting.cpp (the scene includes this file: the pair loop's
// walk stays out of its includers).
#pragma once

#include "sph/mpi/collectives.hpp"

#include "sph/kernels/kernels.hpp"
#include "sph/particles.hpp"

#include <vector>

namespace sph {

template <int D>
class NeighbourList;  // neighbour_list.hpp

template <int D>
class ParticleShifting {
 public:
  ParticleShifting(const Kernel<D>& kernel, Real coefficient, Real spacing, Real restDensity)
      : kernel_(kernel), coefficient_(coefficient), spacing_(spacing), rho0_(restDensity) {}

  // x_i += dr_i for the fluid particles; `neighbours` built on these
  // positions. dr is formed for every particle before any moves. sumsGiven:
  // the particles hold the sums of grad C at this state (shiftSum,
  // shiftGrad, left by the force pass: terms/shifting_sums.hpp), so the
  // neighbours are not walked again; else the shift takes them itself.
  void apply(Particles<D>& P, const NeighbourList<D>& neighbours, Real dt, bool sumsGiven = false) const;

  Real coefficient() const { return coefficient_; }
  // The ranks whose fluid U is the largest speed of (scene.hpp).
  void setCommunicator(const mpi::Communicator& comm) { comm_ = comm; }

 private:
  Kernel<D> kernel_;
  Real coefficient_, spacing_, rho0_;
  mpi::Communicator comm_;
  mutable std::vector<Vec<D>> shift_;  // scratch, reused: no allocation after the first step
};

}  // namespace sph
