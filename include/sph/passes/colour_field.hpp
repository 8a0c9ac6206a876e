// Pass: the colour field's normal n = grad c and the curvature kappa of every
// fluid particle (terms/colour_surface_tension.hpp has the equations and
// sources), after the density and before the force pass, which turns them
// into the surface-tension force. Present only when surface_tension is on.
#pragma once

#include "sph/kernels/kernels.hpp"
#include "sph/particles.hpp"
#include "sph/passes/step_context.hpp"
#include "sph/terms/colour_surface_tension.hpp"

#include <variant>

namespace sph {

template <int D>
struct ColourFieldPass {
  static constexpr const char* name = "colour_field";
  Kernel<D> kernel;
  CurvatureMethod method = CurvatureMethod::kMorris;
  Real minNormal = 0;  // |n| > minNormal: a reliable normal
  bool twoPhase = false;  // a colour region was given: difference forms

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext&) const;
  // run() reads the fluid neighbours' x, m, rho and colour; writes the
  // fluid's colourNormal and curvature (the ghosts' normals and curvatures
  // it refreshes itself, between its loops).
  FieldAccess fields(const StepContext&) const {
    return {fieldBits(kFieldX, kFieldM, kFieldRho, kFieldColour), fieldBits(kFieldColourNormal, kFieldCurvature)};
  }
};

// Defined here, instantiated once (src/instantiate_*.cpp).
template <int D>
unsigned ColourFieldPass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext&) const {
  std::visit(
      [&](const auto& k) {
        computeColourField(P, neighbours, k, method, minNormal, twoPhase);
      },
      kernel);
  return term_bits::kColourField;
}

extern template struct ColourFieldPass<2>;
extern template struct ColourFieldPass<3>;

}  // namespace sph
