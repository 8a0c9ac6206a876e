// The sums of particle shifting (particle_shifting.hpp), taken in the force
// pass's pair loop instead of a walk of their own at the next step's start:
//
//   sum_i    = sum_j V_j W_ij                 (+ V_i W(0), added by the epilogue)
//   grad C_i = sum_j V_j [1 + R (W_ij / W(dx))^n] grad_i W_ij,   R = 0.2, n = 4,
//   V_j = m_j / rho_j (wall particles: m_j / rho0, their lattice volume)
//
// (Lind, Xu, Stansby & Rogers 2012, J. Comput. Phys. 231, 1499.) The force
// pass's last evaluation of a step is at the state the shift acts on (x and
// rho at the step's end), with the same neighbour list, so the sums are
// those the shift's own walk would take, pair for pair and in the same
// order, with the same addShiftingPair() (bit for bit: the shifting
// variants of tests/test_run_folder.cpp's resume test, whose first shift
// walks); the scene uses them unless something changed the state since (a
// density re-initialisation, a resume: then the shift walks the neighbours
// itself). Coincident particles (r = 0) are left out, as the walk does.
// Off: one predictable branch per pair.
#pragma once

#include "sph/pair_loop.hpp"

namespace sph {

// Neighbour j's part of the two sums: V_j W_ij and V_j [1 + R (W_ij /
// W(dx))^n] grad_i W_ij (R = 0.2, n = 4). The shift's own walk
// (src/particle_shifting.cpp) adds the same.
template <int D>
[[gnu::always_inline]] inline void addShiftingPair(Real Vj, Real w, Real invWdx, const Vec<D>& gradW, Real& sum,
                                                   Vec<D>& grad) {
  const Real q = w * invWdx, q2 = q * q;
  sum += Vj * w;
  grad += (Vj * (1 + 0.2 * q2 * q2)) * gradW;
}

template <class Kernel, bool kWall = false>
struct ShiftingSums {
  static constexpr unsigned writes = rates::kShifting;
  static constexpr unsigned bit = 0;  // a scene pass's sums, not a term of the model
  Kernel kernel;
  Real invWdx = 0;  // 1 / W(dx)
  Real rho0 = 0;    // the walls' volume m / rho0
  bool on = false;

  bool active() const { return on; }

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    if (!on || !(c.r > 0)) return;
    const Real Vj = kWall ? P.m[c.j] / rho0 : P.m[c.j] / P.rho[c.j];
    addShiftingPair<D>(Vj, kernel.W(c.r), invWdx, c.gradW, r.shiftSum, r.shiftGrad);
  }
};

}  // namespace sph
