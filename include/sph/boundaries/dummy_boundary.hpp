// Boundary "dummy": layers of dummy wall particles whose pressure, density
// and velocity are extrapolated from the fluid before the forces (Adami, Hu
// & Adams 2012; the equations in dummy_adami2012.hpp). The walls enter every
// SPH sum; the wall guard holds what they let through. The wall keys shared
// by the wall-particle boundaries (wall_layers, lid, wall_guard, wall_slip)
// are declared here, their first user.
#pragma once

#include "sph/boundaries/wall_particle_boundary.hpp"
#include "sph/passes/wall_passes.hpp"

namespace sph {

inline std::vector<std::string> wallSlipNames() { return {"no_slip", "free_slip"}; }
// Whether the walls enter the viscous term (wall_slip = "no_slip").
inline bool noSlipWalls(const CaseConfig& c) { return c.wallSlip == wallSlipNames().front(); }

struct DummyBoundary : WallParticleBoundary {
  static constexpr const char* name = "dummy";
  static constexpr const char* summary =
      "dummy wall particles with pressure extrapolated from the fluid (Adami, Hu & Adams 2012)";
  static constexpr bool kWallDensityFromFluid = true;  // extrapolated at every evaluation
  static inline const std::vector<const char*> reads{"wall_layers",  "wall_layers_override", "lid",
                                                     "lid_velocity", "wall_slip",            "wall_guard",
                                                     "obstacle_min", "obstacle_max"};
  static std::vector<KeySpec> keys() {
    using G = KeyGroup;
    using C = CaseConfig;
    return {
        {"wall_layers", G::kPhysics, &C::wallLayers, "",
         "Layers of dummy or dynamic wall particles (0: as many as the kernel support needs)",
         key_range::count(0, 100), "as many as needed", nullptr},
        {"wall_layers_override", G::kPhysics, &C::wallLayersOverride, "",
         "Allow fewer wall layers than the support needs (the fluid then leaks; for tests of leakage)", {}, nullptr,
         nullptr},
        {"lid", G::kPhysics, &C::lid, "", "Wall particles on the top of the box too (a closed tank)", {}, nullptr,
         nullptr},
        {"wall_guard", G::kPhysics, &C::wallGuard, "",
         "Wall particles (dummy, dynamic, repulsive): a fluid particle that crosses a wall surface is put back onto "
         "it and loses its velocity into the wall (counted in the summary; --no-wall_guard: the bare boundary, "
         "which may leak)",
         {}, nullptr, nullptr},
        {"lid_velocity", G::kPhysics, &C::lidVelocity, "m/s",
         "The lid (lid = true, boundary dummy) slides with this constant velocity, D values along its plane (a "
         "Couette plate, a lid-driven cavity); its particles stay in place and show the fluid that velocity",
         key_range::within(-1e6, 1e6), "at rest", nullptr},
        {"wall_slip", G::kPhysics, &C::wallSlip, "", "Dummy and dynamic walls in the viscous term", {}, nullptr,
         wallSlipNames},
    };
  }
  static void validate(const CaseConfig& c) { validateWallLayers(c); }

  // Before the forces: p, rho and vWall of the walls from their fluid neighbours.
  template <int D>
  static void beforeForces(BoundaryBuild<D>& b) {
    if (b.wallVelocity) b.info.needs |= fieldBit(kFieldVWall);
    b.passes.push_back(
        makePass(AdamiWallsPass<D>{b.kernel, b.eos, b.g, b.noSlip, b.restDensity, b.wallMotion, b.wallVelocity}));
    b.info.termNames.push_back("dummy_walls_adami2012");
  }
};

}  // namespace sph
