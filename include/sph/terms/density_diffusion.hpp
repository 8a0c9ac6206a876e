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
// The case chooses the form by name (diffusion key, methods.hpp) as a
// DensityDiffusionChoice; build() derives the term's constants from it.
#pragma once

#include "sph/models/wcsph_choices.hpp"
#include "sph/pair_loop.hpp"

namespace sph {

template <int D>
struct DensityDiffusion {
  static constexpr unsigned bit = term_bits::kDensityDiffusion;
  static constexpr unsigned writes = rates::kDensityRate;
  Real coefficient = 0;          // 2 delta h c0 (0: off)
  Real eta2 = 0;                 // 0.01 h^2
  Vec<D> hydrostatic = Vec<D>::Zero();  // rho0 g / c0^2 (fourtakas), zero (molteni)

  bool active() const { return coefficient > 0; }

  // The term of a choice: h the smoothing length, c0 the sound speed at
  // rho0, g the gravity vector (zero when there is none).
  static DensityDiffusion build(const DensityDiffusionChoice& choice, Real h, Real c0, Real rho0, const Vec<D>& g) {
    DensityDiffusion d;
    if (!(choice.delta > 0)) return d;
    d.coefficient = 2 * choice.delta * h * c0;
    d.eta2 = 0.01 * h * h;
    if (choice.hydrostatic) d.hydrostatic = rho0 / (c0 * c0) * g;
    return d;
  }

  // m/rho of every particle, formed before the pairs (pair_loop.hpp's
  // ParticlePrologue), or null: formed at each pair.
  const Real* volume = nullptr;

  void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    if (coefficient == 0) return;
    const Real Vj = volume ? volume[c.j] : P.m[c.j] / P.rho[c.j];
    const Real psi = (P.rho[c.j] - P.rho[c.i]) + hydrostatic.dot(c.rij);
    r.drho += coefficient * Vj * psi * (-c.rij.dot(c.gradW)) / (c.r * c.r + eta2);
  }
};

}  // namespace sph
