// Dummy wall particles: the generalised wall boundary condition of Adami,
// Hu & Adams 2012 (J. Comput. Phys. 231, 7057-7075, eqs. 22, 27, 28).
//
// Before the forces, every wall particle w takes from its fluid neighbours f
//   p_w     = (sum_f p_f W_wf + (g - a_w) . sum_f rho_f r_wf W_wf) / sum_f W_wf
//   rho_w   = EOS^-1(p_w)                       (the wall's density)
//   v~_w    = sum_f v_f W_wf / sum_f W_wf       (the fluid's velocity there)
//   vWall_w = 2 u_w - v~_w   (no-slip)   or   v~_w   (free-slip)
// with r_wf = x_w - x_f, g the body acceleration and u_w, a_w the wall's own
// velocity and acceleration (0 for a fixed wall). The walls then enter the
// fluid's pressure term with p_w, rho_w and its viscous term with vWall_w
// (the continuity term uses the wall's own velocity u_w). A wall particle
// with no fluid neighbour gets p = 0, rho = rho0, vWall = u_w. (vWall is
// only there when the viscosity reads it: laplacian and Morris.)
// A wall never pulls: p_w = max(p_w, 0). Tension extrapolated from a free
// surface next to a wall would otherwise glue fluid particles to it (and
// draw them into it); DualSPHysics keeps its boundary densities >= rho0
// for the same reason.
#pragma once

#include "sph/neighbour_walk.hpp"
#include "sph/passes/step_context.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "sph/terms/term_bits.hpp"

#include <algorithm>
#include <cstdint>
#include <tuple>

namespace sph {

// The wall particles with firstId <= id < endId accelerate with a (a
// moving paddle); the others are fixed (a_w = 0).
template <int D>
struct WallAcceleration {
  std::int64_t firstId = 0, endId = 0;
  Vec<D> a = Vec<D>::Zero();
};

// Kernel and Eos: a kernel and an EOS, or the variants of them (resolved
// once, by the walk).
template <int D, class Kernel, class Eos>
void extrapolateToWalls(Particles<D>& P, const NeighbourList<D>& neighbours, const Kernel& kernel, const Eos& eos,
                        const Vec<D>& bodyAcceleration, bool noSlip, Real rho0,
                        const WallAcceleration<D>& moving = {}) {
  const Vec<D> movingBody = bodyAcceleration - moving.a;
  const bool withSoundSpeed = !P.c.empty();
  const bool withWallVelocity = !P.vWall.empty();  // only the laplacian and Morris viscosities read it
  walkNeighbours(P, neighbours, P.range(ParticleRange::kWalls), std::tie(kernel, eos),
                 [&](std::size_t w, const NeighbourRow<D>& row, const auto& k, const auto& e) {
                   Real sumW = 0, sumPW = 0;
                   Vec<D> sumRhoRW = Vec<D>::Zero(), sumVW = Vec<D>::Zero();
                   row.forEach([&](std::uint32_t f, const Vec<D>& rwf) {
                     const Real W = k.W(rwf.norm());
                     sumW += W;
                     sumPW += P.p[f] * W;
                     sumRhoRW += (P.rho[f] * W) * rwf;
                     if (withWallVelocity) sumVW += W * P.v[f];
                   });
                   const Vec<D> uw = P.v[w];
                   if (sumW > 0) {
                     const bool accelerated = P.id[w] >= moving.firstId && P.id[w] < moving.endId;
                     // (The density from the pressure as computed, not as
                     // stored: a mixed-precision build stores p in float.)
                     const Real pw = std::max(
                         Real(0), (sumPW + (accelerated ? movingBody : bodyAcceleration).dot(sumRhoRW)) / sumW);
                     P.p[w] = pw;
                     P.rho[w] = e.density(pw);
                     if (withWallVelocity) {
                       const Vec<D> vFluid = sumVW / sumW;
                       P.vWall[w] = noSlip ? Vec<D>(2 * uw - vFluid) : vFluid;
                     }
                   } else {
                     P.p[w] = 0;
                     P.rho[w] = rho0;
                     if (withWallVelocity) P.vWall[w] = uw;
                   }
                   if (withSoundSpeed) P.c[w] = e.soundSpeed(P.rho[w]);
                 });
}

}  // namespace sph
