// Summation density: rho_i = sum_j m_j W(|x_i - x_j|), self term included,
// for the fluid particles (walls in the neighbour sums), and the equation of
// state applied to each rho_i as soon as it is known (one pass, not two).
//
// Gather form: particle i writes only rho_i, p_i (and c_i), so the loop runs
// in parallel without atomics and gives the same result for any thread
// count (the loop: walkNeighbours, neighbour_walk.hpp). Kernel needs
// density(r2) and densityAtZero(). Wendland C2 and the cubic spline take
// SIMD blocks where they pay (passes/summation_density_blocks.hpp).
#pragma once

#include "sph/neighbour_walk.hpp"
#include "sph/passes/summation_density_blocks.hpp"
#include "sph/particles.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace sph {

// W(r) of a kernel of the family, as a function of r^2.
template <class K>
struct DensityKernel {
  K kernel;
  Real density(Real r2) const { return kernel.W(std::sqrt(r2)); }
  Real densityAtZero() const { return kernel.W(0); }
};

// A DensityKernel whose kernel the SIMD rows take (kRowKernel).
template <class W>
struct IsRowDensityKernel : std::false_type {};
template <class K>
struct IsRowDensityKernel<DensityKernel<K>> : std::bool_constant<kRowKernel<K>> {};

// rho_i by the scalar loop, in the list's order.
template <int D, class W>
[[gnu::always_inline]] inline Real summedDensity(const Particles<D>& P, const NeighbourRow<D>& row, const W& kernel,
                                                 std::size_t i, bool wallsInSums) {
  Real rho_i = P.m[i] * kernel.densityAtZero();
  row.forEachSummed(wallsInSums, [&](std::uint32_t j, const Vec<D>& rij) {
    rho_i += P.m[j] * kernel.density(rij.squaredNorm());
  });
  return rho_i;
}

// wallsInSums = false leaves the wall neighbours out (repulsive walls);
// clampNegative sets p_i = max(p_i, 0). Kernel and Eos: concrete types or
// their variants (resolved once, by the walk).
template <int D, class Kernel, class Eos>
void computeSummationDensity(Particles<D>& P, const NeighbourList<D>& neighbours, const Kernel& kernel,
                             const Eos& eos, bool wallsInSums = true, bool clampNegative = false) {
  const bool withSoundSpeed = !P.c.empty();
  const bool blocks = kPairBlocksPay && pairBlocksAllowed();
  walkNeighbours(P, neighbours, P.range(ParticleRange::kFluid), std::tie(kernel, eos),
                 [&](std::size_t i, const NeighbourRow<D>& row, const auto& W, const auto& e) {
                   // Wendland C2 and the cubic spline in SIMD blocks where they pay
                   // (summation_density_blocks.hpp: the same sum in another order).
                   const Real rho_i = [&] {
                     if constexpr (IsRowDensityKernel<std::decay_t<decltype(W)>>::value) {
                       if (blocks) {
                         const typename NeighbourList<D>::Row r = neighbours.row(i);
                         using K = decltype(W.kernel);
                         return SummationDensityRow<D, K>{P, W.kernel}(static_cast<std::uint32_t>(i), r.begin,
                                                                       wallsInSums ? r.end : r.walls);
                       }
                     }
                     return summedDensity(P, row, W, i, wallsInSums);
                   }();
                   P.rho[i] = rho_i;
                   const Real p = e.pressure(rho_i);
                   P.p[i] = clampNegative ? std::max(p, Real(0)) : p;
                   if (withSoundSpeed) P.c[i] = e.soundSpeed(rho_i);
                 });
}

}  // namespace sph
