// Pass: the wcsph model's pair terms fused in one pair loop:
//   d rho_i/dt = continuity + density diffusion        (density = continuity)
//   a_i        = symmetric pressure [+ the optional pair terms]
//                + viscosity (none | laplacian | monaghan)
//                + body forces [+ the optional per-particle terms]
//                + surface tension (epilogue),
//   XSPH correction (when eps > 0).
// Fluid neighbours and wall neighbours (dummy or dynamic wall particles,
// with their p, rho and the velocity they show the fluid) go through the
// same terms, less the diffusion and XSPH; dynamic wall particles get their
// own density rate from their fluid neighbours in the same parallel region.
// The kernel and the viscosity are resolved once per evaluation with
// std::visit into one fully inlined loop; the pair loop forms grad W once
// per pair for all the terms. The terms that are on or off by a coefficient
// (continuity, diffusion, XSPH) are switched at run time: off, each is one
// predictable branch per pair, and the loop is compiled 4 kernels x 3
// viscosities times (no viscosity is the Laplacian one switched off, below),
// not 2^3 times more. With the CSPM gradient correction
// (cspm_correction.hpp; its L_i computed by the pass before this one) the
// pair loop hands the pressure term L_i grad W instead of grad W (the
// continuity term keeps grad W, so that the density follows the particles'
// packing: continuity_density.hpp); that choice too is a branch per pair,
// the same for every pair, not a second instantiation.
// The optional terms (terms/optional_terms.hpp: artificial pressure, linear
// damping, ...) come from their list: the pair terms' evaluators after the
// pressure term in the fluid-fluid pack, the per-particle terms in the
// epilogue; an inactive one is one predictable branch, not an instantiation.
// The water physics (Wendland C2 or the cubic spline, symmetric pressure
// and Monaghan's viscosity, the density rate computed apart, XSPH or not, nothing else in
// the pack), and the same with Morris', the Laplacian or no viscosity,
// take their pairs, fluid and wall, in SIMD blocks on a build for AVX2 or
// AVX-512 (force_blocks.hpp: the same accelerations up to the order of the
// sum).
#pragma once

#include "sph/boundaries/wall_sums.hpp"
#include "sph/kernels/kernels.hpp"
#include "sph/models/wcsph_choices.hpp"
#include "sph/pair_loop.hpp"
#include "sph/passes/cspm_correction.hpp"
#include "sph/passes/force_blocks.hpp"
#include "sph/passes/seed_forces.hpp"
#include "sph/passes/step_context.hpp"
#include "sph/terms/body_forces.hpp"
#include "sph/terms/continuity_density.hpp"
#include "sph/terms/density_diffusion.hpp"
#include "sph/terms/laplacian_viscosity.hpp"
#include "sph/terms/monaghan_viscosity.hpp"
#include "sph/terms/morris_viscosity.hpp"
#include "sph/terms/optional_terms.hpp"
#include "sph/terms/shifting_sums.hpp"
#include "sph/terms/symmetric_pressure.hpp"
#include "sph/terms/xsph.hpp"

#include <optional>
#include <tuple>
#include <type_traits>
#include <variant>

namespace sph {

// A viscosity evaluator that a flag switches off: not evaluated at all,
// one predictable branch per pair, and its bit not reported.
template <class E>
struct SwitchedViscosity : E {
  bool on = true;
  bool active() const { return on; }
  template <int D>
  [[gnu::always_inline]] void add(const Pair<D>& c, const Particles<D>& P, PairRates<D>& r) const {
    if (on) E::add(c, P, r);
  }
};

// The viscosity as the force loop is compiled for: no viscosity is the
// Laplacian one switched off, so that it shares that loop instead of being
// one of its own (4 kernels x 3 viscosities force loops, not x 4), with the
// same results, bit for bit, for a branch per pair.
struct SwitchedLaplacianChoice {
  LaplacianViscosityChoice laplacian;
  bool on;
};
using LoopViscosity = std::variant<SwitchedLaplacianChoice, MonaghanViscosityChoice, MorrisViscosityChoice>;
inline LoopViscosity loopViscosity(const ViscosityChoice& choice) {
  return std::visit(
      [](const auto& v) -> LoopViscosity {
        using V = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<V, NoViscosity>) return SwitchedLaplacianChoice{{0}, false};
        else if constexpr (std::is_same_v<V, LaplacianViscosityChoice>) return SwitchedLaplacianChoice{v, true};
        else return v;
      },
      choice);
}

// The pair evaluator of a viscosity for kernel K; kWall: for wall
// neighbours (their vWall), `on` = false: coefficient 0.
template <class K, bool kWall>
using SwitchedLaplacian = SwitchedViscosity<LaplacianViscosity<K, kWall>>;
template <class K, bool kWall>
inline std::tuple<SwitchedLaplacian<K, kWall>> viscosityPack(const K& k, SwitchedLaplacianChoice v, bool on = true) {
  return {SwitchedLaplacian<K, kWall>{{k, on ? v.laplacian.mu : 0}, v.on}};
}
template <class K, bool kWall>
inline std::tuple<MonaghanViscosity<K, kWall>> viscosityPack(const K& k, MonaghanViscosityChoice v, bool on = true) {
  return {MonaghanViscosity<K, kWall>{k, on ? v.alpha : 0, on ? v.beta : 0}};
}
template <class K, bool kWall>
inline std::tuple<MorrisViscosity<K, kWall>> viscosityPack(const K& k, MorrisViscosityChoice v, bool on = true) {
  return {MorrisViscosity<K, kWall>{k, on ? v.nu : 0}};
}

template <int D>
struct WcsphForcePass {
  static constexpr const char* name = "wcsph_forces";
  Kernel<D> kernel;
  ViscosityChoice viscosity;
  BodyForces<D> bodies;
  Real xsphEpsilon = 0;
  bool continuity = false;            // density = continuity: write d rho/dt
  DensityDiffusion<D> diffusion;      // coefficient 0: off
  WallSums walls{};                   // the boundary's: wall pairs (inSums), wall d rho/dt (densityRates)
  bool wallViscosity = true;          // the viscous term sees the walls (not with free-slip)
  bool cspm = false;                  // CSPM-corrected pressure gradient (needs cspmL)
  std::optional<ColourSurfaceTension<D>> surfaceTension;  // from the colour pre-pass
  OptionalTerms terms{};              // terms/optional_terms.hpp (each off by default)
  // Particle shifting's sums for the next step's shift (terms/shifting_sums.hpp;
  // off: not taken). spacing: dx of W(dx); rho0: the walls' volume m / rho0.
  struct ShiftingSumsChoice {
    bool on = false;
    Real spacing = 0, rho0 = 0;
  } shifting{};

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const;
  // run() reads x, m, rho and p; v for the viscosity (vWall of the wall
  // neighbours: laplacian and morris; c: monaghan), the continuity term and
  // XSPH; cspmL with CSPM, the colour normal and curvature with surface
  // tension, what the body forces read. It writes the fluid's a, d rho/dt
  // (the walls' too when they have one) unless the integrator computes it
  // apart, the XSPH correction, and particle shifting's sums when asked.
  FieldAccess fields(const StepContext& ctx) const {
    const bool rateHere = continuity && !ctx.densityRateApart;
    FieldSet viscous = std::holds_alternative<NoViscosity>(viscosity) ? 0u : fieldBit(kFieldV);
    if (std::holds_alternative<MonaghanViscosityChoice>(viscosity)) viscous |= fieldBit(kFieldC);
    if (walls.inSums && readsWallVelocity(viscosity)) viscous |= fieldBit(kFieldVWall);
    FieldSet reads = fieldBits(kFieldX, kFieldM, kFieldRho, kFieldP) | viscous | bodies.reads();
    if (rateHere || xsphEpsilon > 0) reads |= fieldBit(kFieldV);
    if (cspm) reads |= fieldBit(kFieldCspmL);
    if (surfaceTension) reads |= ColourSurfaceTension<D>::kReads;
    reads |= optionalTermReads(terms);
    const FieldSet writes = fieldBit(kFieldA) | (rateHere ? fieldBit(kFieldDrho) : 0u) |
                            (xsphEpsilon > 0 ? fieldBit(kFieldVXsph) : 0u) |
                            (shifting.on ? fieldBits(kFieldShiftSum, kFieldShiftGrad) : 0u);
    return {reads, writes};
  }
};

// Defined here, instantiated once (src/instantiate_*.cpp).
template <int D>
unsigned WcsphForcePass<D>::run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext& ctx) const {
  // The density rate is this loop's unless the integrator computes it apart.
  const bool rateHere = continuity && !ctx.densityRateApart;
  const bool wallRatesHere = walls.densityRates && rateHere;
  DensityDiffusion<D> diffusionHere = diffusion;
  if (!rateHere) diffusionHere.coefficient = 0;
  const bool blocks = kPairBlocksPay && pairBlocksAllowed() && !rateHere && !cspm && !shifting.on &&
                     !anyPairTermActive(terms) && isRowKernel(kernel);  // (the rows' physics, below)
  const ParticlePrologue<D> prologue = pairArrays(P, true, diffusionHere.active(), blocks);
  diffusionHere.volume = prologue.volume;
  const unsigned bits = std::visit(
      [&](const auto& k, const auto& visc) {
        using K = std::decay_t<decltype(k)>;
        const SymmetricPressure pressure{cspm, prologue.pOverRho2};
        const GradientCorrection<D> correct{cspm ? P.cspmL.data() : nullptr};
        const ContinuityDensity rate{rateHere};
        const Real invWdx = shifting.on ? 1 / k.W(shifting.spacing) : 0;
        const auto fluidPairs = std::tuple_cat(
            std::make_tuple(rate, diffusionHere, pressure), pairTermEvaluators(terms, k, rateHere),
            viscosityPack<K, false>(k, visc),
            std::make_tuple(Xsph<K>{k, xsphEpsilon}, ShiftingSums<K>{k, invWdx, shifting.rho0, shifting.on}));
        const auto wallNeighbourPairs =
            std::tuple_cat(std::make_tuple(rate, pressure), viscosityPack<K, true>(k, visc, wallViscosity),
                           std::make_tuple(ShiftingSums<K, true>{k, invWdx, shifting.rho0, shifting.on}));
        constexpr unsigned writes = PackTraits<std::decay_t<decltype(fluidPairs)>>::writes;
        const ForceEpilogue<D, writes, ParticleTermForces<D>> epilogue{
            bodies, xsphEpsilon, rateHere, surfaceTension ? &*surfaceTension : nullptr, ParticleTermForces<D>{terms},
            shifting.on, k.W(0)};
        auto loop = [&](const auto& fluidRow, const auto& wallRow) {
          return runPairLoop(P, neighbours, k, k.support(), fluidPairs, wallNeighbourPairs,
                             std::make_tuple(ContinuityDensity{wallRatesHere}), epilogue, DensityRateEpilogue<D>{},
                             PairLoopParts{walls.inSums, wallRatesHere}, correct, prologue, fluidRow, wallRow);
        };
        // The water physics in SIMD blocks (force_blocks.hpp: the
        // same accelerations up to the order of the sum), where they pay.
        // The wall neighbours take the row without XSPH (fluid pairs only),
        // with the walls' viscosity: wallNeighbourPairs' terms.
        using V = std::decay_t<decltype(visc)>;
        if constexpr (kPairBlocksPay && kRowKernel<K> &&
                      std::is_same_v<V, MonaghanViscosityChoice>) {
          const Real* m = realMasses(P, prologue);
          if (blocks && prologue.pOverRho2 && m) {
            // (alpha, beta of the walls' own evaluator: 0 with free slip.)
            const auto wallVisc = std::get<0>(viscosityPack<K, true>(k, visc, wallViscosity));
            const PressureViscosityRow<D, K> wallRow{P, k, prologue.pOverRho2, wallVisc.alpha, wallVisc.beta, m};
            if (xsphEpsilon > 0)
              return loop(PressureViscosityRow<D, K, true>{P, k, prologue.pOverRho2, visc.alpha, visc.beta, m},
                          wallRow);
            return loop(PressureViscosityRow<D, K>{P, k, prologue.pOverRho2, visc.alpha, visc.beta, m}, wallRow);
          }
        }
        // The laminar viscosities: a wall neighbour shows the fluid its
        // vWall (the coefficient of the walls' own evaluator: 0 with free
        // slip). No viscosity is the Laplacian one switched off: the row
        // without a viscous term.
        if constexpr (kPairBlocksPay && kRowKernel<K> &&
                      (std::is_same_v<V, MorrisViscosityChoice> || std::is_same_v<V, SwitchedLaplacianChoice>)) {
          const Real* m = realMasses(P, prologue);
          if (blocks && prologue.pOverRho2 && m) {
            constexpr bool kMorris = std::is_same_v<V, MorrisViscosityChoice>;
            auto laminarLoop = [&](auto kind, Real fluidCoefficient, Real wallCoefficient) {
              constexpr RowViscosity kV = decltype(kind)::value;
              const Real* vWall = P.vWall.empty() ? nullptr : P.vWall.front().data();
              const PressureViscosityRow<D, K, false, kV> wallRow{P, k, prologue.pOverRho2, 0, 0, m, wallCoefficient,
                                                                  vWall};
              if (xsphEpsilon > 0)
                return loop(PressureViscosityRow<D, K, true, kV>{P, k, prologue.pOverRho2, 0, 0, m, fluidCoefficient},
                            wallRow);
              return loop(PressureViscosityRow<D, K, false, kV>{P, k, prologue.pOverRho2, 0, 0, m, fluidCoefficient},
                          wallRow);
            };
            const auto wallVisc = std::get<0>(viscosityPack<K, true>(k, visc, wallViscosity));
            if constexpr (kMorris)
              return laminarLoop(std::integral_constant<RowViscosity, RowViscosity::kMorris>{}, visc.nu, wallVisc.nu);
            else if (visc.on)
              return laminarLoop(std::integral_constant<RowViscosity, RowViscosity::kLaplacian>{}, visc.laplacian.mu,
                                 wallVisc.mu);
            else
              return laminarLoop(std::integral_constant<RowViscosity, RowViscosity::kNone>{}, 0, 0);
          }
        }
        return loop(PairByPair{}, PairByPair{});
      },
      kernel, loopViscosity(viscosity));
  const unsigned wallBits = walls.densityRates && P.hasWalls() ? term_bits::kDynamicWalls : 0u;
  return bits | wallBits | bodies.bits() | particleTermBits(terms) |
         (surfaceTension ? term_bits::kSurfaceTension : 0u);
}

extern template struct WcsphForcePass<2>;
extern template struct WcsphForcePass<3>;

}  // namespace sph
