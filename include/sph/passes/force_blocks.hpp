// The force pass's fluid-fluid pairs in SIMD blocks (pair_loop_blocks.hpp)
// for the water physics of 2D: Wendland C2, the symmetric pressure term and
// Monaghan's artificial viscosity, with the density rate computed apart
// (leap-frog, symplectic Euler) and nothing else in the pack:
//
//   a_i = - sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2) grad_i W_ij         (symmetric_pressure.hpp)
//         - sum_j m_j Pi_ij grad_i W_ij,  Pi_ij = (-alpha cbar_ij mu_ij + beta mu_ij^2) / rhobar_ij
//           for v_ij . r_ij < 0, mu_ij = h v_ij . r_ij / (r_ij^2 + 0.01 h^2)   (monaghan_viscosity.hpp)
//
// Each lane forms one pair's contribution, (m_j (p_i/rho_i^2 + p_j/rho_j^2)
// + m_j Pi_ij) grad_i W_ij, and adds it to its own partial sums; the 8
// partial sums are added at the row's end (pair_loop_blocks.hpp). So the
// acceleration is the scalar loop's up to the order of the sum: within a
// few n eps sum_j |term_j| (test wcsph_terms/force_blocks_match_the_scalar_loop).
#pragma once

#include "sph/pair_loop_blocks.hpp"

#include <cmath>
#include <cstdint>

namespace sph {

template <class Kernel>
struct PressureViscosityRow {
  const Particles<2>& P;
  Kernel kernel;
  const Real* pOverRho2;  // p/rho^2 of every particle (the pass's prologue), required
  Real alpha, beta;

  [[gnu::always_inline]] void operator()(std::uint32_t i, const std::uint32_t* begin, const std::uint32_t* end,
                                         PairRates<2>& rates) const {
    const Real* x = P.x.front().data();  // x_0, y_0, x_1, y_1, ...
    const Real* v = P.v.front().data();
    const Real* m = P.m.data();
    const Real* rho = P.rho.data();
    const Real* c = P.c.data();
    const Real* pr = pOverRho2;
    const Real xi0 = x[2 * i], xi1 = x[2 * i + 1], vi0 = v[2 * i], vi1 = v[2 * i + 1];
    const Real rhoi = rho[i], ci = c[i], pi = pr[i];
    const Real support = kernel.support(), support2 = support * support;
    const Real h = kernel.h(), eps = 0.01, a = alpha, b = beta;
    const Kernel k = kernel;
    alignas(64) Real sx[kPairBlock] = {}, sy[kPairBlock] = {};
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
        const Real sp = -m[j] * (pi + pr[j]);
        const Real vr = (vi0 - vj0[l]) * r0 + (vi1 - vj1[l]) * r1;
        const Real mu = h * vr / (r * r + eps * h * h);
        const Real cBar = (ci + c[j]) / 2, rhoBar = (rhoi + rho[j]) / 2;
        const Real Pi = (-a * cBar * mu + b * mu * mu) / rhoBar;
        const Real sv = -m[j] * Pi;
        const bool viscous = !(vr >= 0);  // (as MonaghanViscosity::add, which skips vr >= 0 only)
        const Real s = laneCounts(l, filled, r2, support2) ? sp + (viscous ? sv : 0.0) : 0.0;
        sx[l] += s * g0;
        sy[l] += s * g1;
      }
    }
    rates.a[0] += laneTotal(sx);
    rates.a[1] += laneTotal(sy);
  }
};

}  // namespace sph
