// The optional terms of model wcsph, listed once. Each is declared in its
// own file (terms/*.hpp) as a value type T with
//   static constexpr const char* name;   // its name in the model's term list (run.json)
//   static constexpr unsigned bit;       // optional: term_bits.hpp (else the list gives one)
//   static constexpr bool kPerPair;      // a pair term, or a per-particle one
//   static std::vector<KeySpec> keys();  // its case keys (termKey rows, case_keys.hpp;
//                                        // the key table lists them after xsph)
//   static T fromCase(const CaseConfig&);                 // the term of a validated case
//   static void validate(const CaseConfig&);              // throws CaseError
//   template <class Note> static void noteUnused(const CaseConfig&, Note&&);  // keys nothing reads
//   bool active() const;                 // off: never listed, one predictable branch per
//                                        // pair or particle, no second instantiation of the loop
//   FieldSet reads() const;              // fields it reads (fields.hpp), beyond x, m, rho, p
// and, for a pair term, template <class K> E pairEvaluator(const K&) const,
// E an evaluator of pair_loop.hpp (writes, active(), add(); bit optional)
// placed after the pressure term in the force pass's fluid-fluid pack; if
// it writes the density rate only (rates::kDensityRate, with continuity
// density), it is also in the density-rate pass that the leap-frog and
// symplectic Euler integrators run apart (passes/density_rate.hpp, after
// the diffusion, the order it has in the force pass), and in the force pass
// it is switched off when that pass computes the rate. For a per-particle
// term, template <int D> Vec<D> acceleration(i, P) const, added in the
// force pass's epilogue after the body forces.
// The key table (case_keys.cpp), the case checks (case_config.cpp), the
// model (model_registry.hpp, models/wcsph.hpp) and the passes iterate this
// list at compile time: a term is its file, and its #include and its entry
// here.
#pragma once

#include "sph/terms/artificial_pressure.hpp"
#include "sph/terms/linear_damping.hpp"

#include "sph/kernels/kernels.hpp"

#include <tuple>
#include <type_traits>
#include <utility>

namespace sph {

// THE list: the order is the order of their keys in the key table, and,
// among the terms of a kind, of their contributions.
using OptionalTerms = std::tuple<LinearDamping, ArtificialPressure>;

static_assert(std::tuple_size_v<OptionalTerms> <= 8, "term_bits.hpp has room for 8 listed terms");

template <class T>
struct TermTag {
  using type = T;
};

// The bit of optional term T: its own, or kFirstListedTerm << its index.
template <class T, class = void>
struct DeclaresBit : std::false_type {};
template <class T>
struct DeclaresBit<T, std::void_t<decltype(T::bit)>> : std::true_type {};
template <class T, class... U>
constexpr unsigned listIndex(const std::tuple<U...>*) {
  constexpr bool same[] = {std::is_same_v<T, U>...};
  unsigned i = 0;
  while (!same[i]) ++i;
  return i;
}
template <class T>
constexpr unsigned termBit() {
  if constexpr (DeclaresBit<T>::value) return T::bit;
  else return term_bits::kFirstListedTerm << listIndex<T>(static_cast<const OptionalTerms*>(nullptr));
}

// An evaluator with the bit of its term (when the evaluator names none).
template <class E, unsigned Bit>
struct ListedEvaluator : E {
  static constexpr unsigned bit = Bit;
};
// A density-rate-only evaluator in the force pass: off when the rate is
// computed apart (one predictable branch per pair).
template <class E>
struct RateHereEvaluator : E {
  bool here = true;
  bool active() const { return here && E::active(); }
  template <int D>
  [[gnu::always_inline]] void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    if (here) E::add(c, P, r);
  }
};
template <class T, class Kernel>
auto listedEvaluator(const T& t, const Kernel& k) {
  using E = decltype(t.pairEvaluator(k));
  if constexpr (DeclaresBit<E>::value) return t.pairEvaluator(k);
  else return ListedEvaluator<E, termBit<T>()>{t.pairEvaluator(k)};
}
template <class E>
constexpr bool kRateOnly = E::writes == rates::kDensityRate;
// Whether term t is a pair term that writes the density rate only (its
// evaluator's `writes` does not depend on the kernel).
template <class T>
constexpr bool rateOnlyTerm(const T&) {
  if constexpr (!T::kPerPair) return false;
  else return kRateOnly<decltype(std::declval<const T&>().pairEvaluator(std::declval<const WendlandC2<2>&>()))>;
}

// f(TermTag<T>{}) for each optional term T, in list order.
template <class F>
void forEachOptionalTerm(F&& f) {
  std::apply([&](const auto&... t) { (f(TermTag<std::decay_t<decltype(t)>>{}), ...); }, OptionalTerms{});
}

// The terms of a validated case.
inline OptionalTerms optionalTermsOf(const CaseConfig& c) {
  return std::apply([&](const auto&... t) { return OptionalTerms{std::decay_t<decltype(t)>::fromCase(c)...}; },
                    OptionalTerms{});
}

// The pair evaluators of the pair terms for kernel k, for the force pass
// (`rateHere`: it computes the density rate; the per-particle terms give
// none).
template <class Kernel, class T>
auto forcePairEvaluatorOf(const T& t, const Kernel& k, bool rateHere) {
  if constexpr (!T::kPerPair) {
    return std::tuple<>{};
  } else {
    auto e = listedEvaluator(t, k);
    if constexpr (kRateOnly<decltype(e)>) return std::make_tuple(RateHereEvaluator<decltype(e)>{e, rateHere});
    else return std::make_tuple(e);
  }
}
template <class Kernel>
auto pairTermEvaluators(const OptionalTerms& terms, const Kernel& k, bool rateHere) {
  return std::apply([&](const auto&... t) { return std::tuple_cat(forcePairEvaluatorOf(t, k, rateHere)...); },
                    terms);
}
// ... and the density-rate-only ones, for the density-rate pass.
template <class Kernel, class T>
auto ratePairEvaluatorOf(const T& t, const Kernel& k) {
  if constexpr (!T::kPerPair) {
    return std::tuple<>{};
  } else {
    auto e = listedEvaluator(t, k);
    if constexpr (kRateOnly<decltype(e)>) return std::make_tuple(e);
    else return std::tuple<>{};
  }
}
template <class Kernel>
auto densityRateTermEvaluators(const OptionalTerms& terms, const Kernel& k) {
  return std::apply([&](const auto&... t) { return std::tuple_cat(ratePairEvaluatorOf(t, k)...); }, terms);
}


// The per-particle terms as a force epilogue's extra acceleration
// (passes/seed_forces.hpp): each active one added in list order.
template <int D>
struct ParticleTermForces {
  const OptionalTerms& terms;
  [[gnu::always_inline]] void add(std::size_t i, const Particles<D>& P, Vec<D>& a) const {
    std::apply([&](const auto&... t) { (addOne(t, i, P, a), ...); }, terms);
  }
  template <class T>
  [[gnu::always_inline]] static void addOne(const T& t, std::size_t i, const Particles<D>& P, Vec<D>& a) {
    if constexpr (!T::kPerPair)
      if (t.active()) a += t.template acceleration<D>(i, P);
  }
};

// The bits of the active per-particle terms (the pair terms' come from the
// pair loop's packs), the fields the active terms read, and their names.
inline unsigned particleTermBits(const OptionalTerms& terms) {
  unsigned bits = 0;
  std::apply(
      [&](const auto&... t) {
        ((bits |= (!std::decay_t<decltype(t)>::kPerPair && t.active()) ? termBit<std::decay_t<decltype(t)>>() : 0u),
         ...);
      },
      terms);
  return bits;
}
inline FieldSet optionalTermReads(const OptionalTerms& terms) {
  FieldSet reads = 0;
  std::apply([&](const auto&... t) { ((reads |= t.active() ? t.reads() : 0u), ...); }, terms);
  return reads;
}
// ... the fields the active density-rate-only terms read.
inline FieldSet rateTermReads(const OptionalTerms& terms) {
  FieldSet reads = 0;
  std::apply([&](const auto&... t) { ((reads |= rateOnlyTerm(t) && t.active() ? t.reads() : 0u), ...); }, terms);
  return reads;
}
// Whether an active optional term writes the density rate only.
inline bool anyRateTermActive(const OptionalTerms& terms) {
  bool any = false;
  std::apply([&](const auto&... t) { ((any = any || (rateOnlyTerm(t) && t.active())), ...); }, terms);
  return any;
}
// Whether an active optional term is a pair term.
inline bool anyPairTermActive(const OptionalTerms& terms) {
  bool any = false;
  std::apply([&](const auto&... t) { ((any = any || (std::decay_t<decltype(t)>::kPerPair && t.active())), ...); },
             terms);
  return any;
}
template <class F>
void forEachActiveTermName(const OptionalTerms& terms, F&& f) {
  std::apply([&](const auto&... t) { ((t.active() ? f(t.name) : void()), ...); }, terms);
}

// The case checks of every term (validateCase), and the keys nothing reads.
inline void validateOptionalTerms(const CaseConfig& c) {
  forEachOptionalTerm([&](auto tag) { decltype(tag)::type::validate(c); });
}
template <class Note>
void noteUnusedTermKeys(const CaseConfig& c, Note&& note) {
  forEachOptionalTerm([&](auto tag) { decltype(tag)::type::noteUnused(c, note); });
}

}  // namespace sph
