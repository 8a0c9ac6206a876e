// Pass: the seed scheme's forces in one pair loop,
//   a_i = (F_p,i [+ F_v,i]) / rho_i [+ gravity]
// (seed_pressure.hpp, seed_viscosity.hpp; body forces in the epilogue).
// The seed's terms evaluate their own kernel factors from q, so the loop
// forms no grad W (NoPairKernel). With mu = 0 the viscosity is not in the
// pack; the choice is made once per evaluation, never per pair.
#pragma once

#include "sph/pair_loop.hpp"
#include "sph/passes/step_context.hpp"
#include "sph/terms/body_forces.hpp"
#include "sph/terms/colour_surface_tension.hpp"
#include "sph/terms/seed_pressure.hpp"
#include "sph/terms/seed_viscosity.hpp"

#include <optional>
#include <tuple>

namespace sph {

// a_i = rates.a + rates.F / rho_i + body forces [+ surface tension, from
// the colour field's pre-pass]; the other rates as the packs write them.
// The one epilogue of every force pass.
// Extra: more per-particle accelerations after the body forces (the
// optional terms', terms/optional_terms.hpp), add(i, P, a).
template <int D>
struct NoExtraForces {
  void add(std::size_t, const Particles<D>&, Vec<D>&) const {}
};

template <int D, unsigned Writes, class Extra = NoExtraForces<D>>
struct ForceEpilogue {
  const BodyForces<D>& bodies;
  Real xsphEpsilon = 0;
  bool densityRate = false;  // continuity density: write d rho/dt
  const ColourSurfaceTension<D>* surfaceTension = nullptr;  // none: one branch per particle
  Extra extra{};
  bool shiftSums = false;  // particle shifting's sums (terms/shifting_sums.hpp), with the particle's own V_i W(0)
  Real selfW = 0;          // W(0)

  void operator()(std::size_t i, Particles<D>& P, const PairRates<D>& r) const {
    Vec<D> a = r.a;
    if constexpr ((Writes & rates::kForceDensity) != 0) a += r.F / P.rho[i];
    bodies.add(i, P, a);
    extra.add(i, P, a);
    if (surfaceTension) a += surfaceTension->acceleration(i, P);
    P.a[i] = a;
    if constexpr ((Writes & rates::kDensityRate) != 0)
      if (densityRate) P.drho[i] = r.drho;
    if constexpr ((Writes & rates::kXsph) != 0)
      if (xsphEpsilon > 0) P.vXsph[i] = xsphEpsilon * r.xsph;
    if constexpr ((Writes & rates::kShifting) != 0)
      if (shiftSums) {
        P.shiftSum[i] = r.shiftSum + P.m[i] / P.rho[i] * selfW;
        P.shiftGrad[i] = r.shiftGrad;
      }
  }
};

// A particle's density rate alone: the wall particles' own (dynamic walls),
// and the fluid's in the density-rate pass (wcsph_forces.hpp).
template <int D>
struct DensityRateEpilogue {
  void operator()(std::size_t i, Particles<D>& P, const PairRates<D>& r) const { P.drho[i] = r.drho; }
};

template <int D>
struct SeedForcePass {
  static constexpr const char* name = "seed_forces";
  SeedPressure pressure;
  std::optional<SeedViscosity> viscosity;
  BodyForces<D> bodies;

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext&) const;
  // run() reads x, m, rho and p (and v with the viscosity, what the body
  // forces read); writes the fluid's a.
  FieldAccess fields(const StepContext&) const {
    return {fieldBits(kFieldX, kFieldM, kFieldRho, kFieldP) | (viscosity ? fieldBit(kFieldV) : 0u) | bodies.reads(),
            fieldBit(kFieldA)};
  }
};

// Defined here, instantiated once (src/instantiate_*.cpp).
template <int D>
unsigned SeedForcePass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext&) const {
  auto loop = [&](const auto& pack) {
    using Pack = std::decay_t<decltype(pack)>;
    constexpr unsigned writes = PackTraits<Pack>::writes;
    return runPairLoop(P, neighbours, NoPairKernel{}, pressure.kernels.support(), pack, pack, std::tuple<>(),
                       ForceEpilogue<D, writes>{bodies}, DensityRateEpilogue<D>{});
  };
  const unsigned bits = viscosity ? loop(std::make_tuple(pressure, *viscosity)) : loop(std::make_tuple(pressure));
  return bits | bodies.bits();
}

extern template struct SeedForcePass<2>;
extern template struct SeedForcePass<3>;

}  // namespace sph
