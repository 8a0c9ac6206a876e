// Equations of state p(rho) and the sound speed c = sqrt(dp/drho).
//
//   linear           p = k (rho - rho0)                      c^2 = k
//   linear_clamped   p = max(0, k (rho - rho0))              (no tension: avoids the
//                                                             tensile instability at free
//                                                             surfaces, Monaghan 2000)
//   tait             p = rho0 c0^2 / gamma ((rho/rho0)^gamma - 1)   (Batchelor 1967;
//                    Monaghan 1994), c^2 = c0^2 (rho/rho0)^(gamma - 1)
//   polytropic       p = k rho^(1 + 1/n)                     c^2 = k (1 + 1/n) rho^(1/n)
//                    (the toy star; Monaghan & Price 2004)
//
// Each is a small value type; a scene picks one by name and the choice is
// resolved once per step (std::visit), never per particle.
#pragma once

#include "sph/particles.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

namespace sph {

struct LinearEos {
  Real k, rho0;
  Real pressure(Real rho) const { return k * (rho - rho0); }
  Real soundSpeed(Real) const { return std::sqrt(k); }
};

struct ClampedLinearEos {
  Real k, rho0;
  Real pressure(Real rho) const { return std::max(Real(0), k * (rho - rho0)); }
  Real soundSpeed(Real) const { return std::sqrt(k); }
};

struct TaitEos {
  Real rho0, c0, gamma;
  Real pressure(Real rho) const {
    return rho0 * c0 * c0 / gamma * (std::pow(rho / rho0, gamma) - 1);
  }
  Real soundSpeed(Real rho) const { return c0 * std::pow(rho / rho0, (gamma - 1) / 2); }
};

struct PolytropicEos {
  Real k, n;
  Real pressure(Real rho) const { return k * std::pow(rho, 1 + 1 / n); }
  Real soundSpeed(Real rho) const { return std::sqrt(k * (1 + 1 / n) * std::pow(rho, 1 / n)); }
};

using EquationOfState = std::variant<LinearEos, ClampedLinearEos, TaitEos, PolytropicEos>;

// p_i = p(rho_i), and c_i = c(rho_i) when the particles carry a sound
// speed, for particles [0, n).
template <int D, class Eos>
void computePressure(Particles<D>& P, const Eos& eos, std::size_t n) {
  const bool withSoundSpeed = !P.c.empty();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
  for (std::size_t i = 0; i < n; ++i) {
    P.p[i] = eos.pressure(P.rho[i]);
    if (withSoundSpeed) P.c[i] = eos.soundSpeed(P.rho[i]);
  }
}

}  // namespace sph
