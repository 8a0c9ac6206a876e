// What the row functions that take a fluid particle's fluid neighbours in
// SIMD blocks share (passes/density_rate_blocks.hpp, passes/force_blocks.hpp;
// runPairLoop's fluidRow, pair_loop.hpp). A row walks its neighbours 8 at a
// time: each lane forms one pair with the scalar evaluators' formulas and
// adds it to the lane's own partial sum, and the row adds the 8 partial sums
// at its end. So a row's sum is the scalar loop's with its terms in another
// order: different in the last bits (a few n eps sum_j |term_j| for n
// pairs; the tests continuity/density_rate_blocks_match_the_scalar_loop and
// wcsph_terms/force_blocks_match_the_scalar_loop hold it to that bound), and
// the same on every run, thread count and resume (the order depends on the
// neighbour list alone). Adding the lanes' results one pair after the other
// in the list's order instead, as the first form of these rows did (the
// scalar loop's bits), made the dam break 1.55 times slower: the serial
// chain of additions, not the pairs' arithmetic, bounded the walk. The wall
// neighbours, the wall particles' own rates and the epilogues stay
// runPairLoop's. A row skips the pairs in the list's skin as the scalar
// loop does.
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
// ways (wcsph_terms/runs_with_blocks_match_the_scalar_runs).
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

// Whether lane l of a block with `filled` real pairs adds its pair: a real
// pair inside the kernel's support (r^2 < support^2, as the scalar loop).
[[gnu::always_inline]] inline bool laneCounts(int l, std::uint32_t filled, Real r2, Real support2) {
  return (l < static_cast<int>(filled)) & (r2 < support2);
}

// The sum of a row's 8 partial sums, in a fixed order (pairwise).
[[gnu::always_inline]] inline Real laneTotal(const Real (&s)[kPairBlock]) {
  static_assert(kPairBlock == 8);
  return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
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
