// Repulsive wall particles: the soft repulsive force of seed document 004
// (after Liu et al. 2012; Chalk et al. 2020), for one layer of wall particles
// on the wall at spacing dx/2. On a fluid particle i, from its wall
// neighbours j:
//
//   a_i += sum_j 0.01 c^2 chi(r) f(gamma) r_ij / r^2,     r = |r_ij|, r_ij = x_i - x_j
//   chi = 1 - r / (1.5 dx)  for r < 1.5 dx, else 0
//   gamma = r / (0.75 h)
//   f = 2/3 (0 < gamma <= 2/3),  2 gamma - 1.5 gamma^2 (2/3 < gamma <= 1),
//       0.5 (2 - gamma)^2 (1 < gamma < 2),  0 (gamma >= 2)
//
// with c the reference sound speed and dx the fluid spacing (h_ij = h: one
// smoothing length for all particles). The force is an acceleration and
// pushes straight away from each wall particle. Repulsive wall particles take
// no part in the SPH sums (density, pressure, viscosity): near a wall the
// fluid sees a free surface, held only by this force. Its pass, which
// applies it: passes/wall_passes.hpp (RepulsiveWallsPass).
#pragma once

#include "sph/types.hpp"

namespace sph {

struct RepulsiveForce {
  Real c2;       // c^2
  Real dx, h;

  Real f(Real gamma) const {
    if (gamma <= 0 || gamma >= 2) return 0;
    if (gamma <= 2.0 / 3) return 2.0 / 3;
    if (gamma <= 1) return 2 * gamma - 1.5 * gamma * gamma;
    return 0.5 * (2 - gamma) * (2 - gamma);
  }

  // The acceleration factor s with a_i += s r_ij.
  Real factor(Real r) const {
    const Real range = 1.5 * dx;
    if (r >= range || r <= 0) return 0;
    const Real chi = 1 - r / range;
    return 0.01 * c2 * chi * f(r / (0.75 * h)) / (r * r);
  }
};

}  // namespace sph
