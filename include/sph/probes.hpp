// Probes: what a gauge in an experiment would record, sampled during a run.
//
//   point probe at x:  A(x) = sum_j A_j V_j W(|x - x_j|) / sum_j V_j W(|x - x_j|),
//                      V_j = m_j / rho_j, over the fluid particles (SPH
//                      interpolation with Shepard normalisation: a constant
//                      field is reproduced exactly, and a probe half in the
//                      water is not biased towards zero; Shepard 1968, as in
//                      Liu & Liu, Smoothed Particle Hydrodynamics, 2003, 4.4).
//                      A probe with sum_j V_j W < 0.1 sum over a full
//                      lattice is dry: its values are written as nan.
//                      probe_interpolation = plain: the sum without the
//                      normalisation, A(x) = sum_j A_j V_j W(|x - x_j|)
//                      (what an SPH sum reads: ~ half the value at a free
//                      surface or a wall, where the support is half empty).
//   water height at x: the highest fluid particle within dx of the gauge's
//                      vertical line, plus dx/2 (its top; the same rule as
//                      validation/observables.py), 0 when none is there.
//   front:             the furthest fluid particle along +x plus dx/2.
//
// In a periodic box the distance to a particle is its nearest image.
// The sums run over every fluid particle (O(N) per probe and sample): no
// neighbour search is needed, and a case without probes does nothing.
#pragma once

#include "sph/kernels/kernels.hpp"
#include "sph/particles.hpp"
#include "sph/periodic_box.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <variant>
#include <vector>

namespace sph {

template <int D>
struct ProbeValues {
  Real pressure = 0, density = 0;
  Vec<D> velocity = Vec<D>::Zero();
  bool wet = false;
};

template <int D>
ProbeValues<D> interpolateAt(const Particles<D>& P, const Kernel<D>& kernel, const Vec<D>& x, Real dryWeight,
                             const PeriodicBox<D>& box = {}, bool shepard = true) {
  return std::visit(
      [&](const auto& W) {
        ProbeValues<D> out;
        const Real support = W.support(), support2 = support * support;
        Real weight = 0;
        for (std::size_t j = 0; j < P.fluidCount(); ++j) {
          const Vec<D> r = box.minimumImage(Vec<D>(x - P.x[j]));
          const Real r2 = r.squaredNorm();
          if (r2 >= support2) continue;
          const Real w = P.m[j] / P.rho[j] * W.W(std::sqrt(r2));
          weight += w;
          out.pressure += w * P.p[j];
          out.density += w * P.rho[j];
          out.velocity += w * P.v[j];
        }
        out.wet = weight > dryWeight && weight > 0;
        if (out.wet && shepard) {
          out.pressure /= weight;
          out.density /= weight;
          out.velocity /= weight;
        }
        return out;
      },
      kernel);
}

// Height of the water above the gauge at horizontal position `at` (D - 1
// coordinates), measured from 0 along the vertical axis D - 1.
template <int D>
Real waterHeightAt(const Particles<D>& P, const Real* at, Real dx) {
  Real top = -std::numeric_limits<Real>::infinity();
  for (std::size_t j = 0; j < P.fluidCount(); ++j) {
    bool inside = true;
    for (int d = 0; d + 1 < D; ++d) inside &= std::abs(P.x[j][d] - at[d]) < dx;
    if (inside && P.x[j][D - 1] > top) top = P.x[j][D - 1];
  }
  return std::isfinite(top) ? top + dx / 2 : 0;
}

template <int D>
Real frontPosition(const Particles<D>& P, Real dx) {
  Real front = -std::numeric_limits<Real>::infinity();
  for (std::size_t j = 0; j < P.fluidCount(); ++j) front = std::max(front, P.x[j][0]);
  return std::isfinite(front) ? front + dx / 2 : std::numeric_limits<Real>::quiet_NaN();
}

}  // namespace sph
