// Passes the scene runs at the start of every step, before the integrator
// (Scene::step), each followed by a refresh of the ghosts of what it wrote:
//   ShiftingPass     particle shifting, x_i += dr_i for the fluid
//                    (particle_shifting.hpp: Lind et al. 2012, Sun et al. 2017)
//   WallMotionPass   a paddle's prescribed motion, its particles moved from
//                    their place at the step's start to its end
//                    (wall_motion.hpp)
// They act on the state between two steps, with the neighbour list of the
// last evaluation; they are not part of an evaluation (the model's passes),
// so they report no term bits.
#pragma once

#include "sph/neighbour_list.hpp"
#include "sph/particle_shifting.hpp"
#include "sph/particles.hpp"
#include "sph/passes/step_context.hpp"
#include "sph/wall_motion.hpp"

namespace sph {

template <int D>
struct ShiftingPass {
  ParticleShifting<D> shifting;

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const {
    shifting.apply(P, neighbours, ctx.dt, ctx.shiftSumsGiven);
    return 0;
  }
  // run() reads x, m and rho of the particle and its neighbours and the
  // fluid's v (the largest speed), or, when the last evaluation left them,
  // the sums of grad C; writes the fluid's x.
  FieldAccess fields(const StepContext& ctx) const {
    const FieldSet sums = ctx.shiftSumsGiven ? fieldBits(kFieldShiftSum, kFieldShiftGrad) : 0u;
    return {fieldBits(kFieldX, kFieldM, kFieldRho, kFieldV) | sums, fieldBit(kFieldX)};
  }
};

template <int D>
struct WallMotionPass {
  SinusoidalWallMotion<D> motion;

  unsigned run(Particles<D>& P, const NeighbourList<D>&, const StepContext& ctx) const {
    motion.advance(P, ctx.start, ctx.time);
    return 0;
  }
  // run() reads the walls' id and x; writes the moving walls' x and v.
  FieldAccess fields(const StepContext&) const {
    return {fieldBits(kFieldId, kFieldX), fieldBits(kFieldX, kFieldV)};
  }
};

}  // namespace sph
