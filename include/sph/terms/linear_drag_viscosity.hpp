// Scratch (registry demonstration): a pair drag a_i = -zeta sum_j V_j W_ij (v_i - v_j).
#pragma once

#include "sph/pair_loop.hpp"
#include "sph/terms/term_bits.hpp"

namespace sph {

template <class Kernel, bool kWall = false>
struct LinearDragViscosity {
  static constexpr unsigned bit = term_bits::kLinearDragViscosity;
  static constexpr unsigned writes = rates::kAcceleration;
  Kernel kernel;
  Real zeta;

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    const Vec<D>& vj = kWall ? P.vWall[c.j] : P.v[c.j];
    r.a -= zeta * P.m[c.j] / P.rho[c.j] * c.w * (P.v[c.i] - vj);
  }
};

}  // namespace sph
