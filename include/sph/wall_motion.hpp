// Prescribed wall motion: the wall particles of one obstacle (a paddle or
// a piston wave maker) move rigidly with
//
//   d(t) = A sin(2 pi t / T),   u_w = d'(t),   a_w = d''(t)
//
// (A the amplitude vector, T the period: DualSPHysics' sinusoidal
// rectilinear motion). The particles are found by their id, which the
// sort keeps: the obstacle's particles are one contiguous range of ids.
// Each step moves them from d(t_n) to d(t_n+1) before the step's
// evaluations and gives them u_w and a_w at t_n+1; the wall passes read
// u_w (Adami's 2 u_w - v~, the continuity term) and a_w (Adami's pressure
// extrapolation, (g - a_w) . r). For leap-frog and symplectic Euler, whose
// one force evaluation is at t_n+1, this is exact there; their density-rate
// pass (the fluid at t_n+1/2 or t_n) and RK4's intermediate stages see the
// wall at t_n+1 too (first order in the wall's position near the paddle;
// the wave-paddle height is within 4% of Biesel's theory with it).
// The motion starts at t = 0 with u_w = A 2 pi / T: an impulsive start, as
// a piston started from rest at full speed.
#pragma once

#include "sph/particles.hpp"

#include <cmath>
#include <cstdint>

namespace sph {

template <int D>
struct SinusoidalWallMotion {
  std::int64_t firstId = 0, endId = 0;  // the moving particles: firstId <= id < endId
  Vec<D> amplitude = Vec<D>::Zero();
  Real period = 1;

  Real omega() const { return 2 * std::acos(Real(-1)) / period; }
  Vec<D> displacement(Real t) const { return amplitude * std::sin(omega() * t); }
  Vec<D> velocity(Real t) const { return amplitude * (omega() * std::cos(omega() * t)); }
  Vec<D> acceleration(Real t) const { return amplitude * (-omega() * omega() * std::sin(omega() * t)); }
  bool moves(std::int64_t id) const { return id >= firstId && id < endId; }

  // Move the wall particles from their place at time `from` to `to`.
  void advance(Particles<D>& P, Real from, Real to) const {
    const Vec<D> step = displacement(to) - displacement(from), u = velocity(to);
    const IndexRange walls = P.range(ParticleRange::kWalls);
    for (std::size_t i = walls.begin; i < walls.end; ++i)
      if (moves(P.id[i])) {
        P.x[i] += step;
        P.v[i] = u;
      }
  }
};

}  // namespace sph
