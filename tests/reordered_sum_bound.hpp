// How far two pair loops that add the same terms in different orders may
// differ (the SIMD rows of pair_loop_blocks.hpp against the scalar loop).
// Summation of k terms t_j in floating point, in any order (recursive or
// pairwise), is within gamma_{k-1} sum_j |t_j| of the exact sum,
// gamma_k = k u / (1 - k u), u = eps/2 the unit round-off (Higham, Accuracy
// and Stability of Numerical Algorithms, 2nd ed., 2002, eqs. 4.4 and 4.6).
// A row of n pairs sums up to k = 2n terms (continuity and diffusion, or
// pressure and viscosity, per pair), so two orders are within
// 2 gamma_{2n-1} ~ (2n - 1) eps of sum_j |t_j|; the force rows' one product
// (m_j P_ij + m_j Pi_ij) grad W where the scalar loop takes two adds about
// 2 u |t_j| per pair, at most n eps more. The bound used, 4 n eps
// sum_j |t_j| (n the particle's listed neighbours), leaves a margin of
// about 2. It holds only if each term is formed with the same operations
// (the build's -ffp-contract=off). sum_j |t_j| comes from the scalar loop
// itself, with each evaluator wrapped in MagnitudeOf.
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
  static_assert((Term::writes & ~(rates::kAcceleration | rates::kDensityRate | rates::kXsph)) == 0,
                "MagnitudeOf sums the acceleration, the density rate and the XSPH sum only");
  Term term;

  unsigned bits() const { return packBits(std::make_tuple(term)); }

  template <int D>
  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    PairRates<D> one;
    term.add(c, P, one);
    r.a += one.a.cwiseAbs();
    r.drho += std::abs(one.drho);
    r.xsph += one.xsph.cwiseAbs();
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
