// Density diffusion ("delta-SPH") added to the continuity equation:
//
//   D_i = 2 delta h c0 sum_j V_j psi_ij (-r_ij . grad_i W) / (r_ij^2 + eta^2),
//   V_j = m_j / rho_j,  eta^2 = 0.01 h^2,  r_ij = x_i - x_j,
//
// molteni:    psi_ij = rho_j - rho_i               (Molteni & Colagrossi 2009,
//             Comput. Phys. Commun. 180, eq. 9)
// fourtakas:  psi_ij = (rho_j - rho_i) - (rho_j^H - rho_i^H), the density
//             difference less its hydrostatic part, so that a fluid at rest
//             in hydrostatic balance is left as it is (Fourtakas et al. 2019,
//             Comput. Fluids 190; the idea of Antuono et al. 2010, without its
//             renormalised gradients). The hydrostatic part is linearised,
//             rho_j^H - rho_i^H = -rho0 (g . r_ij) / c0^2 (exact for a
//             linear EOS, and for Tait to O(rho/rho0 - 1)).
// Fluid pairs only. With a density gradient from gravity the Molteni form
// diffuses mass upwards and a column sinks; the Fourtakas form does not.
//
// With negative pressures clamped (negative_pressure = clamp, or eos =
// linear_clamped) rho_i and rho_j above read max(rho, rho_c), rho_c the
// density of zero pressure: the density the equation of state reads. A splash's densities below rho_c
// carry no pressure, and diffusing them drew a particle's density away from
// what its packing gives, by up to 400 kg/m^3 in the obstacle dam break
// (docs/methods/boundaries.md, "What a splash does to a particle's
// density"). Unclamped, or against reflecting or repulsive walls (which do
// not fill the support of the fluid next to them: src/wcsph_model.cpp),
// rho_c = -inf and the form is the one above.
//
// The case chooses the form by name (diffusion key, methods.hpp) as a
// DensityDiffusionChoice; build() derives the term's constants from it.
#pragma once

#include "sph/models/wcsph_choices.hpp"
#include "sph/pair_loop.hpp"

#include <algorithm>
#include <limits>

namespace sph {

template <int D>
struct DensityDiffusion {
  static constexpr unsigned bit = term_bits::kDensityDiffusion;
  static constexpr unsigned writes = rates::kDensityRate;
  Real coefficient = 0;          // 2 delta h c0 (0: off)
  Real eta2 = 0;                 // 0.01 h^2
  Vec<D> hydrostatic = Vec<D>::Zero();  // rho0 g / c0^2 (fourtakas), zero (molteni)
  Real floor = -std::numeric_limits<Real>::infinity();  // rho_c: clamped pressures; -inf: not

  bool active() const { return coefficient > 0; }

  // The term of a choice: h the smoothing length, c0 the sound speed at
  // rho0, g the gravity vector (zero when there is none), zeroPressure the
  // density of zero pressure when pressures are clamped there (-inf: not).
  static DensityDiffusion build(const DensityDiffusionChoice& choice, Real h, Real c0, Real rho0, const Vec<D>& g,
                                Real zeroPressure = -std::numeric_limits<Real>::infinity()) {
    DensityDiffusion d;
    if (!(choice.delta > 0)) return d;
    d.coefficient = 2 * choice.delta * h * c0;
    d.eta2 = 0.01 * h * h;
    if (choice.hydrostatic) d.hydrostatic = rho0 / (c0 * c0) * g;
    d.floor = zeroPressure;
    return d;
  }

  // m/rho of every particle, formed before the pairs (pair_loop.hpp's
  // ParticlePrologue), or null: formed at each pair.
  const Real* volume = nullptr;

  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    if (coefficient == 0) return;
    const Real Vj = volume ? volume[c.j] : P.m[c.j] / P.rho[c.j];
    const Real psi = (std::max(P.rho[c.j], floor) - std::max(P.rho[c.i], floor)) + hydrostatic.dot(c.rij);
    r.drho += coefficient * Vj * psi * (-c.rij.dot(c.gradW)) / (c.r * c.r + eta2);
  }
};

}  // namespace sph
