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
//   pressure sensor:   probe_radius = r > 0 makes each point probe a sensor
//                      of that radius lying on the wall face nearest to its
//                      point (of the domain box or an obstacle; the face's
//                      normal axis is the disc's): its pressure is the mean
//                      of the interpolated pressure above over n points
//                      spread evenly over the disc (3D: K = max(2,
//                      4 r / h) rings, ring k with 2k + 1 points on its
//                      mid-radius, each point standing for the same area,
//                      n = K^2; 2D: n = max(3, 8 r / h) points on a segment
//                      of length 2r along the face): points about h/4
//                      apart, whose mean is the centre. A dry point reads 0 (air, gauge
//                      pressure): a sensor half in the water reads the
//                      load on its wet half spread over its area, as a
//                      real transducer does. Density and velocity stay at
//                      the centre. The kernel already averages over ~h: a
//                      radius below h/2 changes little; choose r as the
//                      area the reading stands for (e.g. half the
//                      distance between neighbouring sensors).
//   time filter:       probe_window = T > 0 adds a column per sensor: the
//                      mean of its pressure samples over the last T seconds
//                      (t - T, t] (a moving average, trailing: it lags by
//                      T/2; an integrating transducer, or a sampler with
//                      an anti-alias filter of bandwidth ~1/T). It bounds
//                      the weakly compressible impact spike, a pulse of
//                      height ~rho0 c0 v and width ~h/c0, to its impulse
//                      over T, and leaves loads slower than T unchanged.
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
#include "sph/mpi/collectives.hpp"
#include "sph/particles.hpp"
#include "sph/periodic_box.hpp"

#include <cmath>
#include <limits>
#include <algorithm>
#include <string>
#include <utility>
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
                             const PeriodicBox<D>& box = {}, bool shepard = true, const mpi::Communicator& comm = {}) {
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
        if (comm.size > 1) {  // every rank's fluid: the sums reduced, then divided
          double sums[3 + D] = {weight, out.pressure, out.density};
          for (int d = 0; d < D; ++d) sums[3 + d] = out.velocity[d];
          mpi::allSum(comm, sums, 3 + D);
          weight = sums[0], out.pressure = sums[1], out.density = sums[2];
          for (int d = 0; d < D; ++d) out.velocity[d] = sums[3 + d];
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

// The points of a pressure sensor of radius r centred at x, on a plane
// normal to axis `normal` (see the header): n points of equal area.
template <int D>
std::vector<Vec<D>> sensorDiscPoints(const Vec<D>& x, int normal, Real radius, Real h) {
  std::vector<Vec<D>> out;
  if (!(radius > 0)) return {x};
  if constexpr (D == 2) {
    const int n = std::max(3, static_cast<int>(std::ceil(8 * radius / h)));
    const int along = 1 - normal;
    for (int i = 0; i < n; ++i) {
      Vec<D> p = x;
      p[along] += radius * (2 * (i + Real(0.5)) / n - 1);
      out.push_back(p);
    }
  } else {
    // K rings of width r / K; ring k holds 2k + 1 points evenly spaced on
    // its mid-radius (ring 0: the centre), so every point stands for the
    // same area pi (r / K)^2 and the points' mean is the centre.
    const int K = std::max(2, static_cast<int>(std::ceil(4 * radius / h)));
    const int a = (normal + 1) % 3, b = (normal + 2) % 3;
    for (int k = 0; k < K; ++k) {
      const int m = 2 * k + 1;
      const Real r = k == 0 ? 0 : radius * (k + Real(0.5)) / K;
      for (int i = 0; i < m; ++i) {
        const Real theta = 2 * Real(M_PI) * i / m;
        Vec<D> p = x;
        p[a] += r * std::cos(theta);
        p[b] += r * std::sin(theta);
        out.push_back(p);
      }
    }
  }
  return out;
}

// The normal axis of the wall face nearest to x among the faces of the
// boxes [lo_k, hi_k] (the domain's inner faces and the obstacles' outer
// ones; `faces` skips axes without walls, e.g. periodic ones): the distance
// from x to each face rectangle, the nearest wins.
template <int D>
int nearestFaceAxis(const Vec<D>& x, const std::vector<std::pair<Vec<D>, Vec<D>>>& boxes, unsigned skipAxes = 0) {
  Real best = std::numeric_limits<Real>::infinity();
  int axis = D - 1;
  for (const auto& [lo, hi] : boxes)
    for (int d = 0; d < D; ++d) {
      if ((skipAxes >> d) & 1u) continue;
      for (const Real plane : {lo[d], hi[d]}) {
        Real dist2 = (x[d] - plane) * (x[d] - plane);
        for (int e = 0; e < D; ++e)
          if (e != d) {
            const Real out = std::max({lo[e] - x[e], x[e] - hi[e], Real(0)});
            dist2 += out * out;
          }
        if (dist2 < best) best = dist2, axis = d;
      }
    }
  return axis;
}

// The area-averaged pressure over a sensor's points (dry points read 0);
// wet when any point is. Only the fluid particles within the support of
// some point are visited for each point.
template <int D>
ProbeValues<D> sensorAt(const Particles<D>& P, const Kernel<D>& kernel, const Vec<D>& centre,
                        const std::vector<Vec<D>>& points, Real radius, Real dryWeight,
                        const PeriodicBox<D>& box = {}, bool shepard = true, const mpi::Communicator& comm = {}) {
  ProbeValues<D> out = interpolateAt(P, kernel, centre, dryWeight, box, shepard, comm);
  if (points.size() <= 1) return out;
  const Real support = std::visit([](const auto& W) { return W.support(); }, kernel);
  const Real reach = support + radius;
  Particles<D> near;
  std::vector<std::size_t> idx;
  for (std::size_t j = 0; j < P.fluidCount(); ++j)
    if (box.minimumImage(Vec<D>(centre - P.x[j])).squaredNorm() < reach * reach) idx.push_back(j);
  near.resize(idx.size());
  for (std::size_t k = 0; k < idx.size(); ++k) {
    near.x[k] = P.x[idx[k]];
    near.m[k] = P.m[idx[k]];
    near.rho[k] = P.rho[idx[k]];
    near.p[k] = P.p[idx[k]];
    near.v[k] = P.v[idx[k]];
  }
  Real sum = 0;
  bool wet = false;
  for (const Vec<D>& x : points) {
    const ProbeValues<D> v = interpolateAt(near, kernel, x, dryWeight, box, shepard, comm);
    if (v.wet) sum += v.pressure, wet = true;
  }
  if (!out.wet && wet) {  // the centre is dry, part of the disc is wet
    out.density = std::numeric_limits<Real>::quiet_NaN();
    out.velocity = Vec<D>::Constant(std::numeric_limits<Real>::quiet_NaN());
  }
  out.pressure = sum / static_cast<Real>(points.size());
  out.wet = out.wet || wet;
  return out;
}

// Height of the water above the gauge at horizontal position `at` (D - 1
// coordinates), measured from 0 along the vertical axis D - 1.
template <int D>
Real waterHeightAt(const Particles<D>& P, const Real* at, Real dx, const mpi::Communicator& comm = {}) {
  Real top = -std::numeric_limits<Real>::infinity();
  for (std::size_t j = 0; j < P.fluidCount(); ++j) {
    bool inside = true;
    for (int d = 0; d + 1 < D; ++d) inside &= std::abs(P.x[j][d] - at[d]) < dx;
    if (inside && P.x[j][D - 1] > top) top = P.x[j][D - 1];
  }
  top = mpi::allMax(comm, top);
  return std::isfinite(top) ? top + dx / 2 : 0;
}

template <int D>
Real frontPosition(const Particles<D>& P, Real dx, const mpi::Communicator& comm = {}) {
  Real front = -std::numeric_limits<Real>::infinity();
  for (std::size_t j = 0; j < P.fluidCount(); ++j) front = std::max(front, P.x[j][0]);
  front = mpi::allMax(comm, front);
  return std::isfinite(front) ? front + dx / 2 : std::numeric_limits<Real>::quiet_NaN();
}

}  // namespace sph
