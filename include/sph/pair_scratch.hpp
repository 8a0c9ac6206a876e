// The per-particle values a pair loop forms before its pairs (p/rho^2,
// m/rho), in arrays the particles lend.
#pragma once

#include "sph/particles.hpp"
#include "sph/types.hpp"

#include <cstddef>
#include <vector>

namespace sph {

// Per-particle values the evaluators read at every pair, formed once per
// particle before the pairs in the loop's parallel region (every particle,
// ghosts included), so that no pair divides for them: p/rho^2 of the
// pressure term (symmetric_pressure.hpp) and the volume m/rho of the
// density diffusion (density_diffusion.hpp). A null array is not formed.
// The arrays are lent by the particles (pairArrays, below).
template <int D>
struct ParticlePrologue {
  Real* pOverRho2 = nullptr;
  Real* volume = nullptr;
  bool active() const { return pOverRho2 || volume; }
  void operator()(std::size_t i, const Particles<D>& P) const {
    if (pOverRho2) pOverRho2[i] = P.p[i] / (P.rho[i] * P.rho[i]);
    if (volume) volume[i] = P.m[i] / P.rho[i];
  }
};

// The prologue of a pair loop over all of P's particles (ghosts included),
// with the arrays asked for in the particles' re-sort scratch
// (Particles::lendScratch): the re-sort needs it only inside permute(), a
// pass only between its prologue and its last pair, and every pass forms
// the arrays it reads before its pairs, so one buffer serves both (16 bytes
// per particle fewer in 2D and 3D than arrays of their own). Call it
// outside a parallel region; the arrays are valid until P's next permute()
// or lendScratch().
template <int D>
ParticlePrologue<D> pairArrays(Particles<D>& P, bool pressure, bool diffusion) {
  const std::size_t n = P.totalSize();
  const std::size_t count = (pressure ? n : 0) + (diffusion ? n : 0);
  Real* base = count > 0 ? P.lendScratch(count) : nullptr;
  return {pressure ? base : nullptr, diffusion ? base + (pressure ? n : 0) : nullptr};
}

}  // namespace sph
