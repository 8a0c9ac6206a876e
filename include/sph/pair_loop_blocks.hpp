// The pair loop with the fluid particles' fluid neighbours taken in SIMD
// blocks (passes/density_rate_blocks.hpp, passes/force_blocks.hpp): what
// runPairLoop (pair_loop.hpp) does, in the same parallel region and order,
// but for the fluid-fluid pairs of each row, which a row function adds:
//   fluidRow(i, begin, end, rates)   the fluid neighbours [begin, end) of
//                                    fluid particle i, added to its rates
// It forms each pair in a lane with the scalar loop's operations, in the
// same order (no contracted multiply-add: the build's -ffp-contract=off),
// and adds the lanes' results to the sums one pair after the other in the
// list's order, so the rates are the scalar loop's bit for bit (tests:
// continuity/density_rate_blocks_..., wcsph_terms/force_blocks_...). The
// wall neighbours, the wall particles' own rates and the epilogues are the
// scalar loop's own. A row function skips the pairs in the list's skin as
// the scalar loop does.
#pragma once

#include "sph/neighbour_list.hpp"
#include "sph/pair_loop.hpp"
#include "sph/particles.hpp"

#include <cmath>
#include <cstdint>
#include <tuple>

namespace sph {

// The pairs of a block: one per SIMD lane (8 doubles: AVX-512).
constexpr int kPairBlock = 8;

// Whether the blocks pay: with AVX2 or AVX-512 (the build's SPH_NATIVE, on
// such a machine) they cut a walk's time; with the SSE2 of a portable
// x86-64 build (2 lanes) the density-rate blocks measured 19% slower over
// the whole dam break (6.98 against 5.88 CPU s), so the passes keep the
// scalar loop there.
#if defined(__AVX2__) || defined(__AVX512F__)
constexpr bool kPairBlocksPay = true;
#else
constexpr bool kPairBlocksPay = false;
#endif

// Whether the passes may take the blocks where they pay (true): off, every
// pass runs the scalar loop; for the tests that compare whole runs both
// ways (wcsph_terms/runs_with_blocks_are_the_scalar_runs_bit_for_bit).
inline bool& pairBlocksAllowed() {
  static bool allowed = true;
  return allowed;
}

// The indices of the block of a row that starts at `block`, `filled` of
// them real; a lane past the row's end takes the row's first neighbour
// (its result is not added). Signed 64-bit: gather indices.
inline std::uint32_t blockIndices(const std::uint32_t* block, std::uint32_t left, std::int64_t (&index)[kPairBlock]) {
  const std::uint32_t filled = left < kPairBlock ? left : kPairBlock;
  for (std::uint32_t l = 0; l < kPairBlock; ++l) index[l] = block[l < filled ? l : 0];
  return filled;
}

// One lane's pair in 2D, as makePair (pair_loop.hpp) forms it: r_ij =
// x_i - x_j, r^2, r, and grad_i W = dWdr_r(r) r_ij. `x`: x_0, y_0, x_1, ...
struct LanePair {
  Real r0, r1, r2, r, g0, g1;
};
template <class Kernel>
[[gnu::always_inline]] inline LanePair lanePair(Real xi0, Real xi1, const Real* x, std::int64_t j, const Kernel& k) {
  LanePair q;
  q.r0 = xi0 - x[2 * j];
  q.r1 = xi1 - x[2 * j + 1];
  q.r2 = q.r0 * q.r0 + q.r1 * q.r1;
  q.r = std::sqrt(q.r2);
  const Real w = k.dWdr_r(q.r);
  q.g0 = w * q.r0;
  q.g1 = w * q.r1;
  return q;
}

template <int D, class Kernel, class FluidRow, class WallPairs, class WallParticlePairs, class Epilogue,
          class WallEpilogue, class Prologue>
void runPairLoopInBlocks(Particles<D>& P, const NeighbourList<D>& neighbours, const Kernel& kernel,
                         const FluidRow& fluidRow, const WallPairs& wallPairs,
                         const WallParticlePairs& wallParticlePairs, const Epilogue& epilogue,
                         const WallEpilogue& wallEpilogue, PairLoopParts parts, const Prologue& prologue) {
  const std::size_t n = P.size(), nFluid = P.fluidCount();
  const Real support = kernel.support(), invSupport = 1 / support, support2 = support * support;
  const bool wallParticles = std::tuple_size_v<WallParticlePairs> > 0 && parts.wallParticles && P.hasWalls();
  const bool walls = P.hasWalls() && parts.wallPairs;
#pragma omp parallel if (n >= kMinParallelSize)
  {
    if (prologue.active()) {
      const std::size_t total = P.totalSize();
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < total; ++i) prologue(i, P);
    }
#pragma omp for schedule(static) nowait
    for (std::size_t i = 0; i < nFluid; ++i) {
      const auto row = neighbours.row(i);
      const auto ii = static_cast<std::uint32_t>(i);
      PairRates<D> r;
      fluidRow(ii, row.begin, walls ? row.walls : row.end, r);
      if (walls) {
        const Vec<D> xi = P.x[i];
        for (const std::uint32_t* q = row.walls; q != row.end; ++q) {
          if (!(Vec<D>(xi - P.x[*q]).squaredNorm() < support2)) continue;
          addPair(wallPairs, makePair(ii, *q, xi, P.x[*q], kernel, invSupport), P, r);
        }
      }
      epilogue(i, P, r);
    }
    if (wallParticles) {
#pragma omp for schedule(static) nowait
      for (std::size_t i = nFluid; i < n; ++i) {
        PairRates<D> r;
        const Vec<D> xi = P.x[i];
        const auto ii = static_cast<std::uint32_t>(i);
        neighbours.forEach(i, [&](std::uint32_t j) {
          if (!(Vec<D>(xi - P.x[j]).squaredNorm() < support2)) return;
          addPair(wallParticlePairs, makePair(ii, j, xi, P.x[j], kernel, invSupport), P, r);
        });
        wallEpilogue(i, P, r);
      }
    }
  }
}

}  // namespace sph
