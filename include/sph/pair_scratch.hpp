// The per-particle values a pair loop forms before its pairs (p/rho^2,
// m/rho), and the arrays that hold them between runs.
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
// The arrays are a PairScratch's, sized to the particles (PairScratch::fit).
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

// The arrays of a ParticlePrologue, kept between runs (so the step loop does
// not allocate once they have grown to the particle count): the model's,
// shared by its passes (StepContext::pairScratch; each pass fills what it
// reads before its pairs), or a pass's own when run alone.
struct PairScratch {
  std::vector<Real> pOverRho2, volume;
  std::size_t bytesAllocated() const { return (pOverRho2.capacity() + volume.capacity()) * sizeof(Real); }
  // The prologue of a run over n particles (ghosts included): the arrays
  // asked for, sized to n.
  template <int D>
  ParticlePrologue<D> fit(std::size_t n, bool pressure, bool diffusion) {
    if (pressure && pOverRho2.size() < n) pOverRho2.resize(n);
    if (diffusion && volume.size() < n) volume.resize(n);
    return {pressure ? pOverRho2.data() : nullptr, diffusion ? volume.data() : nullptr};
  }
};

}  // namespace sph
