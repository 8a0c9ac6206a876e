// Model "wcsph": weakly-compressible SPH composed by name from a kernel, an
// equation of state, a viscosity, body forces and XSPH.
//
//   rho_i = sum_j m_j W(r_ij, h)                               (self term included)
//   p_i   = EOS(rho_i)                                          (equation_of_state.hpp)
//   a_i   = - sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2) grad W     (symmetric_pressure.hpp)
//           + viscosity (none | laplacian | monaghan)
//           + body forces (gravity -g e_up, star -lambda x, damping -nu v)
//   dx_i/dt = v_i [+ XSPH correction]
// (Monaghan 1992; Monaghan 2005, "Smoothed particle hydrodynamics", Rep. Prog. Phys. 68.)
//
// Passes: summation density with the EOS, then the fused force pass. A
// viscosity set to none or a body force whose coefficient is zero is never
// constructed, and the arrays it would need (sound speed, XSPH correction)
// never allocated.
#pragma once

#include "sph/models/model.hpp"

#include <string>

namespace sph {

// Everything a wcsph model is made of, already resolved from names.
template <int D>
struct WcsphSpec {
  Kernel<D> kernel;
  EquationOfState eos;
  ViscosityChoice viscosity = NoViscosity{};
  Real restDensity = 1000;
  BodyForces<D> bodies;
  Real xsphEpsilon = 0;
};

template <int D>
Model<D> makeWcsph(const WcsphSpec<D>& s) {
  typename Model<D>::Info info;
  info.name = "wcsph";
  info.support = std::visit([](const auto& k) { return k.support(); }, s.kernel);
  info.smoothingLength = std::visit([](const auto& k) { return k.h(); }, s.kernel);
  info.restDensity = s.restDensity;
  info.eos = s.eos;
  info.bodies = s.bodies;
  info.termNames = {"summation_density", "equation_of_state", "symmetric_pressure"};
  if (const auto* l = std::get_if<LaplacianViscosityChoice>(&s.viscosity)) {
    info.kinematicViscosity = l->mu / s.restDensity;
    info.termNames.push_back("laplacian_viscosity");
  }
  if (std::holds_alternative<MonaghanViscosityChoice>(s.viscosity)) {
    info.needs |= fieldBit(kFieldC);
    info.termNames.push_back("monaghan_viscosity");
  }
  if (s.bodies.gravity) info.termNames.push_back("gravity");
  if (s.bodies.star) info.termNames.push_back("star_attraction");
  if (s.bodies.damping) info.termNames.push_back("damping");
  if (s.xsphEpsilon > 0) {
    info.needs |= fieldBit(kFieldVXsph);
    info.termNames.push_back("xsph");
  }
  const auto density = std::visit(
      [](const auto& k) { return DensityKernelChoice<D>(DensityKernel<std::decay_t<decltype(k)>>{k}); }, s.kernel);
  return Model<D>(info, {SummationDensityPass<D>{density, s.eos},
                         WcsphForcePass<D>{s.kernel, s.viscosity, s.bodies, s.xsphEpsilon}});
}

}  // namespace sph
