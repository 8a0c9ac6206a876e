// The density-rate pass's fluid-fluid pairs in SIMD blocks
// (pair_loop_blocks.hpp), in 2D with a kernel whose dWdr_r vectorises:
//
//   d rho_i/dt = sum_j m_j (v_i - v_j) . grad_i W_ij                       (continuity_density.hpp)
//              + 2 delta h c0 sum_j V_j psi_ij (-r_ij . grad_i W_ij) / (r_ij^2 + eta^2)
//                                                                      (density_diffusion.hpp)
//
// Each lane forms one pair's two contributions and adds them to its own
// partial sum; the 8 partial sums are added at the row's end
// (pair_loop_blocks.hpp). So the rate is the scalar loop's up to the order
// of the sum (test continuity/density_rate_blocks_match_the_scalar_loop).
#pragma once

#include "sph/pair_loop_blocks.hpp"
#include "sph/terms/density_diffusion.hpp"

#include <cmath>
#include <cstdint>

namespace sph {

// d rho_i/dt's sum over the fluid neighbours [begin, end) of fluid particle
// i, added to r.drho. `diffusion.volume`: m/rho of every particle, required
// with the diffusion on (the scalar evaluator's fallback, m/rho at each
// pair, is not repeated here).
template <class Kernel>
struct DensityRateRow {
  const Particles<2>& P;
  Kernel kernel;
  DensityDiffusion<2> diffusion;

  [[gnu::always_inline]] void operator()(std::uint32_t i, const std::uint32_t* begin, const std::uint32_t* end,
                                         PairRates<2>& rates) const {
    const Real* x = P.x.front().data();  // x_0, y_0, x_1, y_1, ...
    const Real* v = P.v.front().data();
    const Real* m = P.m.data();
    const Real* rho = P.rho.data();
    const Real xi0 = x[2 * i], xi1 = x[2 * i + 1], vi0 = v[2 * i], vi1 = v[2 * i + 1], rhoi = rho[i];
    const bool diffuse = diffusion.coefficient != 0;
    const Real coefficient = diffusion.coefficient, eta2 = diffusion.eta2;
    const Real h0 = diffusion.hydrostatic[0], h1 = diffusion.hydrostatic[1];
    const Real* V = diffuse ? diffusion.volume : rho;  // (a lane reads it either way: never a null array)
    const Real support = kernel.support(), support2 = support * support;
    const Kernel k = kernel;
    alignas(64) Real sum[kPairBlock] = {};
    for (const std::uint32_t* block = begin; block < end; block += kPairBlock) {
      std::int64_t index[kPairBlock];
      const std::uint32_t filled = blockIndices(block, static_cast<std::uint32_t>(end - block), index);
      alignas(64) Real xj0[kPairBlock], xj1[kPairBlock], vj0[kPairBlock], vj1[kPairBlock];
      gatherVectors(x, index, xj0, xj1);
      gatherVectors(v, index, vj0, vj1);
#pragma omp simd
      for (int l = 0; l < kPairBlock; ++l) {
        const LanePair q = lanePair(xi0, xi1, xj0[l], xj1[l], k);
        const Real r0 = q.r0, r1 = q.r1, r2 = q.r2, r = q.r, g0 = q.g0, g1 = q.g1;
        const std::int64_t j = index[l];
        const Real continuity = m[j] * ((vi0 - vj0[l]) * g0 + (vi1 - vj1[l]) * g1);
        const Real psi = (rho[j] - rhoi) + (h0 * r0 + h1 * r1);
        const Real diffused = coefficient * V[j] * psi * (-(r0 * g0 + r1 * g1)) / (r * r + eta2);
        sum[l] += laneCounts(l, filled, r2, support2) ? continuity + (diffuse ? diffused : 0.0) : 0.0;
      }
    }
    rates.drho += laneTotal(sum);
  }
};

}  // namespace sph
