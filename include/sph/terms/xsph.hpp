// XSPH velocity smoothing (Monaghan 1989, "On the problem of penetration in
// particle methods", J. Comput. Phys. 82):
//
//   dx_i/dt = v_i + eps sum_j (m_j / rhobar_ij) (v_j - v_i) W(r_ij, h)
//
// The correction is stored in vXsph and added to the drift by the integrator;
// it moves particles with a locally averaged velocity and keeps momentum.
#pragma once

#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"

namespace sph {

template <int D, class Kernel>
void computeXsphCorrection(Particles<D>& P, const NeighbourList<D>& neighbours,
                           const Kernel& kernel, Real eps) {
  const std::size_t n = P.size();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
  for (std::size_t i = 0; i < n; ++i) {
    Vec<D> dv = Vec<D>::Zero();
    neighbours.forEach(i, [&](std::uint32_t j) {
      const Real r = (P.x[i] - P.x[j]).norm();
      dv += (2 * P.m[j] / (P.rho[i] + P.rho[j]) * kernel.W(r)) * (P.v[j] - P.v[i]);
    });
    P.vXsph[i] = eps * dv;
  }
}

}  // namespace sph
