// WendlandC2: Wendland's C2 compactly supported function psi_{3,1}
// (H. Wendland, Adv. Comput. Math. 4 (1995) 389), scaled to support 2h as in
// DualSPHysics (Crespo et al., Comput. Phys. Commun. 187 (2015) 204, eq. 6).
// q = r/h:
//
//   W(r)  = sigma_D / h^D (1 - q/2)^4 (2 q + 1)            0 <= q < 2, else 0
//   sigma_2 = 7/(4 pi),  sigma_3 = 21/(16 pi)
//
//   dW/dr = sigma_D / h^(D+1) * (-5 q) (1 - q/2)^3
//   dW/dr / r = sigma_D / h^(D+2) * (-5) (1 - q/2)^3
//   d2W/dr2 = sigma_D / h^(D+2) * 5 (1 - q/2)^2 (2 q - 1)
//   laplacian W = d2W/dr2 + (D-1)/r dW/dr
//               = sigma_D / h^(D+2) * 5 (1 - q/2)^2 [(2 q - 1) - (D - 1)(1 - q/2)]
//     (finite at r = 0: -5 D sigma_D / h^(D+2)).
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
struct WendlandC2 : RadialGradient<WendlandC2<D>, D> {
  static_assert(D == 2 || D == 3, "WendlandC2 is defined for D = 2 and 3");
  static constexpr int dim = D;
  static constexpr const char* name = "wendland_c2";

  explicit WendlandC2(Real h)
      : h_(h),
        support_(2 * h),
        invH_(1 / h),
        sigma_((D == 2 ? 7 / (4 * M_PI) : 21 / (16 * M_PI)) / std::pow(h, D)),
        sigmaGrad_(sigma_ / h),
        sigmaLap_(sigma_ / (h * h)) {}

  Real h() const { return h_; }
  Real support() const { return support_; }

  // The cut-off tests r against support() itself, so W(support()) is exactly
  // 0 whatever the rounding of r / h; t is clamped for r just inside it.
  Real W(Real r) const {
    if (r >= support_) return 0;
    const Real q = r * invH_;
    const Real t = std::max(1 - Real(0.5) * q, Real(0)), t2 = t * t;
    return sigma_ * t2 * t2 * (2 * q + 1);
  }

  Real dWdr(Real r) const {
    if (r >= support_) return 0;
    const Real q = r * invH_;
    const Real t = std::max(1 - Real(0.5) * q, Real(0));
    return -5 * sigmaGrad_ * q * t * t * t;
  }

  // (dW/dr) / r = -5 sigma_D / h^(D+2) (1 - q/2)^3: no division (radial_gradient.hpp).
  Real dWdr_r(Real r) const {
    if (r >= support_) return 0;
    const Real t = std::max(1 - Real(0.5) * (r * invH_), Real(0));
    return -5 * sigmaLap_ * t * t * t;
  }

  // As the SIMD rows' lanes take them (pair_loop_blocks.hpp): W and dWdr_r
  // themselves, whose one branch the compiler forms per lane.
  Real laneW(Real r) const { return W(r); }
  Real laneDWdr_r(Real r) const { return dWdr_r(r); }

  Real laplacianW(Real r) const {
    if (r >= support_) return 0;
    const Real q = r * invH_;
    const Real t = std::max(1 - Real(0.5) * q, Real(0));
    return 5 * sigmaLap_ * t * t * ((2 * q - 1) - (D - 1) * t);
  }

 private:
  Real h_, support_, invH_;
  Real sigma_, sigmaGrad_, sigmaLap_;  // sigma_D / h^D, / h^(D+1), / h^(D+2)
};

}  // namespace sph
