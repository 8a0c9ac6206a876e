// The neighbour-walk driver: the one loop of the passes that visit each
// particle's neighbours outside the fused pair loop (pair_loop.hpp, which
// has its own). walkNeighbours() runs one parallel loop over a particle
// range (the fluid, the walls, or every owned particle), resolves the
// kernel (and any other run-time choice, such as the EOS) once per walk,
// not per particle, and hands each particle i its row: its neighbours in
// the list's order, fluid then wall, each with r_ij = x_i - x_j
// (forEachNeighbourSeparation, pair_loop.hpp: r_ij has one definition).
// What the pass does with them (its sums, in its own order) stays in the
// pass; the driver adds no arithmetic, so a pass moved onto it gives the
// same numbers, bit for bit.
//
// Users: the Adami wall extrapolation (boundaries/dummy_adami2012.hpp),
// the repulsive walls (src/wall_passes.cpp), the CSPM moments
// (passes/cspm_correction.hpp), the Shepard and MLS re-initialisations
// (passes/shepard_density.hpp, mls_density.hpp), the summation density
// (terms/summation_density.hpp) and the regime check (regime_check.hpp).
// Not yet: the colour field (terms/colour_surface_tension.hpp: three loops
// in one parallel region) and the particle shifting
// (src/particle_shifting.cpp).
//
// (Not the case key neighbour_walk, which chooses how the list yields a
// row, stored or scanned from the cells: the driver serves both alike.)
//
// Gather form: particle i writes only its own values, so there are no
// atomics and the results do not depend on the thread count. A walk that
// also counts (fallbacks, the regime check's maxima and sums) names a Sums
// type: each thread adds into its own, and the driver merges them
// (Sums += Sums) into the value it returns; counts and maxima, whose merge
// is exact in any order.
#pragma once

#include "sph/neighbour_list.hpp"
#include "sph/pair_loop.hpp"
#include "sph/particles.hpp"

#include <cstdint>
#include <tuple>
#include <type_traits>
#include <variant>

namespace sph {

// Particle i's neighbours, each as f(j, r_ij), r_ij = x_i - x_j.
template <int D>
class NeighbourRow {
 public:
  NeighbourRow(const Particles<D>& P, const NeighbourList<D>& neighbours, std::size_t i)
      : P_(P), neighbours_(neighbours), i_(i) {}

  std::size_t index() const { return i_; }

  // Every neighbour: the fluid ones, then the wall ones.
  template <class F>
  [[gnu::always_inline]] void forEach(F&& f) const {
    forEachNeighbourSeparation(P_, neighbours_, i_, f);
  }
  // f for the fluid neighbours, then g for the wall ones.
  template <class F, class G>
  [[gnu::always_inline]] void forEachByKind(F&& f, G&& g) const {
    forEachNeighbourSeparationByKind(P_, neighbours_, i_, f, g);
  }
  template <class F>
  [[gnu::always_inline]] void forEachFluid(F&& f) const {
    forEachByKind(f, [](std::uint32_t, const Vec<D>&) {});
  }
  template <class F>
  [[gnu::always_inline]] void forEachWall(F&& f) const {
    forEachByKind([](std::uint32_t, const Vec<D>&) {}, f);
  }
  // The neighbours of a sum: the fluid ones, then the wall ones when the
  // walls are in the sums (WallSums::inSums).
  template <class F>
  [[gnu::always_inline]] void forEachSummed(bool walls, F&& f) const {
    if (walls) forEach(f);
    else forEachFluid(f);
  }

 private:
  const Particles<D>& P_;
  const NeighbourList<D>& neighbours_;
  std::size_t i_;
};

// A walk that counts nothing.
struct NoSums {
  void operator+=(const NoSums&) {}
};

namespace walk_detail {

// A std::variant, or a type derived from one (EquationOfState).
template <class... T>
std::true_type variantBase(const std::variant<T...>*);
std::false_type variantBase(const void*);
template <class T>
using IsVariant = decltype(variantBase(static_cast<const T*>(nullptr)));
template <class T>
struct IsTuple : std::false_type {};
template <class... T>
struct IsTuple<std::tuple<T...>> : std::true_type {};

// f(c...) with each variant among the choices replaced by its alternative.
template <class F>
void resolve(F&& f) {
  f();
}
template <class F, class First, class... Rest>
void resolve(F&& f, const First& first, const Rest&... rest) {
  auto next = [&](const auto& chosen) { resolve([&](const auto&... r) { f(chosen, r...); }, rest...); };
  if constexpr (IsVariant<First>::value) std::visit(next, first);
  else next(first);
}

}  // namespace walk_detail

// One parallel loop over the particles of `over` (a range of the
// particles' table: P.range(ParticleRange::kFluid), ...):
//   f(i, row, choice...)          (Sums = NoSums)
//   f(i, row, sums, choice...)    (otherwise: this thread's Sums; returned merged)
// `choices`: a kernel, an EOS, ... or a std::tuple of them (std::tie);
// each that is a std::variant is resolved once, here, and f gets the
// alternative. Without choices: walkNeighbours(P, neighbours, over, f).
template <class Sums = NoSums, int D, class Choices, class F>
Sums walkNeighbours(const Particles<D>& P, const NeighbourList<D>& neighbours, IndexRange over,
                    const Choices& choices, F&& f) {
  const std::size_t begin = over.begin, end = over.end;
  Sums total{};
  auto loop = [&](const auto&... chosen) {
    // flatten: the pass's body and its walk in the loop itself, as when
    // each pass wrote its loop out. The body is the thread's own copy (a
    // closure of references: a few pointers), which the calls in it (pow)
    // cannot change, so they are not loaded again per particle.
    auto particle = [&P, &neighbours, &chosen...](auto& body, std::size_t i, Sums& mine)
                        __attribute__((flatten)) {
                          const NeighbourRow<D> row(P, neighbours, i);
                          if constexpr (std::is_same_v<Sums, NoSums>) body(i, row, chosen...);
                          else body(i, row, mine, chosen...);
                        };
#pragma omp parallel if (end - begin >= kMinParallelSize)
    {
      std::decay_t<F> body(f);
      auto each = particle;
      Sums mine{};
#pragma omp for schedule(static) nowait
      for (std::size_t i = begin; i < end; ++i) each(body, i, mine);
      if constexpr (!std::is_same_v<Sums, NoSums>) {
#pragma omp critical(sph_neighbour_walk_sums)
        total += mine;
      }
    }
  };
  if constexpr (walk_detail::IsTuple<Choices>::value)
    std::apply([&](const auto&... c) { walk_detail::resolve(loop, c...); }, choices);
  else walk_detail::resolve(loop, choices);
  return total;
}

template <class Sums = NoSums, int D, class F>
Sums walkNeighbours(const Particles<D>& P, const NeighbourList<D>& neighbours, IndexRange over, F&& f) {
  return walkNeighbours<Sums>(P, neighbours, over, std::tuple<>{}, f);
}

}  // namespace sph
