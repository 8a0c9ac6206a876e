// SeedKernels: the three kernel factors of the seed 2D weakly-compressible
// scheme, with support radius h (q = r/h < 1).
//
//   density      W(r)      = 4/(pi h^2) (1 - q^2)^3
//   pressure     G(r) r_ij = -30/(pi h^3) r_ij (1 - q)^2 / q
//   viscosity    L(r)      = 40/(pi h^4) (1 - q)
//
// These are the seed document's constants, powers of h included, kept as
// written: they are the 2D poly6 / spiky / viscosity kernels of Mueller,
// Charypar & Gross (2003) up to the seed's own prefactors (the pressure factor
// carries h^3 where the normalised spiky gradient has h^4). Mass scaling to
// rho0 absorbs the density constant; the other two set the model's stiffness
// and viscosity as the seed defines them. A normalised kernel set is a
// separate model, not a change to this one.
#pragma once

#include "sph/types.hpp"

#include <cmath>

namespace sph {

struct SeedKernels {
  explicit SeedKernels(Real h)
      : h_(h),
        h2_(h * h),
        invH_(1 / h),
        cDensity_(4 / (M_PI * h * h)),
        cPressure_(-30 / (M_PI * h * h * h)),
        cViscosity_(40 / (M_PI * h * h * h * h)) {}

  Real support() const { return h_; }
  Real support2() const { return h2_; }

  // W as a function of r^2 (no square root needed for density).
  Real density(Real r2) const {
    const Real s = 1 - r2 / h2_;
    return r2 < h2_ ? cDensity_ * s * s * s : 0;
  }
  Real densityAtZero() const { return cDensity_; }

  // Scalar G with pressure-kernel vector G r_ij; q in (0, 1).
  Real pressureFactor(Real q) const { return cPressure_ * (1 - q) * (1 - q) / q; }

  Real viscosityLaplacian(Real q) const { return cViscosity_ * (1 - q); }

  Real q(Real r) const { return r * invH_; }

 private:
  Real h_, h2_, invH_;
  Real cDensity_, cPressure_, cViscosity_;
};

}  // namespace sph
