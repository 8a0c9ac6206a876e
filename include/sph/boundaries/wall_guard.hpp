// Wall guard: the no-penetration condition at the surfaces of the wall
// particles (dummy, dynamic and repulsive walls), a last line of defence
// behind their SPH forces.
//
// Why it is needed. Dummy walls (Adami et al. 2012) push a fluid particle
// back with the pressure they extrapolate from it, p_w ~ p_f + rho_f g.r_wf,
// and the pressure term pushes only where the kernel sums are lopsided. A
// particle thrown alone at a flat wall is held (its continuity density
// rises against the wall particles), but two flows get through (measured,
// with `wall_guard = false`): fluid coming over a convex corner in a splash,
// at p ~ 0 (cases/dam_break_obstacle.case: a splash particle falling onto
// the floor passes it at t = 0.69 s; SPHERIC Test 2's box at 0.6 s, measured
// before the change below), and, until the density diffusion read
// max(rho, rho0) under clamped pressures (terms/density_diffusion.hpp), the
// first fluid layer settling onto the wall after impacts (the dam break in
// a closed tank went through the floor at 1.68 s; it now runs to 3 s
// without the guard). Dynamic walls (Crespo et al. 2007) and
// repulsive walls fail in the same places. DualSPHysics removes such
// particles from the run ("excluded particles"); sph keeps them in, which
// conserves mass.
//
// What it does. Right after its position update (integrator_support.hpp,
// like the reflecting walls), a fluid particle that has crossed a wall
// surface by a depth d is put back to d in front of it (mirrored: two
// particles pushed into a corner do not land on one point) and loses the
// part of its velocity (integer-time and half-step) that takes it into the
// wall, relative to the wall's own velocity (an inelastic, frictionless
// contact: the tangential velocity is kept):
//
//   x_n <- 2 x_wall - x_n,   v_n <- u_n   where (v - u) . n_out > 0
//
// The surfaces are those the wall particles are built behind
// (wall_particles.hpp): the faces of the domain box [lo, hi] (not along a
// periodic axis, not the top without a lid) and the faces of each obstacle
// box (a particle inside one leaves through its nearest face); a paddle's
// box moves with it. A particle that stays in the fluid region is not
// touched, so a flow whose wall forces hold every particle runs exactly as
// without the guard. Every action is counted (the run's summary and
// run.json: `wall_guard_actions`), so a run says how often it was needed.
// `wall_guard = false` turns it off (the stability atlas's leakage map
// measures the bare boundary that way).
#pragma once

#include "sph/particles.hpp"

#include <limits>
#include <vector>

namespace sph {

template <int D>
struct WallGuard {
  using Box = AxisBox<D>;
  // The fluid region: a face at +-infinity has no wall (periodic axis, open top).
  Vec<D> lo = Vec<D>::Constant(-std::numeric_limits<Real>::infinity());
  Vec<D> hi = Vec<D>::Constant(std::numeric_limits<Real>::infinity());
  std::vector<Box> obstacles;  // solid boxes, where they are at the start
  int paddle = -1;             // index in obstacles of the box that moves, -1: none
  Vec<D> paddleOffset = Vec<D>::Zero();    // its displacement from the start ...
  Vec<D> paddleVelocity = Vec<D>::Zero();  // ... and its velocity, at the end of the step

  // Particle i (a fluid particle) right after its position update; true if
  // the guard moved it.
  bool operator()(Particles<D>& P, std::size_t i) const {
    bool acted = false;
    Vec<D>& x = P.x[i];
    for (int d = 0; d < D; ++d) {
      if (x[d] < lo[d]) {
        x[d] = 2 * lo[d] - x[d];
        stopInto(P, i, d, -1, 0);
        acted = true;
      } else if (x[d] > hi[d]) {
        x[d] = 2 * hi[d] - x[d];
        stopInto(P, i, d, +1, 0);
        acted = true;
      }
    }
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
      const bool moving = static_cast<int>(k) == paddle;
      const Vec<D> blo = moving ? Vec<D>(obstacles[k].lo + paddleOffset) : obstacles[k].lo;
      const Vec<D> bhi = moving ? Vec<D>(obstacles[k].hi + paddleOffset) : obstacles[k].hi;
      if (!((x.array() > blo.array()).all() && (x.array() < bhi.array()).all())) continue;
      // Out through the nearest face that touches fluid (not one lying on
      // a wall of the domain, as a box's bottom on the floor); its outward
      // normal points into the fluid.
      int face = 0, side = -1;
      Real depth = std::numeric_limits<Real>::infinity();
      for (int d = 0; d < D; ++d) {
        if (blo[d] > lo[d] && x[d] - blo[d] < depth) depth = x[d] - blo[d], face = d, side = -1;
        if (bhi[d] < hi[d] && bhi[d] - x[d] < depth) depth = bhi[d] - x[d], face = d, side = +1;
      }
      if (depth == std::numeric_limits<Real>::infinity()) continue;  // a box filling the domain: no fluid face
      x[face] = 2 * (side < 0 ? blo[face] : bhi[face]) - x[face];
      // Seen from the fluid, the wall's outward direction (into the solid) is -side.
      stopInto(P, i, face, -side, moving ? paddleVelocity[face] : 0);
      acted = true;
    }
    return acted;
  }

 private:
  // Along axis d, `into` = +1 if the wall lies towards +d from the fluid;
  // u: the wall's velocity along d.
  static void stopInto(Particles<D>& P, std::size_t i, int d, int into, Real u) {
    if ((P.v[i][d] - u) * into > 0) P.v[i][d] = u;
    if (!P.vHalf.empty() && (P.vHalf[i][d] - u) * into > 0) P.vHalf[i][d] = u;
    if (!P.vPrev.empty() && (P.vPrev[i][d] - u) * into > 0) P.vPrev[i][d] = u;
  }
};

}  // namespace sph
