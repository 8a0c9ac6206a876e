// How far two pair loops that add the same terms in different orders may
// differ (the SIMD rows of pair_loop_blocks.hpp against the scalar loop).
// Recursive or pairwise summation of n terms t_j in floating point is within
// gamma_{n-1} sum_j |t_j| of the exact sum, gamma_k = k eps / (1 - k eps)
// (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., 2002,
// eqs. 4.4 and 4.6, for any order); two orders are then within twice that,
// and a term formed with another association of its products (the force
// rows add (m_j P_ij + m_j Pi_ij) grad W instead of each apart) adds a few
// eps |t_j| more. The bound used: 4 n eps sum_j |t_j|, n the particle's
// listed neighbours. sum_j |t_j| comes from the scalar loop itself, with
// each evaluator wrapped in MagnitudeOf.
#pragma once

#include "sph/pair_loop.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <tuple>

namespace sph::test {

// An evaluator that adds the absolute value of what `Term` adds, per
// component: a scalar loop of these gives sum_j |t_j| per particle.
template <class Term>
struct MagnitudeOf {
  static constexpr unsigned writes = Term::writes;
  Term term;

  unsigned bits() const { return packBits(std::make_tuple(term)); }

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    PairRates<D> one;
    term.add(c, P, one);
    r.a += one.a.cwiseAbs();
    r.drho += std::abs(one.drho);
  }
};

template <class... T>
std::tuple<MagnitudeOf<T>...> magnitudesOf(const std::tuple<T...>& pack) {
  return std::apply([](const T&... t) { return std::make_tuple(MagnitudeOf<T>{t}...); }, pack);
}

// The bound 4 n eps sum_j |t_j| on how far two orders of the sum of n terms
// may be apart.
inline Real reorderedSumBound(std::size_t n, Real sumOfMagnitudes) {
  return 4.0 * static_cast<Real>(n) * std::numeric_limits<Real>::epsilon() * sumOfMagnitudes;
}

}  // namespace sph::test
