// Pass: the wcsph model's pair terms fused in one pair loop:
//   a_i = symmetric pressure + viscosity (none | laplacian | monaghan)
//         + body forces (epilogue),   XSPH correction (when eps > 0).
// The kernel and the viscosity are resolved once per evaluation with
// std::visit into one fully inlined loop; the pair loop forms grad W once
// per pair for all the terms.
#pragma once

#include "sph/kernels/kernels.hpp"
#include "sph/pair_loop.hpp"
#include "sph/passes/seed_forces.hpp"
#include "sph/passes/step_context.hpp"
#include "sph/terms/body_forces.hpp"
#include "sph/terms/laplacian_viscosity.hpp"
#include "sph/terms/monaghan_viscosity.hpp"
#include "sph/terms/symmetric_pressure.hpp"
#include "sph/terms/xsph.hpp"

#include <tuple>
#include <variant>

namespace sph {

template <int D>
using Kernel = std::variant<CubicSpline<D>, WendlandC2<D>, Gaussian<D>, Muller<D>>;

struct NoViscosity {};
struct LaplacianViscosityChoice {
  Real mu;
};
struct MonaghanViscosityChoice {
  Real alpha, beta;
};
using ViscosityChoice = std::variant<NoViscosity, LaplacianViscosityChoice, MonaghanViscosityChoice>;

// The pair evaluator of a viscosity choice for kernel K (none: an empty pack).
template <class K>
inline std::tuple<> viscosityPack(const K&, NoViscosity) { return {}; }
template <class K>
inline std::tuple<LaplacianViscosity<K>> viscosityPack(const K& k, LaplacianViscosityChoice v) {
  return {LaplacianViscosity<K>{k, v.mu}};
}
template <class K>
inline std::tuple<MonaghanViscosity<K>> viscosityPack(const K& k, MonaghanViscosityChoice v) {
  return {MonaghanViscosity<K>{k, v.alpha, v.beta}};
}

template <int D>
struct WcsphForcePass {
  Kernel<D> kernel;
  ViscosityChoice viscosity;
  BodyForces<D> bodies;
  Real xsphEpsilon = 0;

  unsigned run(Particles<D>& P, const NeighbourList<D>& neighbours, const StepContext&) const {
    const unsigned bits = std::visit(
        [&](const auto& k, const auto& visc) {
          using K = std::decay_t<decltype(k)>;
          const auto wallPairs = std::tuple_cat(std::make_tuple(SymmetricPressure{}), viscosityPack(k, visc));
          const auto fluidPairs = std::tuple_cat(wallPairs, std::make_tuple(Xsph<K>{k, xsphEpsilon}));
          constexpr unsigned writes = PackTraits<std::decay_t<decltype(fluidPairs)>>::writes;
          return runPairLoop(P, neighbours, k, k.support(), fluidPairs, wallPairs, std::tuple<>(),
                             ForceEpilogue<D, writes>{bodies, xsphEpsilon}, WallEpilogue<D, 0>{});
        },
        kernel, viscosity);
    return bits | bodies.bits();
  }
};

}  // namespace sph
