// The choices a wcsph model is made from, as the method tables of
// methods.hpp build them from a case's names: plain values, before any
// kernel, term or pass exists. The viscosity, the density treatment and its
// re-initialisation, the density diffusion's form and the curvature of the
// surface tension. Many files read them (the tables, the factory, the
// presets, the passes), so they live apart from the terms and the pair loop
// that act on them (terms/*.hpp, passes/wcsph_forces.hpp).
#pragma once

#include "sph/types.hpp"

#include <variant>

namespace sph {

// The viscosity (viscosity key): none, or the coefficients of one term
// (terms/laplacian_viscosity.hpp, monaghan_viscosity.hpp, morris_viscosity.hpp).
struct NoViscosity {};
struct LaplacianViscosityChoice {
  Real mu;
};
struct MonaghanViscosityChoice {
  Real alpha, beta;
};
struct MorrisViscosityChoice {
  Real nu;
};
using ViscosityChoice =
    std::variant<NoViscosity, LaplacianViscosityChoice, MonaghanViscosityChoice, MorrisViscosityChoice>;

// Whether the viscosity reads the velocity a wall particle shows the fluid
// (vWall: laplacian and Morris; Monaghan's reads the wall's own v).
inline bool readsWallVelocity(const ViscosityChoice& v) {
  return std::holds_alternative<LaplacianViscosityChoice>(v) || std::holds_alternative<MorrisViscosityChoice>(v);
}

// How the density is found (density key).
enum class DensityTreatment { kSummation, kContinuity };

// Density re-initialisation every N steps (continuity density): none,
// Shepard (zeroth order) or MLS (first order, Colagrossi & Landrieu 2003).
enum class DensityReinit { kNone, kShepard, kMls };

// The density diffusion's form and its delta (diffusion and delta keys),
// before the kernel and the EOS are known (terms/density_diffusion.hpp
// builds the term from it).
struct DensityDiffusionChoice {
  Real delta = 0;           // delta-SPH coefficient (0: off)
  bool hydrostatic = true;  // fourtakas (true) or molteni (false)
  const char* term = "density_diffusion_fourtakas";  // the term's name in run.json
};

// The curvature of the colour-field surface tension (surface_tension key;
// terms/colour_surface_tension.hpp).
enum class CurvatureMethod { kMuller, kMorris, kCorrected };

}  // namespace sph
