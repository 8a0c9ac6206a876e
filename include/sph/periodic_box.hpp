// PeriodicBox<D>: periodic boundaries along a subset of the axes of the
// domain box [lo, hi).
//
// Along a periodic axis a of length L_a = hi_a - lo_a, a particle leaving
// through one face re-enters through the other (positions wrap into
// [lo_a, hi_a)), and a pair interacts through its nearest image, the
// minimum-image convention (Allen & Tildesley, "Computer Simulation of
// Liquids", 1987, sec. 1.5.2):
//
//   r_ij,a <- r_ij,a - L_a round(r_ij,a / L_a)
//
// With L_a >= 2 x support at most one image of j lies within the support of
// i, so the nearest image is the only one that interacts (validateCase
// refuses narrower periodic boxes). The separation is computed by one of two
// value types, chosen once per pass, never per pair:
//   FreeSpace       r_ij = x_i - x_j            (no periodic axis: as before,
//                                                bit for bit)
//   MinimumImage    r_ij = nearest image of x_i - x_j
// Positions are within one box length of [lo, hi) (they are wrapped at
// every stage), so |r_ij,a| < 1.5 L_a and one compare-and-shift per axis is
// the exact nearest image.
#pragma once

#include "sph/types.hpp"

namespace sph {

template <int D>
struct PeriodicBox {
  Vec<D> lo = Vec<D>::Zero();
  Vec<D> length = Vec<D>::Ones();
  unsigned axes = 0;  // bit a: axis a is periodic

  bool any() const { return axes != 0; }
  bool periodic(int a) const { return (axes >> a) & 1u; }

  // The nearest image of a separation.
  Vec<D> minimumImage(Vec<D> d) const {
    for (int a = 0; a < D; ++a) {
      if (!periodic(a)) continue;
      const Real L = length[a], half = L / 2;
      if (d[a] > half) d[a] -= L;
      else if (d[a] < -half) d[a] += L;
    }
    return d;
  }

  // Bring x back into [lo, hi) along the periodic axes (x is within one box
  // length of it: a particle moves less than a support per stage).
  void wrap(Vec<D>& x) const {
    for (int a = 0; a < D; ++a) {
      if (!periodic(a)) continue;
      const Real L = length[a], hi = lo[a] + L;
      if (x[a] >= hi) x[a] -= L;
      else if (x[a] < lo[a]) x[a] += L;
      // x a hair below lo by round-off would land on hi itself after += L.
      if (!(x[a] < hi)) x[a] = lo[a];
    }
  }
};

// r_ij = x_i - x_j, no periodic axis.
struct FreeSpace {
  template <int D>
  Vec<D> operator()(const Vec<D>& xi, const Vec<D>& xj) const {
    return xi - xj;
  }
};

// r_ij = the nearest image of x_i - x_j.
template <int D>
struct MinimumImage {
  PeriodicBox<D> box;
  Vec<D> operator()(const Vec<D>& xi, const Vec<D>& xj) const { return box.minimumImage(Vec<D>(xi - xj)); }
};

}  // namespace sph
