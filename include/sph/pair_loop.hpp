// The one pair loop (HOOMD-style evaluators, fused as in DualSPHysics'
// fluid loop): the only place that forms r_ij, r, q and grad W for a pair
// (but for the SIMD blocks of pair_loop_blocks.hpp, whose row functions,
// passes/density_rate_blocks.hpp and passes/force_blocks.hpp, repeat these
// operations lane by lane and add the pairs in another order: tests hold
// their rates to this loop's within a bound on that reordering).
//
// For every fluid particle i it visits the fluid neighbours with the
// evaluators of `FluidPairs` and the wall neighbours with those of
// `WallPairs`; the evaluators add into one PairRates (acceleration, force
// density, density rate, XSPH correction), and the epilogue turns the sums
// into the particle's rates (body forces added there). Wall particles then
// get their own rates from their fluid neighbours with `WallParticlePairs`
// (e.g. the density rate of dynamic boundary particles). Both loops share
// one parallel region.
//
// An evaluator is a small value type with
//   static constexpr unsigned bit;      // term_bits.hpp: which pass it is
//   static constexpr unsigned writes;   // which PairRates members it adds to
//   template <int D> void add(const Pair<D>&, const Particles<D>&, PairRates<D>&) const;
// The packs are std::tuples, so the compiler inlines every evaluator into
// the loop: no per-pair virtual call or runtime switch, and an evaluator
// that a case does not enable is not in the pack.
// Gather form: particle i writes only its own rates (no atomics, results
// independent of the thread count).
// A gradient correction gives the pair its corrected gradient
// gradWC = L_i grad_i W (GradientCorrection with the CSPM matrices of
// passes/cspm_correction.hpp), used by the pressure term; without one
// (NoGradientCorrection, or GradientCorrection with no matrices) gradWC is
// grad W itself.
//
// A neighbour list with a Verlet skin (scene.hpp) also holds pairs a little
// beyond the support: the loop skips them (r^2 >= support^2, the test the
// list's build makes), so they cost a distance, not the kernel and the
// evaluators. Every kernel's W and grad W are 0 there too, so the other
// walks (forEachNeighbourSeparation) get exact zeros from them.
//
// r_ij is always x_i - x_j: along periodic axes a neighbour across a face
// is a ghost particle, a copy of it shifted by the box length
// (periodic_ghosts.hpp), so no pair needs a minimum image. The loop runs
// over owned particles only (fluid, then walls); ghosts are read as
// neighbours. The other passes that need r_ij (summation density, the wall
// extrapolation, repulsive walls) take it from forEachNeighbourSeparation()
// below, so r_ij has one definition.
#pragma once

#include "sph/neighbour_list.hpp"
#include "sph/pair_scratch.hpp"
#include "sph/particles.hpp"
#include "sph/terms/term_bits.hpp"

#include <tuple>
#include <type_traits>
#include <vector>

namespace sph {

// Which members of PairRates an evaluator adds to.
namespace rates {
enum : unsigned { kAcceleration = 1, kForceDensity = 2, kDensityRate = 4, kXsph = 8, kShifting = 16 };
}

// One interacting pair seen from particle i. Convention: rij = x_i - x_j.
template <int D>
struct Pair {
  std::uint32_t i, j;
  Vec<D> rij;
  Real r;        // |rij|
  Real q;        // r / support
  Real dWdr_r;   // (dW/dr) / r, so that grad_i W = dWdr_r rij (0 without a kernel)
  Vec<D> gradW;  // grad_i W(r_ij)
  Vec<D> gradWC; // corrected grad_i W (the pressure term); = gradW without a correction
};

// No gradient correction: gradWC = gradW.
struct NoGradientCorrection {
  template <int D>
  const Vec<D>& operator()(std::uint32_t, const Vec<D>& gradW) const { return gradW; }
};

// A gradient correction chosen at run time: gradWC = L_i grad W when the
// case has the matrices L (CSPM, passes/cspm_correction.hpp), grad W itself
// when L is null. The branch is the same for every pair of a loop, so it
// costs next to nothing, and the force loop is compiled once for both.
template <int D>
struct GradientCorrection {
  const Mat<D>* L = nullptr;
  Vec<D> operator()(std::uint32_t i, const Vec<D>& gradW) const {
    if (L) return L[i] * gradW;
    return gradW;
  }
};

template <int D>
struct PairRates {
  Vec<D> a = Vec<D>::Zero();     // acceleration
  Vec<D> F = Vec<D>::Zero();     // force per volume, divided by rho_i in the epilogue
  Real drho = 0;                 // d rho_i / dt
  Vec<D> xsph = Vec<D>::Zero();  // XSPH velocity correction, before its epsilon
  Real shiftSum = 0;                  // particle shifting's kernel sum (terms/shifting_sums.hpp)
  Vec<D> shiftGrad = Vec<D>::Zero();  // ... and concentration gradient
};

// The pair loop of a model with no kernel of this form (the seed scheme: its
// terms evaluate their own factors from q).
struct NoPairKernel {};

template <class Tuple>
struct PackTraits;
template <class... T>
struct PackTraits<std::tuple<T...>> {
  static constexpr unsigned writes = (T::writes | ... | 0u);
};

// The bit of an evaluator that ran: its `bit`, unless it is switched off at
// run time (an evaluator with active() == false), or the bits() it names at
// run time (one evaluator that stands for two passes).
template <class T, class = void>
struct HasActive : std::false_type {};
template <class T>
struct HasActive<T, std::void_t<decltype(std::declval<const T&>().active())>> : std::true_type {};
template <class T, class = void>
struct HasBits : std::false_type {};
template <class T>
struct HasBits<T, std::void_t<decltype(std::declval<const T&>().bits())>> : std::true_type {};

template <class Pack>
unsigned packBits(const Pack& pack) {
  auto one = [](const auto& e) -> unsigned {
    using T = std::decay_t<decltype(e)>;
    if constexpr (HasBits<T>::value) return e.bits();
    else if constexpr (HasActive<T>::value) return e.active() ? T::bit : 0u;
    else return T::bit;
  };
  return std::apply([&](const auto&... t) { return (one(t) | ... | 0u); }, pack);
}

// Every evaluator of the pack inlined into the loop (flatten: the compiler
// left DensityDiffusion::add out of line in the force loop: inlining it
// cut a water step's instructions by about 10%).
template <class Pack, int D>
[[gnu::always_inline, gnu::flatten]] inline void addPair(const Pack& pack, const Pair<D>& c, const Particles<D>& P,
                                                         PairRates<D>& r) {
  std::apply([&](const auto&... t) { (t.add(c, P, r), ...); }, pack);
}

// Fill in r_ij = x_i - x_j, r, q and the kernel terms of the pair (i, j).
// `correct` gives the corrected gradient gradWC.
template <int D, class Kernel, class Correction = NoGradientCorrection>
[[gnu::always_inline]] inline Pair<D> makePair(std::uint32_t i, std::uint32_t j, const Vec<D>& xi, const Vec<D>& xj,
                        const Kernel& kernel, Real invSupport, const Correction& correct = {}) {
  Pair<D> c;
  c.i = i;
  c.j = j;
  c.rij = xi - xj;
  c.r = c.rij.norm();
  c.q = c.r * invSupport;
  if constexpr (!std::is_same_v<Kernel, NoPairKernel>) {
    // At r = 0 (coincident particles) rij is the zero vector, so grad W is
    // 0, and dW/dr / r takes its limit (radial_gradient.hpp), so that
    // Laplacian-type terms stay finite.
    c.dWdr_r = kernel.dWdr_r(c.r);
    c.gradW = c.dWdr_r * c.rij;
    c.gradWC = correct(i, c.gradW);
  } else {
    c.dWdr_r = 0;
    c.gradW = Vec<D>::Zero();
    c.gradWC = c.gradW;
  }
  return c;
}

// Which parts of the loop run, decided per evaluation.
struct PairLoopParts {
  bool wallPairs = true;       // fluid particles see their wall neighbours
  bool wallParticles = false;  // wall particles get rates of their own
};

// No per-particle values before the pairs.
struct NoPrologue {};

// No row function: the fluid-fluid pairs go one at a time through the pack.
struct PairByPair {};

// A row function called as a function of its own, once per particle: the
// row loop's `flatten` would otherwise inline it into the pair-by-pair
// machinery around it (measured 4% slower on the dam break).
template <int D, class FluidRow>
[[gnu::noinline]] void runFluidRow(const FluidRow& fluidRow, std::uint32_t i, const std::uint32_t* begin,
                                   const std::uint32_t* end, PairRates<D>& r) {
  fluidRow(i, begin, end, r);
}

// Returns the term bits of the packs it ran.
//   prologue(i, P)              per-particle values for the pairs (every
//                               particle, ghosts included), before any pair
//   epilogue(i, P, rates)       writes particle i's rates (fluid particles)
//   wallEpilogue(i, P, rates)   the same for wall particles
// `correct` corrects the gradients of the fluid particles' pairs (wall
// particles' own rates use grad W as it is).
//   fluidRow(i, begin, end, rates)  optional: adds the fluid-fluid pairs of
//                               fluid particle i, its neighbours [begin, end),
//                               in place of `fluidPairs` (SIMD blocks that
//                               repeat the pack's operations lane by lane:
//                               pair_loop_blocks.hpp); the pack still names
//                               the bits
//   wallRow(i, begin, end, rates)   optional, with a fluidRow: the same for
//                               the fluid particle's wall neighbours, in
//                               place of `wallPairs`
template <int D, class Kernel, class FluidPairs, class WallPairs, class WallParticlePairs, class Epilogue,
          class WallEpilogue, class Correction = NoGradientCorrection, class Prologue = NoPrologue,
          class FluidRow = PairByPair, class WallRow = PairByPair>
unsigned runPairLoop(Particles<D>& P, const NeighbourList<D>& neighbours, const Kernel& kernel, Real support,
                     const FluidPairs& fluidPairs, const WallPairs& wallPairs,
                     const WallParticlePairs& wallParticlePairs, const Epilogue& epilogue,
                     const WallEpilogue& wallEpilogue, PairLoopParts parts = {}, const Correction& correct = {},
                     const Prologue& prologue = {}, const FluidRow& fluidRow = {}, const WallRow& wallRow = {}) {
  const std::size_t n = P.size(), nFluid = P.fluidCount();
  const Real invSupport = 1 / support, support2 = support * support;
  const bool wallParticles = std::tuple_size_v<WallParticlePairs> > 0 && parts.wallParticles && P.hasWalls();
  const bool walls = P.hasWalls() && parts.wallPairs;
  // A pair in the list's skin. (Never for the seed scheme, NoPairKernel,
  // which keeps skin 0: its loop has no test.)
  auto beyond = [support2](const Vec<D>& xi, const Vec<D>& xj) {
    if constexpr (std::is_same_v<Kernel, NoPairKernel>) return false;
    else return !(Vec<D>(xi - xj).squaredNorm() < support2);
  };
#pragma omp parallel if (n >= kMinParallelSize)
  {
    if constexpr (!std::is_same_v<Prologue, NoPrologue>) {
      if (prologue.active()) {
        const std::size_t total = P.totalSize();
#pragma omp for schedule(static)
        for (std::size_t i = 0; i < total; ++i) prologue(i, P);
      }
    }
    // flatten: the whole row (the list's walk, the pair, every evaluator,
    // the epilogue) in one function, so the particle's sums stay in
    // registers (an evaluator left out of line takes them by reference,
    // in memory: a store and a load per pair and rate).
    auto fluidParticle = [&](std::size_t i, auto byKind) __attribute__((flatten)) {
      PairRates<D> r;
      const Vec<D> xi = P.x[i];
      const auto ii = static_cast<std::uint32_t>(i);
      auto fluid = [&](std::uint32_t j) {
        if (beyond(xi, P.x[j])) return;
        addPair(fluidPairs, makePair(ii, j, xi, P.x[j], kernel, invSupport, correct), P, r);
      };
      auto wall = [&](std::uint32_t j) {
        if (beyond(xi, P.x[j])) return;
        addPair(wallPairs, makePair(ii, j, xi, P.x[j], kernel, invSupport, correct), P, r);
      };
      if constexpr (!std::is_same_v<FluidRow, PairByPair>) {
        const auto row = neighbours.row(i);
        runFluidRow<D>(fluidRow, ii, row.begin, decltype(byKind)::value ? row.walls : row.end, r);
        if constexpr (decltype(byKind)::value) {
          if constexpr (!std::is_same_v<WallRow, PairByPair>) {
            if (row.walls != row.end) runFluidRow<D>(wallRow, ii, row.walls, row.end, r);  // (most have none)
          } else {
            for (const std::uint32_t* q = row.walls; q != row.end; ++q) wall(*q);
          }
        }
      } else if constexpr (decltype(byKind)::value) {
        neighbours.forEachByKind(i, fluid, wall);
      } else {
        neighbours.forEach(i, fluid);
      }
      epilogue(i, P, r);
    };
    if (walls) {
#pragma omp for schedule(static) nowait
      for (std::size_t i = 0; i < nFluid; ++i) fluidParticle(i, std::true_type{});
    } else {
#pragma omp for schedule(static) nowait
      for (std::size_t i = 0; i < nFluid; ++i) fluidParticle(i, std::false_type{});
    }
    auto wallParticle = [&](std::size_t i) __attribute__((flatten)) {
      PairRates<D> r;
      const Vec<D> xi = P.x[i];
      const auto ii = static_cast<std::uint32_t>(i);
      neighbours.forEach(i, [&](std::uint32_t j) {
        if (beyond(xi, P.x[j])) return;
        addPair(wallParticlePairs, makePair(ii, j, xi, P.x[j], kernel, invSupport), P, r);
      });
      wallEpilogue(i, P, r);
    };
    if (wallParticles) {
#pragma omp for schedule(static) nowait
      for (std::size_t i = nFluid; i < n; ++i) wallParticle(i);
    }
  }
  unsigned bits = packBits(fluidPairs);
  if (walls) bits |= packBits(wallPairs);
  if (wallParticles) bits |= packBits(wallParticlePairs);
  return bits;
}

// f(j, r_ij) for every neighbour j of particle i, r_ij = x_i - x_j: for the passes that walk the neighbours without the pair
// evaluators. `byKind`: f for the fluid neighbours, g for the wall ones.
template <int D, class F>
[[gnu::always_inline]] inline void forEachNeighbourSeparation(const Particles<D>& P,
                                                              const NeighbourList<D>& neighbours, std::size_t i,
                                                              F&& f) {
  const Vec<D> xi = P.x[i];
  neighbours.forEach(i, [&](std::uint32_t j) { f(j, Vec<D>(xi - P.x[j])); });
}
template <int D, class F, class G>
[[gnu::always_inline]] inline void forEachNeighbourSeparationByKind(const Particles<D>& P,
                                                                    const NeighbourList<D>& neighbours,
                                                                    std::size_t i, F&& f, G&& g) {
  const Vec<D> xi = P.x[i];
  neighbours.forEachByKind(
      i, [&](std::uint32_t j) { f(j, Vec<D>(xi - P.x[j])); },
      [&](std::uint32_t j) { g(j, Vec<D>(xi - P.x[j])); });
}

}  // namespace sph
