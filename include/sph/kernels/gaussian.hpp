// Gaussian: the Gaussian kernel of Gingold & Monaghan (MNRAS 181 (1977) 375;
// Monaghan, Annu. Rev. Astron. Astrophys. 30 (1992) 543, eq. 2.5), truncated
// at 3h and renormalised so that the truncated kernel integrates to exactly 1.
// q = r/h:
//
//   W(r) = sigma_D / h^D exp(-q^2)       0 <= q < 3, else 0
//
// Normalisation: with S_D the area of the unit sphere (S_2 = 2 pi,
// S_3 = 4 pi), 1 = sigma_D S_D int_0^3 q^(D-1) exp(-q^2) dq, and
//   int_0^a q   exp(-q^2) dq = (1 - exp(-a^2)) / 2
//   int_0^a q^2 exp(-q^2) dq = sqrt(pi)/4 erf(a) - a/2 exp(-a^2)
// so, at a = 3,
//   sigma_2 = 1 / (pi (1 - e^-9))                                 = 0.318349173593...
//   sigma_3 = 1 / (pi^(3/2) erf(3) - 6 pi e^-9)                   = 0.179666148218...
// (the untruncated 1/pi and 1/pi^(3/2) are off by 1.2e-4 and 4.4e-4 relative).
//
//   dW/dr       = sigma_D / h^(D+1) (-2 q) exp(-q^2)
//   laplacian W = sigma_D / h^(D+2) (4 q^2 - 2 D) exp(-q^2)    (true Laplacian, q < 3)
//
// The truncation leaves a jump of sigma_D e^-9 / h^D (1.2e-4 of W(0)) at
// r = 3h. dW/dr, gradW and the Laplacian are those of the smooth part; the
// delta shell at the jump is dropped (it is isotropic, so sums of gradW over
// symmetric neighbourhoods still vanish).
//
// Conventions: rij = x_i - x_j, r = |rij|; gradW = dW/dr rij / r (the
// gradient with respect to x_i), the zero vector at r = 0.
#pragma once

#include "sph/kernels/radial_gradient.hpp"
#include "sph/types.hpp"

#include <cmath>

namespace sph {

template <int D>
struct Gaussian : RadialGradient<Gaussian<D>, D> {
  static_assert(D == 2 || D == 3, "Gaussian is defined for D = 2 and 3");
  static constexpr int dim = D;
  static constexpr const char* name = "gaussian";

  explicit Gaussian(Real h)
      : h_(h),
        support_(3 * h),
        invH_(1 / h),
        sigma_(sigmaD() / std::pow(h, D)),
        sigmaGrad_(sigma_ / h),
        sigmaLap_(sigma_ / (h * h)) {}

  Real h() const { return h_; }
  Real support() const { return support_; }

  // The cut-off tests r against support() itself, so W(support()) is exactly
  // 0 whatever the rounding of r / h.
  Real W(Real r) const {
    const Real q = r * invH_;
    return r < support_ ? sigma_ * std::exp(-q * q) : 0;
  }

  Real dWdr(Real r) const {
    const Real q = r * invH_;
    return r < support_ ? -2 * sigmaGrad_ * q * std::exp(-q * q) : 0;
  }

  // (dW/dr) / r = -2 sigma_D / h^(D+2) exp(-q^2): no division (radial_gradient.hpp).
  Real dWdr_r(Real r) const {
    const Real q = r * invH_;
    return r < support_ ? -2 * sigmaLap_ * std::exp(-q * q) : 0;
  }

  Real laplacianW(Real r) const {
    const Real q = r * invH_;
    return r < support_ ? sigmaLap_ * (4 * q * q - 2 * D) * std::exp(-q * q) : 0;
  }

 private:
  static Real sigmaD() {
    const Real e9 = std::exp(Real(-9));
    if constexpr (D == 2)
      return 1 / (M_PI * (1 - e9));
    else
      return 1 / (M_PI * std::sqrt(M_PI) * std::erf(Real(3)) - 6 * M_PI * e9);
  }

  Real h_, support_, invH_;
  Real sigma_, sigmaGrad_, sigmaLap_;  // sigma_D / h^D, / h^(D+1), / h^(D+2)
};

}  // namespace sph
