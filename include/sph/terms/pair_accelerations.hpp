// The pair loop shared by all force terms (HOOMD-style evaluators).
//
//   a_i = (1 / rho_i) sum_{j in neighbours(i)} sum_{F-terms} F(i, j)
//         +           sum_{j in neighbours(i)} sum_{a-terms} a(i, j)
//         + sum_{body terms} a_body(i)
//
// A pair term is a small value type with
//   static constexpr bool isForceDensity;   // true: returns F (the seed's form)
//   Vec<D> pair(const PairContext<D>&, const Particles<D>&) const;
// a body term has
//   Vec<D> acceleration(std::size_t i, const Particles<D>&) const.
// The term lists are template parameter packs, so the compiler inlines every
// term into one neighbour loop: no per-pair virtual call, no runtime switch,
// and a term that a case does not enable is not in the pack at all.
// Gather form: i writes only a_i (thread-count independent, no atomics).
#pragma once

#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"

#include <cmath>
#include <tuple>

namespace sph {

// One interacting pair, seen from particle i. Convention: rij = x_i - x_j.
template <int D>
struct PairContext {
  std::uint32_t i, j;
  Vec<D> rij;
  Real r;  // |rij|
  Real q;  // r / support
};

template <class Tuple>
struct HasForceDensityTerm;
template <class... T>
struct HasForceDensityTerm<std::tuple<T...>> {
  static constexpr bool value = (T::isForceDensity || ... || false);
};

template <class Tuple>
struct TermBitsOf;
template <class... T>
struct TermBitsOf<std::tuple<T...>> {
  static constexpr unsigned value = (T::bit | ... | 0u);
};

// Returns the bits of the terms it ran (term_bits.hpp).
template <int D, class PairTerms, class BodyTerms>
unsigned computeAccelerations(Particles<D>& P, const NeighbourList<D>& neighbours, Real support,
                          const PairTerms& pairTerms, const BodyTerms& bodyTerms) {
  const std::size_t n = P.size();
  const Real invSupport = 1 / support;
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
  for (std::size_t i = 0; i < n; ++i) {
    Vec<D> F = Vec<D>::Zero(), A = Vec<D>::Zero();
    const Vec<D> xi = P.x[i];
    neighbours.forEach(i, [&](std::uint32_t j) {
      const Vec<D> rij = xi - P.x[j];
      const Real r = rij.norm();
      const PairContext<D> c{static_cast<std::uint32_t>(i), j, rij, r, r * invSupport};
      std::apply(
          [&](const auto&... t) {
            (
                [&](const auto& term) {
                  if constexpr (std::decay_t<decltype(term)>::isForceDensity) {
                    F += term.pair(c, P);
                  } else {
                    A += term.pair(c, P);
                  }
                }(t),
                ...);
          },
          pairTerms);
    });
    Vec<D> a = A;
    if constexpr (HasForceDensityTerm<PairTerms>::value) a += F / P.rho[i];
    std::apply([&](const auto&... t) { ((a += t.acceleration(i, P)), ...); }, bodyTerms);
    P.a[i] = a;
  }
  return TermBitsOf<PairTerms>::value | TermBitsOf<BodyTerms>::value;
}

}  // namespace sph
