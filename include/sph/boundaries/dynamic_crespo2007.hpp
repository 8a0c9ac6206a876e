// Dynamic boundary particles (Crespo, Gomez-Gesteira & Dalrymple 2007,
// Comput. Mater. Contin. 5; the boundary of DualSPHysics, Crespo et al.
// 2015, Comput. Phys. Commun. 187): wall particles that do not move but
// carry a density by the continuity equation from their fluid neighbours,
//
//   d rho_w / dt = sum_f m_f (v_w - v_f) . grad_w W_wf,
//
// and a pressure by the same equation of state as the fluid. A fluid
// particle that comes close compresses them, their pressure rises and the
// fluid's own pressure term pushes it back. They enter the fluid's
// pressure, viscosity and continuity terms like fluid particles, with their
// own (prescribed) velocity; no density diffusion, no XSPH.
//
// In the pass list (models/wcsph.hpp) this is: the EOS pass over walls too,
// and the wall-particle density rates of the force pass; the integrator then
// advances the walls' density with the fluid's. Known behaviour: the fluid
// stands off the wall by about one smoothing length, and the first fluid
// layer's pressure is a little noisy (Crespo et al. 2007).
#pragma once

#include "sph/boundaries/dummy_boundary.hpp"
#include "sph/boundaries/wall_particle_boundary.hpp"
#include "sph/passes/wall_passes.hpp"

namespace sph {

inline bool continuityDensity(const CaseConfig& c);  // methods.hpp

// Boundary "dynamic": the EOS pass runs over the walls and the force pass
// gives them a density rate (WallSums::densityRates); no pass of its own.
struct DynamicBoundary : WallParticleBoundary {
  static constexpr const char* name = "dynamic";
  static constexpr const char* summary =
      "dynamic boundary particles: density by continuity, pressure by the EOS (Crespo et al. 2007)";
  static constexpr WallSums kSums{true, true};
  static inline const std::vector<const char*> reads{"wall_layers", "wall_layers_override", "lid",         "wall_slip",
                                                     "wall_guard",  "obstacle_min",         "obstacle_max"};
  static void validate(const CaseConfig& c) {
    if (!continuityDensity(c))
      throw CaseError("boundary = \"dynamic\" needs density = \"continuity\" (dynamic wall particles carry a "
                      "density by the continuity equation)");
    validateWallLayers(c);
  }

  template <int D>
  static void beforeForces(BoundaryBuild<D>& b) {
    // The laplacian and Morris viscosities read the walls' velocity from
    // vWall: a dynamic wall's is its own.
    if (b.wallVelocity) {
      b.info.needs |= fieldBit(kFieldVWall);
      b.passes.push_back(makePass(DynamicWallVelocityPass<D>{}));
    }
    b.info.termNames.push_back("dynamic_walls_crespo2007");
  }
};

}  // namespace sph
