// RadialGradient: the gradient of a radial kernel, written once for every
// kernel of the family (CRTP base; the kernel supplies dWdr):
//
//   grad_i W(|x_i - x_j|) = dW/dr (x_i - x_j) / r,   the zero vector at r = 0
//
// (r = 0 is a particle with itself, or two particles on the same spot, where
// every radial kernel's gradient vanishes by symmetry).
#pragma once

#include "sph/types.hpp"

namespace sph {

template <class Kernel, int D>
struct RadialGradient {
  Vec<D> gradW(const Vec<D>& rij, Real r) const {
    if (r <= 0) return Vec<D>::Zero();
    return (static_cast<const Kernel&>(*this).dWdr(r) / r) * rij;
  }
};

}  // namespace sph
