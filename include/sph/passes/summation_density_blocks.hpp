// The summation density's sum in SIMD blocks (pair_loop_blocks.hpp), for
// Wendland C2 and the cubic spline (the kernel's laneW) in 2D and 3D:
//
//   rho_i = m_i W(0) + sum_j m_j W(|x_i - x_j|)        (terms/summation_density.hpp)
//
// over a fluid particle's neighbours [begin, end): its fluid ones, then its
// wall ones when the walls are in the sums. Each lane adds m_j W_ij to its
// own partial sum; the row adds the 8 partial sums at its end, then the
// self term. So rho_i is the scalar loop's sum with its terms in another
// order: within a few n eps sum_j m_j W_ij of it (test
// wcsph_terms/summation_density_blocks_match_the_scalar_loop), and the same
// on every run, thread count and resume. A pair in the list's skin adds an
// exact 0 either way (W = 0 beyond the support); a NaN distance makes rho_i
// NaN, as in the scalar loop, for the state check to name.
#pragma once

#include "sph/pair_loop_blocks.hpp"

#include <cmath>
#include <cstdint>

namespace sph {

template <int D, class Kernel = WendlandC2<D>>
struct SummationDensityRow {
  const Particles<D>& P;
  Kernel kernel;

  // (Its own function, called once per particle: as runFluidRow.)
  [[gnu::noinline]] Real operator()(std::uint32_t i, const std::uint32_t* begin, const std::uint32_t* end) const {
    const Real* x = P.x.front().data();  // x_0, y_0, (z_0,) x_1, ...
    const Narrow* m = P.m.data();
    Real xi[D];
    for (int d = 0; d < D; ++d) xi[d] = x[D * i + d];
    const Kernel k = kernel;
    alignas(64) Real sum[kPairBlock] = {};
    for (const std::uint32_t* block = begin; block < end; block += kPairBlock) {
      std::int64_t index[kPairBlock];
      const std::uint32_t filled = blockIndices(block, static_cast<std::uint32_t>(end - block), index);
      const BlockVectors<D> xj(x, index);
      const NarrowBlock mj(m, index);
#pragma omp simd
      for (int l = 0; l < kPairBlock; ++l) {
        Real r2 = 0;
        for (int d = 0; d < D; ++d) {
          const Real rij = xi[d] - xj(d, l);
          r2 += rij * rij;
        }
        const Real term = mj(l, index[l]) * k.laneW(std::sqrt(r2));
        sum[l] += l < static_cast<int>(filled) ? term : 0.0;
      }
    }
    return Real(m[i]) * k.W(0) + laneTotal(sum);
  }
};

}  // namespace sph
