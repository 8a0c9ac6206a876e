// Summation density: rho_i = sum_j m_j W(|x_i - x_j|), self term included,
// for the fluid particles (walls in the neighbour sums), and the equation of
// state applied to each rho_i as soon as it is known (one pass, not two).
//
// Gather form: particle i writes only rho_i, p_i (and c_i), so the loop runs
// in parallel without atomics and gives the same result for any thread
// count (the loop: walkNeighbours, neighbour_walk.hpp). Kernel needs
// density(r2) and densityAtZero().
#pragma once

#include "sph/neighbour_walk.hpp"
#include "sph/particles.hpp"

#include <algorithm>

namespace sph {

// wallsInSums = false leaves the wall neighbours out (repulsive walls);
// clampNegative sets p_i = max(p_i, 0). Kernel and Eos: concrete types or
// their variants (resolved once, by the walk).
template <int D, class Kernel, class Eos>
void computeSummationDensity(Particles<D>& P, const NeighbourList<D>& neighbours, const Kernel& kernel,
                             const Eos& eos, bool wallsInSums = true, bool clampNegative = false) {
  const bool withSoundSpeed = !P.c.empty();
  walkNeighbours(P, neighbours, P.range(ParticleRange::kFluid), std::tie(kernel, eos),
                 [&](std::size_t i, const NeighbourRow<D>& row, const auto& W, const auto& e) {
                   Real rho_i = P.m[i] * W.densityAtZero();
                   row.forEachSummed(wallsInSums, [&](std::uint32_t j, const Vec<D>& rij) {
                     rho_i += P.m[j] * W.density(rij.squaredNorm());
                   });
                   P.rho[i] = rho_i;
                   const Real p = e.pressure(rho_i);
                   P.p[i] = clampNegative ? std::max(p, Real(0)) : p;
                   if (withSoundSpeed) P.c[i] = e.soundSpeed(rho_i);
                 });
}

}  // namespace sph
