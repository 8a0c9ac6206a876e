// What the row functions that take a fluid particle's fluid neighbours in
// SIMD blocks share (passes/density_rate_blocks.hpp, passes/force_blocks.hpp;
// runPairLoop's fluidRow, pair_loop.hpp). A row function forms each pair in a lane with the scalar loop's operations, in the
// same order (no contracted multiply-add: the build's -ffp-contract=off),
// and adds the lanes' results to the sums one pair after the other in the
// list's order, so the rates are the scalar loop's bit for bit (tests:
// continuity/density_rate_blocks_..., wcsph_terms/force_blocks_...). The
// wall neighbours, the wall particles' own rates and the epilogues stay
// runPairLoop's. A row function skips the pairs in the list's skin as the
// scalar loop does.
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

}  // namespace sph
