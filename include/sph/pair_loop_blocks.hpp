// What the row functions that take a fluid particle's neighbours in SIMD
// blocks share (passes/density_rate_blocks.hpp, passes/force_blocks.hpp:
// runPairLoop's fluidRow and wallRow, pair_loop.hpp; and
// passes/summation_density_blocks.hpp). A row walks its neighbours 8 at a
// time: each lane forms one pair with the scalar evaluators' formulas and
// adds it to the lane's own partial sum, and the row adds the 8 partial sums
// at its end. So a row's sum is the scalar loop's with its terms in another
// order: different in the last bits (a few n eps sum_j |term_j| for n
// pairs; the tests continuity/density_rate_blocks_match_the_scalar_loop,
// wcsph_terms/force_blocks_match_the_scalar_loop and
// wcsph_terms/summation_density_blocks_match_the_scalar_loop hold it to that
// bound), and the same on every run, thread count and resume (the order
// depends on the neighbour list alone). Adding the lanes' results one pair
// after the other in the list's order instead, as the first form of these
// rows did (the scalar loop's bits), made the dam break 1.55 times slower:
// the serial chain of additions, not the pairs' arithmetic, bounded the
// walk. Each term is formed with the scalar evaluator's operations, in its
// order (the build's -ffp-contract=off keeps the compiler from fusing
// them), so only the order of the sum differs, and the force row's one
// product (m_j P_ij + m_j Pi_ij) grad W where the scalar loop takes two.
// The wall particles' own rates and the epilogues stay runPairLoop's. Each
// row writes its own block loop around these helpers: a shared walk calling
// the row's lambda per lane left GCC 12's loop scalar, 2.5 times slower
// (docs/performance.md). The force and density-rate rows skip the pairs in
// the list's skin, and a pair whose r^2 is NaN, as their scalar loop does;
// the summation row adds the skin's exact zeros and a NaN, as its scalar
// loop does.
#pragma once

#include "sph/kernels/kernels.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/pair_loop.hpp"
#include "sph/particles.hpp"

#include <cmath>
#if defined(__AVX__)
#include <immintrin.h>
#endif
#include <cstdint>
#include <type_traits>
#include <tuple>

namespace sph {

// The pairs of a block: one per SIMD lane (8 doubles: AVX-512).
constexpr int kPairBlock = 8;

// Whether the blocks pay: with AVX2 or AVX-512 (the build's SPH_NATIVE, on
// such a machine) they cut a walk's time; with the SSE2 of a portable
// x86-64 build (2 lanes) the density-rate blocks measured 19% slower over
// the whole dam break (6.98 against 5.88 CPU s; the rows' first form, with
// the lanes' results added in order: not measured again), so the passes
// keep the scalar loop there.
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

// The kernels the rows take: those whose laneW and laneDWdr_r the compiler
// forms per lane, Wendland C2 and the cubic spline (the Gaussian's exp and
// Muller's kernels stay with the scalar loop).
template <class K>
inline constexpr bool kRowKernel = false;
template <int D>
inline constexpr bool kRowKernel<WendlandC2<D>> = true;
template <int D>
inline constexpr bool kRowKernel<CubicSpline<D>> = true;
template <int D>
bool isRowKernel(const Kernel<D>& kernel) {
  return std::visit([](const auto& k) { return kRowKernel<std::decay_t<decltype(k)>>; }, kernel);
}

// The indices of the block of a row that starts at `block`, `filled` of
// them real; a lane past the row's end takes the block's first neighbour
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

// The 2D vectors (x, or v) of a block's 8 particles, one array per
// component: with AVX, two 16-byte loads per pair of lanes and two shuffles
// per 4 lanes, instead of a scalar load and an insert per component and
// lane (what the compiler makes of a gather, tuned generic).
[[gnu::always_inline]] inline void gatherVectors(const Real* xy, const std::int64_t (&index)[kPairBlock],
                                                 Real (&c0)[kPairBlock], Real (&c1)[kPairBlock]) {
#if defined(__AVX__)
  for (int q = 0; q < kPairBlock; q += 4) {
    const __m256d a = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(xy + 2 * index[q])),
                                           _mm_loadu_pd(xy + 2 * index[q + 2]), 1);  // x_a y_a x_c y_c
    const __m256d b = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(xy + 2 * index[q + 1])),
                                           _mm_loadu_pd(xy + 2 * index[q + 3]), 1);  // x_b y_b x_d y_d
    _mm256_storeu_pd(c0 + q, _mm256_unpacklo_pd(a, b));                               // x_a x_b x_c x_d
    _mm256_storeu_pd(c1 + q, _mm256_unpackhi_pd(a, b));
  }
#else
  for (int l = 0; l < kPairBlock; ++l) c0[l] = xy[2 * index[l]], c1[l] = xy[2 * index[l] + 1];
#endif
}

// The 3D vectors of a block's 8 particles, one array per component: with
// AVX, one masked 32-byte load per lane (x, y, z and a 0 in place of the
// next particle's x, which is never read: no load past the array's end) and
// a 4 x 4 transpose per 4 lanes, instead of a scalar load and an insert per
// component and lane.
[[gnu::always_inline]] inline void gatherVectors3(const Real* xyz, const std::int64_t (&index)[kPairBlock],
                                                  Real (&c0)[kPairBlock], Real (&c1)[kPairBlock],
                                                  Real (&c2)[kPairBlock]) {
#if defined(__AVX__)
  const __m256i three = _mm256_setr_epi64x(-1, -1, -1, 0);
  for (int q = 0; q < kPairBlock; q += 4) {
    const __m256d a = _mm256_maskload_pd(xyz + 3 * index[q], three);      // x_a y_a z_a 0
    const __m256d b = _mm256_maskload_pd(xyz + 3 * index[q + 1], three);  // x_b y_b z_b 0
    const __m256d c = _mm256_maskload_pd(xyz + 3 * index[q + 2], three);
    const __m256d d = _mm256_maskload_pd(xyz + 3 * index[q + 3], three);
    const __m256d ab0 = _mm256_unpacklo_pd(a, b), ab1 = _mm256_unpackhi_pd(a, b);  // x_a x_b z_a z_b; y_a y_b 0 0
    const __m256d cd0 = _mm256_unpacklo_pd(c, d), cd1 = _mm256_unpackhi_pd(c, d);
    _mm256_storeu_pd(c0 + q, _mm256_permute2f128_pd(ab0, cd0, 0x20));  // x_a x_b x_c x_d
    _mm256_storeu_pd(c1 + q, _mm256_permute2f128_pd(ab1, cd1, 0x20));  // y_a y_b y_c y_d
    _mm256_storeu_pd(c2 + q, _mm256_permute2f128_pd(ab0, cd0, 0x31));  // z_a z_b z_c z_d
  }
#else
  for (int l = 0; l < kPairBlock; ++l)
    c0[l] = xyz[3 * index[l]], c1[l] = xyz[3 * index[l] + 1], c2[l] = xyz[3 * index[l] + 2];
#endif
}

// The positions (or velocities) of a block's 8 neighbours, gathered into
// one array per component before the lanes (gatherVectors, gatherVectors3).
template <int D>
struct BlockVectors {
  alignas(64) Real c[D][kPairBlock];  // the gathered components
  static_assert(sizeof(Vec<D>) == D * sizeof(Real), "the particles' vectors are D packed doubles");

  // all: component d of particle j at all[D j + d].
  [[gnu::always_inline]] BlockVectors(const Real* all, const std::int64_t (&index)[kPairBlock]) {
    if constexpr (D == 2) gatherVectors(all, index, c[0], c[1]);
    else gatherVectors3(all, index, c[0], c[1], c[2]);
  }
  [[gnu::always_inline]] Real operator()(int d, int l) const { return c[d][l]; }
};

// A narrow field (sph::Narrow, types.hpp: the sound speed of the force
// walk, the mass of the summation walk; the water walks read the masses
// widened once per pass, realMasses in pair_scratch.hpp) of a block's
// neighbours, read as Real by lane: in a double build the field
// itself, read in the lanes' loop; in a mixed-precision build its floats
// gathered and widened to doubles before the loop, since GCC 12 leaves a
// lanes' loop that reads a float array through the lanes' indices scalar
// (the 2D dam break ran 2.3 times slower: 3.54 against 1.56 CPU s to
// 0.2 s; 1.66 with the widening).
struct NarrowBlock {
  static constexpr bool kWiden = !std::is_same_v<Narrow, Real>;
  const Narrow* all;
  alignas(64) Real widened[kWiden ? kPairBlock : 1];

  // (One load and widening per lane: AVX2's gather of 4 floats and
  // widening measured slower on this host, 1.28 times the double build's
  // CPU time against this loop's 1.09, each interleaved with it.)
  [[gnu::always_inline]] NarrowBlock(const Narrow* values, const std::int64_t (&index)[kPairBlock]) : all(values) {
    if constexpr (kWiden)
      for (int l = 0; l < kPairBlock; ++l) widened[l] = static_cast<Real>(values[index[l]]);
  }
  // Lane l, whose neighbour is j.
  [[gnu::always_inline]] Real operator()(int l, std::int64_t j) const {
    if constexpr (kWiden) return widened[l];
    else return all[j];
  }
};

// One lane's pair, as makePair (pair_loop.hpp) forms it: r_ij = x_i - x_j,
// r^2, r, w = dWdr_r(r) (the kernel's laneDWdr_r: its values) and grad_i W
// = w r_ij.
template <int D>
struct LanePair {
  Real rij[D], r2, r, w, g[D];
};
template <int D, class Kernel>
[[gnu::always_inline]] inline LanePair<D> lanePair(const Real (&xi)[D], const BlockVectors<D>& xj, int l,
                                                   const Kernel& k) {
  LanePair<D> q;
  q.r2 = 0;
  for (int d = 0; d < D; ++d) {
    q.rij[d] = xi[d] - xj(d, l);
    q.r2 += q.rij[d] * q.rij[d];
  }
  q.r = std::sqrt(q.r2);
  q.w = k.laneDWdr_r(q.r);
  for (int d = 0; d < D; ++d) q.g[d] = q.w * q.rij[d];
  return q;
}

// a . b over D components, as the lanes form it.
template <int D>
[[gnu::always_inline]] inline Real laneDot(const Real (&a)[D], const Real (&b)[D]) {
  Real s = a[0] * b[0];
  for (int d = 1; d < D; ++d) s += a[d] * b[d];
  return s;
}

}  // namespace sph
