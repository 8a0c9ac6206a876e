// Passes of the wall-particle boundaries (boundaries/ has each method's
// equations and source):
//   AdamiWallsPass       dummy walls: wall p, rho, vWall from the fluid,
//                        before the forces (dummy_adami2012.hpp)
//   RepulsiveWallsPass   repulsive walls: their force, after the forces
//                        (repulsive_liu2012.hpp)
//   DynamicWallVelocityPass  dynamic walls: the velocity they show the
//                        viscous term is their own, vWall = v (only with a
//                        viscosity that reads vWall: laplacian, Morris)
// Otherwise dynamic walls (dynamic_crespo2007.hpp) need no pass of their
// own: the equation of state runs over them and the force pass gives them
// a density rate.
// The boundary types that add these passes (dummy_boundary.hpp,
// repulsive_boundary.hpp) are included wherever the method tables are, so
// this file declares the passes only: their run() is in src/wall_passes.cpp,
// with the extrapolation and the pair loop it walks the neighbours with.
#pragma once

#include "sph/boundaries/repulsive_liu2012.hpp"
#include "sph/fields.hpp"
#include "sph/kernels/kernels.hpp"
#include "sph/particles.hpp"
#include "sph/passes/step_context.hpp"
#include "sph/terms/equation_of_state_fwd.hpp"
#include "sph/wall_motion.hpp"

#include <memory>
#include <optional>

namespace sph {

template <int D>
class NeighbourList;  // neighbour_list.hpp

template <int D>
struct AdamiWallsPass {
  static constexpr const char* name = "adami_walls";
  Kernel<D> kernel;
  std::shared_ptr<const EquationOfState> eos;  // the model's (declared only here: its header rebuilds less)
  Vec<D> bodyAcceleration;  // g (fixed walls: a_w = 0)
  bool noSlip = true;
  Real rho0 = 1000;
  std::optional<SinusoidalWallMotion<D>> motion;  // a paddle's a_w (wall_motion.hpp)
  bool wallVelocity = true;  // extrapolate vWall (the viscosity reads it)

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const;
  // run() reads x, the fluid's p, rho and v and the wall's own v (its id:
  // a paddle's); writes the walls' p, rho, c and, when the viscosity reads
  // it, vWall.
  FieldAccess fields(const StepContext&) const {
    return {fieldBits(kFieldX, kFieldP, kFieldRho, kFieldV) | (motion ? fieldBit(kFieldId) : 0u),
            fieldBits(kFieldP, kFieldRho, kFieldC) | (wallVelocity ? fieldBit(kFieldVWall) : 0u)};
  }
};

template <int D>
struct DynamicWallVelocityPass {
  static constexpr const char* name = "dynamic_wall_velocity";

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const;
  // run() reads the walls' v; writes their vWall.
  FieldAccess fields(const StepContext&) const { return {fieldBit(kFieldV), fieldBit(kFieldVWall)}; }
};

template <int D>
struct RepulsiveWallsPass {
  static constexpr const char* name = "repulsive_walls";
  RepulsiveForce force;

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext&) const;
  // run() reads x (and adds to a): a += the walls' force.
  FieldAccess fields(const StepContext&) const { return {fieldBits(kFieldX, kFieldA), fieldBit(kFieldA)}; }
};

}  // namespace sph
