// Linear equation of state: p = k (rho - rho0).
//
// The seed scheme's EOS. Negative pressures (tension) are kept, as the seed
// defines them.
#pragma once

#include "sph/particles.hpp"

namespace sph {

struct LinearEos {
  Real k;     // stiffness [Pa / (kg m^-D)]
  Real rho0;  // rest density

  Real pressure(Real rho) const { return k * (rho - rho0); }
};

template <int D, class Eos>
void computePressure(Particles<D>& P, const Eos& eos) {
  const std::size_t n = P.size();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
  for (std::size_t i = 0; i < n; ++i) P.p[i] = eos.pressure(P.rho[i]);
}

}  // namespace sph
