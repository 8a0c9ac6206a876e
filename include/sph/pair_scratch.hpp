// The per-particle values a pair loop forms before its pairs (p/rho^2,
// m/rho), in arrays the particles lend.
#pragma once

#include "sph/particles.hpp"
#include "sph/types.hpp"

#include <cstddef>
#include <type_traits>
#include <vector>

namespace sph {

// Per-particle values the evaluators read at every pair, formed once per
// particle before the pairs in the loop's parallel region (every particle,
// ghosts included), so that no pair divides for them: p/rho^2 of the
// pressure term (symmetric_pressure.hpp) and the volume m/rho of the
// density diffusion (density_diffusion.hpp), and in a mixed-precision
// build the mass widened to Real for the SIMD rows (pair_loop_blocks.hpp),
// which would otherwise widen a block's 8 masses in scalar code at every
// block. A null array is not formed. The arrays are lent by the particles
// (pairArrays, below).
template <int D>
struct ParticlePrologue {
  Real* pOverRho2 = nullptr;
  Real* volume = nullptr;
  Real* mass = nullptr;
  bool active() const { return pOverRho2 || volume || mass; }
  void operator()(std::size_t i, const Particles<D>& P) const {
    if (pOverRho2) pOverRho2[i] = P.p[i] / (P.rho[i] * P.rho[i]);
    if (volume) volume[i] = P.m[i] / P.rho[i];
    if (mass) mass[i] = P.m[i];
  }
};

// The prologue of a pair loop over all of P's particles (ghosts included),
// with the arrays asked for in the particles' re-sort scratch
// (Particles::lendScratch): the re-sort needs it only inside permute(), a
// pass only between its prologue and its last pair, and every pass forms
// the arrays it reads before its pairs, so one buffer serves both (16 bytes
// per particle fewer in 2D and 3D than arrays of their own). `blocks`:
// the pass may run SIMD rows, which read the masses as Real (realMasses):
// a mixed-precision build lends an array for them too (the scratch holds D
// values per particle, so 2D's force pass of leap-frog, p/rho^2 and m, and
// its density-rate pass, m/rho and m, fit without growing it). Call it
// outside a parallel region; the arrays are valid until P's next permute()
// or lendScratch().
template <int D>
ParticlePrologue<D> pairArrays(Particles<D>& P, bool pressure, bool diffusion, bool blocks = false) {
  const std::size_t n = P.totalSize();
  const bool mass = blocks && !std::is_same_v<Narrow, Real>;
  const std::size_t count = (pressure ? n : 0) + (diffusion ? n : 0) + (mass ? n : 0);
  Real* base = count > 0 ? P.lendScratch(count) : nullptr;
  Real* next = base;
  auto take = [&](bool wanted) {
    Real* array = wanted ? next : nullptr;
    if (wanted) next += n;
    return array;
  };
  ParticlePrologue<D> prologue;
  prologue.pOverRho2 = take(pressure);
  prologue.volume = take(diffusion);
  prologue.mass = take(mass);
  return prologue;
}

// The masses as Real, as the SIMD rows read them: the particles' own in a
// double build, the prologue's widened copy in a mixed-precision one (null
// unless pairArrays was asked for blocks).
template <int D>
const Real* realMasses(const Particles<D>& P, const ParticlePrologue<D>& prologue) {
  if constexpr (std::is_same_v<Narrow, Real>)
    return P.m.data();
  else
    return prologue.mass;
}

}  // namespace sph
