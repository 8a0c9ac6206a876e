// Summation density: rho_i = sum_j m_j W(|x_i - x_j|), self term included,
// for the fluid particles (walls in the neighbour sums), and the equation of
// state applied to each rho_i as soon as it is known (one pass, not two).
//
// Gather form: particle i writes only rho_i, p_i (and c_i), so the loop runs
// in parallel without atomics and gives the same result for any thread
// count. Kernel needs density(r2) and densityAtZero().
#pragma once

#include "sph/neighbour_list.hpp"
#include "sph/pair_loop.hpp"
#include "sph/particles.hpp"

namespace sph {

// wallsInSums = false leaves the wall neighbours out (repulsive walls);
// clampNegative sets p_i = max(p_i, 0).
template <int D, class Kernel, class Eos>
void computeSummationDensity(Particles<D>& P, const NeighbourList<D>& neighbours, const Kernel& W,
                             const Eos& eos, bool wallsInSums = true, bool clampNegative = false) {
  {
    const std::size_t n = P.fluidCount();
    const bool withSoundSpeed = !P.c.empty();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      Real rho_i = P.m[i] * W.densityAtZero();
      auto add = [&](std::uint32_t j, const Vec<D>& rij) { rho_i += P.m[j] * W.density(rij.squaredNorm()); };
      if (wallsInSums) forEachNeighbourSeparation(P, neighbours, i, add);
      else forEachNeighbourSeparationByKind(P, neighbours, i, add, [](std::uint32_t, const Vec<D>&) {});
      P.rho[i] = rho_i;
      const Real p = eos.pressure(rho_i);
      P.p[i] = clampNegative ? std::max(p, Real(0)) : p;
      if (withSoundSpeed) P.c[i] = eos.soundSpeed(rho_i);
    }
  }
}

}  // namespace sph
