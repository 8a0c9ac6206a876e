// CubicSpline: the M4 cubic B-spline kernel of Monaghan & Lattanzio (1985),
// as written in Monaghan, "Smoothed particle hydrodynamics", Rep. Prog. Phys.
// 68 (2005) 1703, eq. (2.6). Support 2h, q = r/h:
//
//   W(r) = sigma_D / h^D * { 1 - 3/2 q^2 + 3/4 q^3     0 <= q < 1
//                          { 1/4 (2 - q)^3             1 <= q < 2
//                          { 0                         q >= 2
//   sigma_2 = 10/(7 pi),  sigma_3 = 1/pi
//
//   dW/dr = sigma_D / h^(D+1) * { -3 q + 9/4 q^2     q < 1
//                               { -3/4 (2 - q)^2     1 <= q < 2
//
//   laplacian W = d2W/dr2 + (D-1)/r dW/dr
//               = sigma_D / h^(D+2) * { -3 D + 9/4 (D + 1) q                  q < 1
//                                     { 3/2 (2 - q) - 3/4 (D-1) (2 - q)^2 / q  1 <= q < 2
//     (finite at r = 0: -3 D sigma_D / h^(D+2); the second derivative jumps
//     at q = 1 and q = 2, where the spline is only C2 in W, C1 in dW/dr).
//
// Conventions: rij = x_i - x_j, r = |rij|; gradW = dW/dr rij / r (the
// gradient with respect to x_i), the zero vector at r = 0.
#pragma once

#include "sph/kernels/radial_gradient.hpp"
#include "sph/types.hpp"

#include <algorithm>
#include <cmath>

namespace sph {

template <int D>
struct CubicSpline : RadialGradient<CubicSpline<D>, D> {
  static_assert(D == 2 || D == 3, "CubicSpline is defined for D = 2 and 3");
  static constexpr int dim = D;
  static constexpr const char* name = "cubic_spline";

  explicit CubicSpline(Real h)
      : h_(h),
        support_(2 * h),
        invH_(1 / h),
        sigma_((D == 2 ? 10 / (7 * M_PI) : 1 / M_PI) / std::pow(h, D)),
        sigmaGrad_(sigma_ / h),
        sigmaLap_(sigma_ / (h * h)) {}

  Real h() const { return h_; }
  Real support() const { return support_; }

  // The cut-off tests r against support() itself, so W(support()) is exactly
  // 0 whatever the rounding of r / h; t is clamped for r just inside it.
  Real W(Real r) const {
    if (r >= support_) return 0;
    const Real q = r * invH_;
    if (q < 1) return sigma_ * (1 - q * q * (Real(1.5) - Real(0.75) * q));
    const Real t = std::max(2 - q, Real(0));
    return sigma_ * Real(0.25) * t * t * t;
  }

  Real dWdr(Real r) const {
    if (r >= support_) return 0;
    const Real q = r * invH_;
    if (q < 1) return sigmaGrad_ * q * (Real(2.25) * q - 3);
    const Real t = std::max(2 - q, Real(0));
    return -sigmaGrad_ * Real(0.75) * t * t;
  }

  // (dW/dr) / r: sigma_D / h^(D+2) (9/4 q - 3) inside q < 1, no division
  // there; dW/dr / r outside (radial_gradient.hpp).
  Real dWdr_r(Real r) const {
    if (r >= support_) return 0;
    const Real q = r * invH_;
    if (q < 1) return sigmaLap_ * (Real(2.25) * q - 3);
    return dWdr(r) / r;
  }

  // W and dWdr_r as the SIMD rows' lanes take them (pair_loop_blocks.hpp):
  // both parts formed in every lane and one selected, with the operations
  // of W and dWdr_r above, so the same values. (The branches' form would
  // leave the lanes' loop scalar: the compiler does not form the outer
  // part's division in a lane whose branch skips it.)
  Real laneW(Real r) const {
    const Real q = r * invH_;
    const Real t = std::max(2 - q, Real(0));
    const Real inner = sigma_ * (1 - q * q * (Real(1.5) - Real(0.75) * q)), outer = sigma_ * Real(0.25) * t * t * t;
    return r >= support_ ? 0 : q < 1 ? inner : outer;
  }
  Real laneDWdr_r(Real r) const {
    const Real q = r * invH_;
    const Real t = std::max(2 - q, Real(0));
    const Real inner = sigmaLap_ * (Real(2.25) * q - 3), outer = -sigmaGrad_ * Real(0.75) * t * t / r;
    return r >= support_ ? 0 : q < 1 ? inner : outer;
  }

  Real laplacianW(Real r) const {
    if (r >= support_) return 0;
    const Real q = r * invH_;
    if (q < 1) return sigmaLap_ * (-3 * D + Real(2.25) * (D + 1) * q);
    const Real t = std::max(2 - q, Real(0));
    return sigmaLap_ * (Real(1.5) * t - Real(0.75) * (D - 1) * t * t / q);
  }

 private:
  Real h_, support_, invH_;
  Real sigma_, sigmaGrad_, sigmaLap_;  // sigma_D / h^D, / h^(D+1), / h^(D+2)
};

}  // namespace sph
