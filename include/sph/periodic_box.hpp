// PeriodicBox<D>: periodic boundaries along a subset of the axes of the
// domain box [lo, hi).
//
// Along a periodic axis a of length L_a = hi_a - lo_a, a particle leaving
// through one face re-enters through the other (positions wrap into
// [lo_a, hi_a) at every sort), and the particles near one face interact
// with those near the other through ghost particles (periodic_ghosts.hpp),
// so no pair ever needs a minimum image.
//
// minimumImage() is kept for what is not a pair of particles (a probe point
// and the particles around it) and for tests that check the ghosts against
// it:
//   r_a <- r_a - L_a round(r_a / L_a)
// (Allen & Tildesley, "Computer Simulation of Liquids", 1987, sec. 1.5.2),
// exact for |r_a| < 1.5 L_a with one compare-and-shift per axis.
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

}  // namespace sph
