// A boundary: how the walls of the domain act, stated in one place per
// boundary type (reflecting_boundary.hpp, dummy_boundary.hpp,
// dynamic_crespo2007.hpp, repulsive_boundary.hpp) and read by everything else
// through the value `Boundary` built from that type:
//
//   particles     whether it makes wall particles, and how (layers behind the
//                 wall surface, or one layer on it)
//   sums          what the SPH sums take from the wall particles (WallSums)
//   passes        the passes it adds before and after the fused force pass
//   constraint    what it does to a particle right after its position update
//                 (reflecting clamp, wall guard, nothing)
//   stateCheck    how the state check treats wall particles
//
// A boundary type B provides (defaults in NoWallsBoundary): name, summary,
// reads (the case keys it reads), keys() (the key rows it declares),
// validate(case), kParticles, kSums, kWallDensityFromFluid, and for each D
// beforeForces, afterForces, constraint and stateCheck. `describeBoundary<B>()`
// turns it into the value below: plain data and function pointers, called
// when the model and scene are built, never per pair (the passes read
// WallSums once per pass).
#pragma once

#include "sph/boundaries/damped_reflecting_walls.hpp"
#include "sph/boundaries/wall_guard.hpp"
#include "sph/boundaries/wall_sums.hpp"
#include "sph/case_config.hpp"
#include "sph/case_keys.hpp"
#include "sph/kernels/kernels.hpp"
#include "sph/models/model.hpp"
#include "sph/state_check.hpp"
#include "sph/wall_motion.hpp"

#include <optional>
#include <variant>
#include <vector>

namespace sph {

// Which wall particles a boundary makes (wall_particles.cpp builds them).
enum class WallLattice {
  kNone,       // none: the walls act on the fluid directly, or not at all
  kLayers,     // layers behind the wall surface, on the fluid lattice
  kOnSurface,  // one layer on the wall surface, at spacing dx/2
};

// The per-particle constraint right after a position update: none, the
// damped reflecting walls, or the wall guard (counted when it acts).
template <int D>
struct WallConstraint {
  std::variant<std::monostate, DampedReflectingWalls<D>, WallGuard<D>> rule;

  WallConstraint() = default;
  WallConstraint(std::nullopt_t) {}
  WallConstraint(const std::optional<DampedReflectingWalls<D>>& walls) {
    if (walls) rule = *walls;
  }
  WallConstraint(DampedReflectingWalls<D> walls) : rule(std::move(walls)) {}
  WallConstraint(WallGuard<D> guard) : rule(std::move(guard)) {}

  WallGuard<D>* guard() { return std::get_if<WallGuard<D>>(&rule); }
  const DampedReflectingWalls<D>* reflecting() const { return std::get_if<DampedReflectingWalls<D>>(&rule); }

  // Particle i after its position update; true if the guard moved it.
  bool operator()(Particles<D>& P, std::size_t i) const {
    if (const auto* w = std::get_if<DampedReflectingWalls<D>>(&rule)) {
      (*w)(P, i);
      return false;
    }
    if (const auto* g = std::get_if<WallGuard<D>>(&rule)) return (*g)(P, i);
    return false;
  }
};

// What a model is being built from, for a boundary's passes (wcsph:
// src/wcsph_model.cpp), and the model's pass list and Info it adds to.
template <int D>
struct BoundaryBuild {
  const Kernel<D>& kernel;
  std::shared_ptr<const EquationOfState> eos;  // the model's
  Real restDensity;
  bool noSlip;   // dummy/dynamic walls in the viscous term (wall_slip)
  bool wallVelocity;  // the viscosity reads the velocity a wall shows the fluid, vWall (laplacian, morris)
  Real spacing;  // the fluid's spacing dx
  const std::optional<SinusoidalWallMotion<D>>& wallMotion;  // a paddle
  Vec<D> g;      // the body acceleration
  Real c0;       // the reference sound speed
  Real h;        // the smoothing length
  PassList<D>& passes;
  typename Model<D>::Info& info;
};

// A boundary's steps for dimension D (each a no-op by default).
template <int D>
struct BoundaryHooks {
  void (*beforeForces)(BoundaryBuild<D>&) = [](BoundaryBuild<D>&) {};
  void (*afterForces)(BoundaryBuild<D>&) = [](BoundaryBuild<D>&) {};
  WallConstraint<D> (*constraint)(const ResolvedCase&) = [](const ResolvedCase&) { return WallConstraint<D>{}; };
  void (*stateCheck)(StateCheck<D>&, const ResolvedCase&) = [](StateCheck<D>&, const ResolvedCase&) {};
};

// A boundary as the model, the scene and the particle sources see it. A
// default-constructed one is "no walls" (walls = false).
struct Boundary {
  WallLattice particles = WallLattice::kNone;
  WallSums sums{};
  // The walls' density is extrapolated from the fluid at every evaluation
  // (dummy walls): a hydrostatic start leaves their masses at rho0 V.
  bool wallDensityFromFluid = false;
  BoundaryHooks<2> hooks2{};
  BoundaryHooks<3> hooks3{};

  bool wallParticles() const { return particles != WallLattice::kNone; }
  template <int D>
  const BoundaryHooks<D>& hooks() const {
    if constexpr (D == 2) return hooks2;
    else return hooks3;
  }
};

// The defaults of a boundary type: no particles, walls in the sums (there
// are none), no passes, no constraint, no state-check rule, no keys.
struct NoWallsBoundary {
  static constexpr WallLattice kParticles = WallLattice::kNone;
  static constexpr WallSums kSums{};
  static constexpr bool kWallDensityFromFluid = false;
  static inline const std::vector<const char*> reads{};
  static std::vector<KeySpec> keys() { return {}; }
  static void validate(const CaseConfig&) {}
  template <int D>
  static void beforeForces(BoundaryBuild<D>&) {}
  template <int D>
  static void afterForces(BoundaryBuild<D>&) {}
  template <int D>
  static WallConstraint<D> constraint(const ResolvedCase&) {
    return {};
  }
  template <int D>
  static void stateCheck(StateCheck<D>&, const ResolvedCase&) {}
};

template <class B, int D>
BoundaryHooks<D> boundaryHooks() {
  BoundaryHooks<D> h;
  h.beforeForces = &B::template beforeForces<D>;
  h.afterForces = &B::template afterForces<D>;
  h.constraint = &B::template constraint<D>;
  h.stateCheck = &B::template stateCheck<D>;
  return h;
}

// The value of boundary type B.
template <class B>
Boundary describeBoundary() {
  Boundary b;
  b.particles = B::kParticles;
  b.sums = B::kSums;
  b.wallDensityFromFluid = B::kWallDensityFromFluid;
  b.hooks2 = boundaryHooks<B, 2>();
  b.hooks3 = boundaryHooks<B, 3>();
  return b;
}

}  // namespace sph
