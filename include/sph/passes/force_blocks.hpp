// The force pass's pairs in SIMD blocks (pair_loop_blocks.hpp; a fluid
// particle's fluid neighbours, and with kXsph = false its wall neighbours)
// for the water physics and the laminar one, 2D and 3D: Wendland C2 or the
// cubic spline (the kernel's laneW and laneDWdr_r), the
// symmetric pressure term and a viscosity (RowViscosity: Monaghan's
// artificial one, Morris' or the Laplacian one, or none), with the density
// rate computed apart (leap-frog, symplectic Euler or summation density),
// and optionally XSPH:
//
//   a_i = - sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2) grad_i W_ij         (symmetric_pressure.hpp)
//         - sum_j m_j Pi_ij grad_i W_ij,  Pi_ij = (-alpha cbar_ij mu_ij + beta mu_ij^2) / rhobar_ij
//           for v_ij . r_ij < 0, mu_ij = h v_ij . r_ij / (r_ij^2 + 0.01 h^2)   (monaghan_viscosity.hpp)
//     or  + sum_j m_j nu (rho_i + rho_j) / (rho_i rho_j) (r_ij . grad_i W_ij) / (r_ij^2 + 1e-4 h^2)
//           (v_i - v_j)                                                (kMorris: morris_viscosity.hpp)
//     or  + sum_j mu m_j / (rho_i rho_j) (-2 dW/dr / r) (v_j - v_i)   (kLaplacian: laplacian_viscosity.hpp)
//     (Morris and Laplacian: a wall neighbour shows the fluid its vWall)
//   xsph_i = sum_j (2 m_j / (rho_i + rho_j)) W_ij (v_j - v_i)          (xsph.hpp, Monaghan 1989;
//                                                                      kXsph only)
//
// Each lane forms one pair's contribution, (m_j (p_i/rho_i^2 + p_j/rho_j^2)
// + m_j Pi_ij) grad_i W_ij (the laminar viscosities: the pressure's, plus
// f_ij times the velocity difference) (and its XSPH sum's term), and adds it
// to its own
// partial sums; the 8 partial sums are added at the row's end
// (pair_loop_blocks.hpp). So the acceleration (and the XSPH sum) is the
// scalar loop's up to the order of the sum: within a few n eps sum_j
// |term_j| (test wcsph_terms/force_blocks_match_the_scalar_loop). The row
// without XSPH is compiled apart, so a case without it pays nothing for it;
// only the Monaghan row reads the sound speeds.
#pragma once

#include "sph/pair_loop_blocks.hpp"

#include <cmath>
#include <cstdint>
#include <type_traits>

namespace sph {

// The viscosity of a row.
enum class RowViscosity { kMonaghan, kMorris, kLaplacian, kNone };

// What a row without Monaghan's viscosity reads in place of the sound speeds: nothing.
struct NoSoundSpeeds {
  [[gnu::always_inline]] NoSoundSpeeds(const Narrow*, const std::int64_t (&)[kPairBlock]) {}
};

template <int D, class Kernel, bool kXsph = false, RowViscosity kViscosity = RowViscosity::kMonaghan>
struct PressureViscosityRow {
  static constexpr bool kMonaghan = kViscosity == RowViscosity::kMonaghan;
  static constexpr bool kLaminar = kViscosity == RowViscosity::kMorris || kViscosity == RowViscosity::kLaplacian;
  const Particles<D>& P;
  Kernel kernel;
  const Real* pOverRho2;  // p/rho^2 of every particle (the pass's prologue), required
  Real alpha, beta;       // Monaghan's
  const Real* m;  // every particle's mass as Real (realMasses, pair_scratch.hpp), required
  // Morris: the kinematic viscosity nu; Laplacian: the dynamic viscosity mu
  // (0: the term adds nothing).
  Real laminar = 0;
  // Morris, Laplacian: the neighbours' velocity the viscosity reads (a wall
  // row: P.vWall's first component); nullptr: P.v.
  const Real* vViscous = nullptr;

  [[gnu::always_inline]] void operator()(std::uint32_t i, const std::uint32_t* begin, const std::uint32_t* end,
                                         PairRates<D>& rates) const {
    const Real* x = P.x.front().data();  // x_0, y_0, (z_0,) x_1, ...
    const Real* v = P.v.front().data();
    const Real* vShown = kLaminar && vViscous ? vViscous : v;  // (v_j, or a wall's vWall_j)
    const Real* rho = P.rho.data();
    const Narrow* c = kMonaghan ? P.c.data() : nullptr;
    const Real* pr = pOverRho2;
    Real xi[D], vi[D];
    for (int d = 0; d < D; ++d) xi[d] = x[D * i + d], vi[d] = v[D * i + d];
    const Real rhoi = rho[i], ci = kMonaghan ? c[i] : 0, pi = pr[i];
    const Real support = kernel.support(), support2 = support * support;
    const Real h = kernel.h(), eps = 0.01, a = alpha, b = beta, n = laminar;
    const Kernel k = kernel;
    alignas(64) Real sa[D][kPairBlock] = {};
    alignas(64) Real sx[kXsph ? D : 1][kPairBlock] = {};
    for (const std::uint32_t* block = begin; block < end; block += kPairBlock) {
      std::int64_t index[kPairBlock];
      const std::uint32_t filled = blockIndices(block, static_cast<std::uint32_t>(end - block), index);
      const BlockVectors<D> xj(x, index), vj(vShown, index);
      const std::conditional_t<kMonaghan, NarrowBlock, NoSoundSpeeds> cj(c, index);
#pragma omp simd
      for (int l = 0; l < kPairBlock; ++l) {
        const LanePair<D> q = lanePair<D>(xi, xj, l, k);
        const std::int64_t j = index[l];
        const Real sp = -m[j] * (pi + pr[j]);
        Real vij[D];
        for (int d = 0; d < D; ++d) vij[d] = vi[d] - vj(d, l);
        const bool counts = laneCounts(l, filled, q.r2, support2);
        if constexpr (kViscosity == RowViscosity::kMorris) {
          // (MorrisViscosity::add's factor, in its order; r^2 as r r.)
          const Real rr = q.r * q.r, rhoj = rho[j];
          const Real f = m[j] * n * (rhoi + rhoj) / (rhoi * rhoj) * (rr * q.w) / (rr + 1e-4 * h * h);
          for (int d = 0; d < D; ++d) sa[d][l] += counts ? sp * q.g[d] + f * vij[d] : 0.0;
        } else if constexpr (kViscosity == RowViscosity::kLaplacian) {
          // (LaplacianViscosity::add's factor, in its order, with -2 (dW/dr)/r;
          // f (v_j - v_i) is exactly -(f v_ij).)
          const Real f = n * m[j] / (rhoi * rho[j]) * (-2 * q.w);
          for (int d = 0; d < D; ++d) sa[d][l] += counts ? sp * q.g[d] - f * vij[d] : 0.0;
        } else if constexpr (kViscosity == RowViscosity::kNone) {
          for (int d = 0; d < D; ++d) sa[d][l] += counts ? sp * q.g[d] : 0.0;
        } else {
          const Real vr = laneDot<D>(vij, q.rij);
          const Real mu = h * vr / (q.r * q.r + eps * h * h);
          const Real cBar = (ci + cj(l, j)) / 2, rhoBar = (rhoi + rho[j]) / 2;
          const Real Pi = (-a * cBar * mu + b * mu * mu) / rhoBar;
          const Real sv = -m[j] * Pi;
          const bool viscous = !(vr >= 0);  // (as MonaghanViscosity::add, which skips vr >= 0 only)
          const Real s = sp + (viscous ? sv : 0.0);
          for (int d = 0; d < D; ++d) sa[d][l] += counts ? s * q.g[d] : 0.0;  // (not 0 x a NaN of a skipped pair)
        }
        if constexpr (kXsph) {
          const Real f = 2 * m[j] / (rhoi + rho[j]) * k.laneW(q.r);  // (Xsph::add's factor, in its order)
          for (int d = 0; d < D; ++d) sx[d][l] += counts ? f * (vj(d, l) - vi[d]) : 0.0;
        }
      }
    }
    for (int d = 0; d < D; ++d) rates.a[d] += laneTotal(sa[d]);
    if constexpr (kXsph)
      for (int d = 0; d < D; ++d) rates.xsph[d] += laneTotal(sx[d]);
  }
};

}  // namespace sph
