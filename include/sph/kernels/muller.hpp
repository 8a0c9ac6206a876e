// Muller: the kernel set of Mueller, Charypar & Gross, "Particle-based fluid
// simulation for interactive applications", SCA 2003, section 3.5 and eqs.
// (20)-(22). Support h (h is the support radius here, not half of it), r < h:
//
//   W          = poly6      3D: 315/(64 pi h^9) (h^2 - r^2)^3
//                           2D:   4/(pi h^8)     (h^2 - r^2)^3
//   dWdr,gradW = spiky      3D: W_s = 15/(pi h^6) (h - r)^3, dW_s/dr = -45/(pi h^6) (h - r)^2
//                           2D: W_s = 10/(pi h^5) (h - r)^3, dW_s/dr = -30/(pi h^5) (h - r)^2
//   laplacianW = viscosity  3D: lap W_v = 45/(pi h^6) (h - r)
//                           2D: lap W_v = 40/(pi h^5) (h - r)
//
// W, gradW and laplacianW come from three different kernels, as in the paper:
// gradW is NOT the gradient of W, and dWdr is the spiky derivative dW_s/dr,
// not d(poly6)/dr. spikyW and viscosityW expose the kernels that gradW and
// laplacianW differentiate. All three are normalised to integrate to 1 in D
// dimensions; the 2D constants are not in the paper and are derived here.
//
// poly6 and spiky in 2D: int_0^h (h^2 - r^2)^3 2 pi r dr = pi h^8 / 4 and
// int_0^h (h - r)^3 2 pi r dr = pi h^5 / 10.
//
// Viscosity kernel, q = r/h. 3D (paper, eq. 22):
//   W_v = 15/(2 pi h^3) (-q^3/2 + q^2 + 1/(2q) - 1),  lap W_v = 45/(pi h^6)(h - r).
// 2D: the 3D shape above, renormalised in 2D (10/(3 pi h^2)), does NOT have a
// linear Laplacian in 2D (it is 5/(3 pi h^4) (1 + 8 q^3 - 9 q^4)/q^3). The 2D
// kernel with the paper's properties (lap W_v = C (1 - q) / h^4, W_v(h) = 0,
// W_v'(h) = 0) solves (q f')' = C (q - q^2), i.e.
//   f = C (q^2/4 - q^3/9 - ln(q)/6 - 5/36),
// with int_0^1 f 2 pi q dq = C pi / 40, so C = 40/pi:
//   W_v = 10/(9 pi h^2) (9 q^2 - 4 q^3 - 6 ln q - 5),  lap W_v = 40/(pi h^5)(h - r).
// f' = -C (q - 1)^2 (2q + 1) / (6 q) <= 0, so W_v > 0 on (0, h). As in 3D,
// W_v is singular at r = 0 (log in 2D, 1/r in 3D; viscosityW(0) = +inf) and
// laplacianW is its Laplacian for r > 0 (the distributional Laplacian adds a
// negative point source at r = 0, irrelevant since pair terms skip i = j).
//
// Conventions: rij = x_i - x_j, r = |rij|; gradW = dWdr rij / r (the
// gradient of W_s with respect to x_i), the zero vector at r = 0.
#pragma once

#include "sph/kernels/radial_gradient.hpp"
#include "sph/types.hpp"

#include <algorithm>
#include <cmath>

namespace sph {

template <int D>
struct Muller : RadialGradient<Muller<D>, D> {
  static_assert(D == 2 || D == 3, "Muller is defined for D = 2 and 3");
  static constexpr int dim = D;
  static constexpr const char* name = "muller";

  explicit Muller(Real h)
      : h_(h),
        h2_(h * h),
        invH_(1 / h),
        cPoly6_(D == 2 ? 4 / (M_PI * std::pow(h, 8)) : 315 / (64 * M_PI * std::pow(h, 9))),
        cSpiky_(D == 2 ? 10 / (M_PI * std::pow(h, 5)) : 15 / (M_PI * std::pow(h, 6))),
        cViscosity_(D == 2 ? 10 / (9 * M_PI * h * h) : 15 / (2 * M_PI * h * h * h)),
        cLaplacian_(D == 2 ? 40 / (M_PI * std::pow(h, 5)) : 45 / (M_PI * std::pow(h, 6))) {}

  Real h() const { return h_; }
  Real support() const { return h_; }

  // poly6.
  Real W(Real r) const {
    if (r >= h_) return 0;
    const Real s = h2_ - r * r;
    return cPoly6_ * s * s * s;
  }

  // Derivative of the spiky kernel (see the header comment).
  Real dWdr(Real r) const {
    if (r >= h_) return 0;
    const Real s = h_ - r;
    return -3 * cSpiky_ * s * s;
  }

  // Laplacian of the viscosity kernel.
  Real laplacianW(Real r) const { return r < h_ ? cLaplacian_ * (h_ - r) : 0; }

  Real spikyW(Real r) const {
    if (r >= h_) return 0;
    const Real s = h_ - r;
    return cSpiky_ * s * s * s;
  }

  Real viscosityW(Real r) const {
    if (r >= h_) return 0;
    // Clamped at 0: near r = h the O(1) terms cancel to (1 - q)^3 and
    // rounding could leave a tiny negative value.
    const Real q = r * invH_;
    if constexpr (D == 2)
      return std::max(cViscosity_ * (q * q * (9 - 4 * q) - 6 * std::log(q) - 5), Real(0));
    else
      return std::max(cViscosity_ * (q * q * (1 - Real(0.5) * q) + Real(0.5) / q - 1), Real(0));
  }

 private:
  Real h_, h2_, invH_;
  Real cPoly6_, cSpiky_, cViscosity_, cLaplacian_;
};

}  // namespace sph
