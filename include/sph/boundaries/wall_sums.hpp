// WallSums: what the SPH sums take from the wall particles, one small value
// a boundary states (boundaries/boundary.hpp) and the passes read once per
// pass (summation density, the EOS, the CSPM and MLS moments, the Shepard
// sum, the force pass's pair loop). Never branched on per pair.
//
//   inSums        wall neighbours enter the sums: density, the corrections'
//                 moments and the force pass's pairs (false: repulsive
//                 walls, which act only through their own force)
//   densityRates  the wall particles carry d rho/dt by continuity and an EOS
//                 pressure (dynamic walls, Crespo et al. 2007)
#pragma once

namespace sph {

struct WallSums {
  bool inSums = true;
  bool densityRates = false;

  // The sums over fluid neighbours only (the density re-initialisations).
  static constexpr WallSums fluidOnly() { return WallSums{false, false}; }
};

}  // namespace sph
