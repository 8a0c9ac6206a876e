// RadialGradient: the gradient of a radial kernel, written once for every
// kernel of the family (CRTP base; the kernel supplies dWdr):
//
//   F(r) = (dW/dr) / r,   grad_i W(|x_i - x_j|) = F(r) (x_i - x_j)
//
// the zero vector at r = 0 (a particle with itself, or two particles on the
// same spot, where every radial kernel's gradient vanishes by symmetry).
// F is what the pair loop forms for every pair (pair_loop.hpp). Its default
// here divides dW/dr by r (at r = 0 it takes r = 1e-9 h, so that
// Laplacian-type terms stay finite); a kernel whose dW/dr carries a factor
// r writes F without that division (dWdr_r: Wendland C2, Gaussian, the
// cubic spline's inner part): a division per pair is the slowest operation
// of the pair loop (its latency and the one divider it shares with sqrt).
#pragma once

#include "sph/types.hpp"

namespace sph {

template <class Kernel, int D>
struct RadialGradient {
  Vec<D> gradW(const Vec<D>& rij, Real r) const {
    if (r <= 0) return Vec<D>::Zero();
    return static_cast<const Kernel&>(*this).dWdr_r(r) * rij;
  }

  // F(r) = (dW/dr) / r (a kernel may hide this with a division-free form).
  Real dWdr_r(Real r) const {
    const Kernel& k = static_cast<const Kernel&>(*this);
    const Real s = r > 0 ? r : Real(1e-9) * k.h();
    return k.dWdr(s) / s;
  }
};

}  // namespace sph
