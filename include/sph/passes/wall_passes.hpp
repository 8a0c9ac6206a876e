// Passes of the wall-particle boundaries (boundaries/ has each method's
// equations and source):
//   AdamiWallsPass       dummy walls: wall p, rho, vWall from the fluid,
//                        before the forces (dummy_adami2012.hpp)
//   RepulsiveWallsPass   repulsive walls: their force, after the forces
//                        (repulsive_liu2012.hpp)
// Dynamic walls (dynamic_crespo2007.hpp) need no pass of their own: the
// equation of state runs over them and the force pass gives them a density
// rate.
#pragma once

#include "sph/boundaries/dummy_adami2012.hpp"
#include "sph/boundaries/repulsive_liu2012.hpp"
#include "sph/kernels/kernels.hpp"
#include "sph/wall_motion.hpp"

#include <optional>

#include <variant>

namespace sph {

template <int D>
struct AdamiWallsPass {
  Kernel<D> kernel;
  EquationOfState eos;
  Vec<D> bodyAcceleration;  // g (fixed walls: a_w = 0)
  bool noSlip = true;
  Real rho0 = 1000;
  std::optional<SinusoidalWallMotion<D>> motion;  // a paddle's a_w (wall_motion.hpp)

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const;
  // run() reads x, the fluid's p, rho and v and the wall's own v (its id:
  // a paddle's); writes the walls' p, rho, vWall and c.
  FieldAccess fields(const StepContext&) const {
    return {fieldBits(kFieldX, kFieldP, kFieldRho, kFieldV) | (motion ? fieldBit(kFieldId) : 0u),
            fieldBits(kFieldP, kFieldRho, kFieldVWall, kFieldC)};
  }
};

// Defined here, instantiated once (src/instantiate_*.cpp).
template <int D>
unsigned AdamiWallsPass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const {
  const WallAcceleration<D> moving =
      motion ? WallAcceleration<D>{motion->firstId, motion->endId, motion->acceleration(ctx.time)}
             : WallAcceleration<D>{};
  std::visit(
      [&](const auto& k, const auto& e) {
        extrapolateToWalls(P, neighbours, k, e, bodyAcceleration, noSlip, rho0, moving);
      },
      kernel, eos);
  return term_bits::kAdamiWalls;
}

extern template struct AdamiWallsPass<2>;
extern template struct AdamiWallsPass<3>;

}  // namespace sph
