// The density-rate pass's pairs in SIMD blocks (pair_loop_blocks.hpp; a fluid
// particle's fluid neighbours, and with kDiffusion = false, continuity
// alone, its wall neighbours), in 2D and 3D, with a kernel the rows take
// (kRowKernel: its laneDWdr_r vectorises):
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

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sph {

// d rho_i/dt's sum over the fluid neighbours [begin, end) of fluid particle
// i, added to r.drho. `diffusion.volume`: m/rho of every particle, required
// with the diffusion on (the scalar evaluator's fallback, m/rho at each
// pair, is not repeated here). kDiffusion = false: continuity alone (the
// wall neighbours' row; the diffusion's sum is compiled out).
template <int D, class Kernel, bool kDiffusion = true>
struct DensityRateRow {
  const Particles<D>& P;
  Kernel kernel;
  DensityDiffusion<D> diffusion;
  const Real* m;  // every particle's mass as Real (realMasses, pair_scratch.hpp), required

  [[gnu::always_inline]] void operator()(std::uint32_t i, const std::uint32_t* begin, const std::uint32_t* end,
                                         PairRates<D>& rates) const {
    const Real* x = P.x.front().data();  // x_0, y_0, (z_0,) x_1, ...
    const Real* v = P.v.front().data();
    const Real* rho = P.rho.data();
    Real xi[D], vi[D], hydrostatic[D];
    for (int d = 0; d < D; ++d) xi[d] = x[D * i + d], vi[d] = v[D * i + d], hydrostatic[d] = diffusion.hydrostatic[d];
    const Real floor = diffusion.floor, rhoi = std::max(rho[i], floor);
    const bool diffuse = kDiffusion && diffusion.coefficient != 0;
    const Real coefficient = diffusion.coefficient, eta2 = diffusion.eta2;
    const Real* V = diffuse ? diffusion.volume : rho;  // (a lane reads it either way: never a null array)
    const Real support = kernel.support(), support2 = support * support;
    const Kernel k = kernel;
    alignas(64) Real sum[kPairBlock] = {};
    for (const std::uint32_t* block = begin; block < end; block += kPairBlock) {
      std::int64_t index[kPairBlock];
      const std::uint32_t filled = blockIndices(block, static_cast<std::uint32_t>(end - block), index);
      const BlockVectors<D> xj(x, index), vj(v, index);
#pragma omp simd
      for (int l = 0; l < kPairBlock; ++l) {
        const LanePair<D> q = lanePair<D>(xi, xj, l, k);
        const std::int64_t j = index[l];
        Real vij[D];
        for (int d = 0; d < D; ++d) vij[d] = vi[d] - vj(d, l);
        const Real continuity = m[j] * laneDot<D>(vij, q.g);
        if constexpr (kDiffusion) {
          const Real psi = (std::max(rho[j], floor) - rhoi) + laneDot<D>(hydrostatic, q.rij);
          const Real diffused = coefficient * V[j] * psi * (-laneDot<D>(q.rij, q.g)) / (q.r * q.r + eta2);
          sum[l] += laneCounts(l, filled, q.r2, support2) ? continuity + (diffuse ? diffused : 0.0) : 0.0;
        } else {
          sum[l] += laneCounts(l, filled, q.r2, support2) ? continuity : 0.0;
        }
      }
    }
    rates.drho += laneTotal(sum);
  }
};

}  // namespace sph
