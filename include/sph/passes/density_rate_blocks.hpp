// The density-rate pass's fluid-fluid pairs in blocks of 8, for SIMD lanes
// (2D, a kernel whose dWdr_r the compiler vectorises):
//
//   d rho_i/dt = sum_j m_j (v_i - v_j) . grad_i W_ij                       (continuity_density.hpp)
//              + 2 delta h c0 sum_j V_j psi_ij (-r_ij . grad_i W_ij) / (r_ij^2 + eta^2)
//                                                                      (density_diffusion.hpp)
//
// Each lane forms one pair's two contributions from the same operations,
// in the same order, as the scalar pair loop (pair_loop.hpp: makePair,
// ContinuityDensity::add, DensityDiffusion::add), and the lanes' results
// are then added to the row's sum one pair after the other in the list's
// order, so the rate is the scalar loop's bit for bit (with
// -ffp-contract=off, which the build sets: a fused multiply-add would
// round differently). Pairs in the list's skin are computed and not added;
// lanes past the row's end repeat its first neighbour and are not added.
// Only the work per pair is vectorised (the gathers of x, v, m, rho, V, the
// square root, the kernel, the diffusion's division); the sum stays serial.
#pragma once

#include "sph/boundaries/wall_sums.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/pair_loop.hpp"
#include "sph/particles.hpp"
#include "sph/terms/continuity_density.hpp"
#include "sph/terms/density_diffusion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sph {

constexpr int kRateBlock = 8;

// Whether the blocks pay: with AVX2 or AVX-512 (the build's SPH_NATIVE, on
// such a machine) they cut the walk's time; with the SSE2 of a portable
// x86-64 build (2 lanes) they measured 19% slower over the whole dam break
// (6.98 against 5.88 CPU s), so the pass keeps the scalar loop there.
#if defined(__AVX2__) || defined(__AVX512F__)
constexpr bool kRateBlocksPay = true;
#else
constexpr bool kRateBlocksPay = false;
#endif

// d rho_i/dt's sum over the fluid neighbours [begin, end) of fluid particle
// i, added to drho. `volume`: m/rho of every particle (with the diffusion).
template <class Kernel>
[[gnu::always_inline]] inline Real densityRateFluidRow(std::uint32_t i, const std::uint32_t* begin,
                                                       const std::uint32_t* end, const Particles<2>& P,
                                                       const Kernel& kernel, Real support2,
                                                       const DensityDiffusion<2>& diffusion, const Real* volume,
                                                       Real drho) {
  const Real* x = P.x.front().data();  // x_0, y_0, x_1, y_1, ...
  const Real* v = P.v.front().data();
  const Real* m = P.m.data();
  const Real* rho = P.rho.data();
  const Real xi0 = x[2 * i], xi1 = x[2 * i + 1], vi0 = v[2 * i], vi1 = v[2 * i + 1], rhoi = rho[i];
  const bool diffuse = diffusion.coefficient != 0;
  const Real coefficient = diffusion.coefficient, eta2 = diffusion.eta2;
  const Real h0 = diffusion.hydrostatic[0], h1 = diffusion.hydrostatic[1];
  const Real* V = diffuse ? volume : rho;  // (a lane reads it either way: never a null array)
  const Kernel k = kernel;
  const auto count = static_cast<std::uint32_t>(end - begin);
  for (std::uint32_t k0 = 0; k0 < count; k0 += kRateBlock) {
    const std::uint32_t filled = std::min<std::uint32_t>(kRateBlock, count - k0);
    const std::uint32_t* block = begin + k0;
    alignas(64) Real continuity[kRateBlock], diffused[kRateBlock];
    alignas(64) std::int64_t inside[kRateBlock], index[kRateBlock];
    // (A lane past the row's end takes the row's first neighbour.)
    for (std::uint32_t l = 0; l < kRateBlock; ++l) index[l] = block[l < filled ? l : 0];
#pragma omp simd
    for (int l = 0; l < kRateBlock; ++l) {
      const std::int64_t j = index[l];
      const Real r0 = xi0 - x[2 * j], r1 = xi1 - x[2 * j + 1];
      const Real r2 = r0 * r0 + r1 * r1;
      const Real r = std::sqrt(r2);
      const Real w = k.dWdr_r(r);
      const Real g0 = w * r0, g1 = w * r1;
      continuity[l] = m[j] * ((vi0 - v[2 * j]) * g0 + (vi1 - v[2 * j + 1]) * g1);
      const Real psi = (rho[j] - rhoi) + (h0 * r0 + h1 * r1);
      diffused[l] = coefficient * V[j] * psi * (-(r0 * g0 + r1 * g1)) / (r * r + eta2);
      inside[l] = r2 < support2;
    }
    for (std::uint32_t l = 0; l < filled; ++l) {
      if (!inside[l]) continue;
      drho += continuity[l];
      if (diffuse) drho += diffused[l];
    }
  }
  return drho;
}

// The density-rate pass of 2D with these rows: what runPairLoop does for
// it (density_rate.hpp), with the fluid particles' fluid neighbours in
// blocks. Wall neighbours (walls in the sums) and the dynamic walls' own
// rates are the scalar loop's. Returns the term bits of the packs it ran.
template <class Kernel>
unsigned densityRateInBlocks(Particles<2>& P, const NeighbourList<2>& neighbours, const Kernel& kernel,
                             const DensityDiffusion<2>& diffusion, WallSums walls,
                             const ParticlePrologue<2>& prologue) {
  const std::size_t n = P.size(), nFluid = P.fluidCount();
  const Real support = kernel.support(), invSupport = 1 / support, support2 = support * support;
  const bool wallPairs = P.hasWalls() && walls.inSums;
  const bool wallParticles = P.hasWalls() && walls.densityRates;
  const ContinuityDensity rate{true}, wallRate{walls.densityRates};
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
      PairRates<2> r;
      r.drho = densityRateFluidRow(ii, row.begin, wallPairs ? row.walls : row.end, P, kernel, support2, diffusion,
                                   prologue.volume, Real(0));
      if (wallPairs) {
        const Vec<2> xi = P.x[i];
        for (const std::uint32_t* q = row.walls; q != row.end; ++q) {
          if (!(Vec<2>(xi - P.x[*q]).squaredNorm() < support2)) continue;
          rate.add(makePair(ii, *q, xi, P.x[*q], kernel, invSupport), P, r);
        }
      }
      P.drho[i] = r.drho;
    }
    if (wallParticles) {
#pragma omp for schedule(static) nowait
      for (std::size_t i = nFluid; i < n; ++i) {
        PairRates<2> r;
        const Vec<2> xi = P.x[i];
        const auto ii = static_cast<std::uint32_t>(i);
        neighbours.forEach(i, [&](std::uint32_t j) {
          if (!(Vec<2>(xi - P.x[j]).squaredNorm() < support2)) return;
          wallRate.add(makePair(ii, j, xi, P.x[j], kernel, invSupport), P, r);
        });
        P.drho[i] = r.drho;
      }
    }
  }
  unsigned bits = packBits(std::make_tuple(rate, diffusion));
  if (wallPairs) bits |= packBits(std::make_tuple(rate));
  if (wallParticles) bits |= packBits(std::make_tuple(wallRate));
  return bits;
}

}  // namespace sph
