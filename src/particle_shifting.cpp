// ParticleShifting<D>::apply (particle_shifting.hpp has the method and its
// sources), compiled for D = 2 and 3.
#include "sph/particle_shifting.hpp"

#include "sph/neighbour_list.hpp"
#include "sph/pair_loop.hpp"
#include "sph/terms/shifting_sums.hpp"

#include <algorithm>
#include <cmath>

namespace sph {

template <int D>
void ParticleShifting<D>::apply(Particles<D>& P, const NeighbourList<D>& neighbours, Real dt, bool sumsGiven) const {
  const std::size_t n = P.fluidCount();
  shift_.resize(n);
  std::visit(
      [&](const auto& W) {
        {
          const Real h = W.h();
          const Real invWdx = 1 / W.W(spacing_);
          const Real scale = coefficient_ * h * dt;
          // U over every MPI rank's fluid: reduced between two regions
          // (a collective call), else in the region's first loop.
          Real v2max = 0;
          const bool ranks = comm_.size > 1;
          if (ranks) {
#pragma omp parallel for schedule(static) reduction(max : v2max)
            for (std::size_t i = 0; i < n; ++i) v2max = std::max(v2max, P.v[i].squaredNorm());
            v2max = mpi::allMax(comm_, v2max);
          }
#pragma omp parallel
          {
            if (!ranks) {
#pragma omp for schedule(static) reduction(max : v2max)
              for (std::size_t i = 0; i < n; ++i) v2max = std::max(v2max, P.v[i].squaredNorm());
            }
            const Real speed = std::sqrt(v2max);
#pragma omp for schedule(static)
            for (std::size_t i = 0; i < n; ++i) {
              Vec<D> gradC = Vec<D>::Zero();
              Real sum = 0;
              if (sumsGiven) {
                sum = P.shiftSum[i];
                gradC = P.shiftGrad[i];
              } else {
                // Fluid neighbours (ghosts of fluid included) with their own
                // volume, wall ones with the rest volume m / rho0; the
                // particle's own term last, as the force pass's sums
                // (terms/shifting_sums.hpp) have it.
                auto add = [&](std::uint32_t j, const Vec<D>& rij, bool fluid) {
                  const Real r = rij.norm();
                  if (r <= 0) return;
                  const Real Vj = fluid ? P.m[j] / P.rho[j] : P.m[j] / rho0_;
                  addShiftingPair<D>(Vj, W.W(r), invWdx, W.gradW(rij, r), sum, gradC);
                };
                forEachNeighbourSeparationByKind(
                    P, neighbours, i, [&](std::uint32_t j, const Vec<D>& rij) { add(j, rij, true); },
                    [&](std::uint32_t j, const Vec<D>& rij) { add(j, rij, false); });
                sum += P.m[i] / P.rho[i] * W.W(0);
              }
              shift_[i] = sum < 0.9 ? Vec<D>::Zero() : Vec<D>(-scale * speed * gradC);
            }
#pragma omp for schedule(static)
            for (std::size_t i = 0; i < n; ++i) P.x[i] += shift_[i];
          }
        }
      },
      kernel_);
}

template class ParticleShifting<2>;
template class ParticleShifting<3>;

}  // namespace sph
