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
// linear and tait take a background pressure p_b (key background_pressure,
// default 0), added to p: a flow without a free surface (a periodic box)
// then keeps p > 0 where the flow's own pressure is negative, which keeps
// the particles from clumping under tension (Morris, Fox & Zhu 1997; Adami,
// Hu & Adams 2013 use it in the transport velocity only). A constant p_b
// exerts no force on an even particle set; on a disordered one it pushes
// the particles apart, and it raises the pressure noise in proportion.
//
// Each is a small value type; a scene picks one by name and the choice is
// resolved once per step (std::visit), never per particle. density(p) is
// the inverse, for wall pressures (Adami 2012) and the hydrostatic start.
// Tait with a whole-number gamma (7, the usual value) raises to its power
// by multiplication, not pow().
#pragma once

#include "sph/particles.hpp"
#include "sph/terms/equation_of_state_fwd.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

namespace sph {

// x^e for a whole number e >= 0, by squaring.
inline Real wholePower(Real x, unsigned e) {
  Real r = 1;
  for (; e; e >>= 1, x *= x)
    if (e & 1u) r *= x;
  return r;
}

struct LinearEos {
  Real k, rho0, background = 0;
  Real pressure(Real rho) const { return k * (rho - rho0) + background; }
  Real soundSpeed(Real) const { return std::sqrt(k); }
  Real density(Real p) const { return rho0 + (p - background) / k; }
};

struct ClampedLinearEos {
  Real k, rho0;
  Real pressure(Real rho) const { return std::max(Real(0), k * (rho - rho0)); }
  Real soundSpeed(Real) const { return std::sqrt(k); }
  Real density(Real p) const { return rho0 + p / k; }
};

struct TaitEos {
  TaitEos(Real rho0_, Real c0_, Real gamma_, Real background_ = 0)
      : rho0(rho0_), c0(c0_), gamma(gamma_), background(background_), B(rho0_ * c0_ * c0_ / gamma_),
        whole(gamma_ == std::round(gamma_) && gamma_ <= 32), g(static_cast<unsigned>(std::lround(gamma_))) {}
  Real rho0, c0, gamma, background;
  Real B;       // rho0 c0^2 / gamma
  bool whole;   // gamma is a whole number: powers by multiplication
  unsigned g;

  Real pressure(Real rho) const {
    const Real x = rho / rho0;
    return B * ((whole ? wholePower(x, g) : std::pow(x, gamma)) - 1) + background;
  }
  // c = c0 (rho/rho0)^((gamma - 1)/2); an odd gamma gives a whole power.
  Real soundSpeed(Real rho) const {
    const Real x = rho / rho0;
    if (whole && g % 2 == 1) return c0 * wholePower(x, (g - 1) / 2);
    return c0 * std::pow(x, (gamma - 1) / 2);
  }
  // rho = rho0 (1 + (p - p_b) / B)^(1/gamma), for p - p_b > -B.
  Real density(Real p) const {
    return rho0 * std::pow(std::max(1 + (p - background) / B, Real(1e-12)), 1 / gamma);
  }
};

struct PolytropicEos {
  Real k, n;
  Real pressure(Real rho) const { return k * std::pow(rho, 1 + 1 / n); }
  Real soundSpeed(Real rho) const { return std::sqrt(k * (1 + 1 / n) * std::pow(rho, 1 / n)); }
  Real density(Real p) const { return std::pow(std::max(p, Real(0)) / k, n / (n + 1)); }
};

// The choice of one. A struct, not an alias of the variant, so that a
// header can declare it (equation_of_state_fwd.hpp): a call that looks up
// names by argument would complete a declared variant's alternatives.
struct EquationOfState : std::variant<LinearEos, ClampedLinearEos, TaitEos, PolytropicEos> {
  using variant::variant;
};

// p_i = p(rho_i), and c_i = c(rho_i) when the particles carry a sound
// speed, for particles [0, n); with `clampNegative` p_i = max(p_i, 0).
template <int D, class Eos>
void computePressure(Particles<D>& P, const Eos& eos, std::size_t n, bool clampNegative = false) {
  const bool withSoundSpeed = !P.c.empty();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
  for (std::size_t i = 0; i < n; ++i) {
    const Real p = eos.pressure(P.rho[i]);
    P.p[i] = clampNegative ? std::max(p, Real(0)) : p;
    if (withSoundSpeed) P.c[i] = eos.soundSpeed(P.rho[i]);
  }
}

}  // namespace sph
