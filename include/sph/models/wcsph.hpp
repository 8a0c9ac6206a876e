// Model "wcsph": weakly-compressible SPH composed by name from a kernel, an
// equation of state, a viscosity, body forces and XSPH.
//
//   rho_i = sum_j m_j W(r_ij, h)                               (self term included)
//   p_i   = EOS(rho_i)                                          (equation_of_state.hpp)
//   a_i   = - sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2) grad W     (symmetric_pressure.hpp)
//           + viscosity (none | laplacian | monaghan)
//           + body forces (gravity -g e_up, star -lambda x, damping -nu v)
//   dx_i/dt = v_i [+ XSPH correction]
// (Monaghan 1992; Monaghan 2005, "Smoothed particle hydrodynamics", Rep. Prog. Phys. 68.)
//
// The kernel and the viscosity are resolved once per step with std::visit
// into one fully inlined pair loop; a viscosity set to none, a body force
// whose coefficient is zero and XSPH with eps = 0 are never constructed, and
// the arrays they would need (sound speed, XSPH correction) never allocated.
#pragma once

#include "sph/kernels/kernels.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "sph/terms/laplacian_viscosity.hpp"
#include "sph/terms/linear_damping.hpp"
#include "sph/terms/monaghan_viscosity.hpp"
#include "sph/terms/pair_accelerations.hpp"
#include "sph/terms/star_attraction.hpp"
#include "sph/terms/summation_density.hpp"
#include "sph/terms/symmetric_pressure.hpp"
#include "sph/terms/uniform_gravity.hpp"
#include "sph/terms/xsph.hpp"

#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <variant>
#include <vector>

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

// W(r) seen as a function of r^2, for the summation-density loop.
template <class K>
struct DensityKernel {
  K kernel;
  Real density(Real r2) const { return kernel.W(std::sqrt(r2)); }
  Real densityAtZero() const { return kernel.W(0); }
};

template <int D>
struct WcsphTerms {
  std::optional<UniformGravity<D>> gravity;
  std::optional<StarAttraction<D>> star;
  std::optional<LinearDamping<D>> damping;
  Real xsphEpsilon = 0;
};

template <int D>
class Wcsph {
 public:
  Wcsph(Kernel<D> kernel, EquationOfState eos, ViscosityChoice viscosity, Real restDensity,
        WcsphTerms<D> terms)
      : kernel_(kernel), eos_(eos), viscosity_(viscosity), rho0_(restDensity), terms_(terms) {}

  Real support() const {
    return std::visit([](const auto& k) { return k.support(); }, kernel_);
  }
  Real smoothingLength() const {
    return std::visit([](const auto& k) { return k.h(); }, kernel_);
  }
  Real restDensity() const { return rho0_; }
  const WcsphTerms<D>& terms() const { return terms_; }
  const EquationOfState& eos() const { return eos_; }
  const ViscosityChoice& viscosity() const { return viscosity_; }

  FieldNeeds needs() const {
    FieldNeeds f;
    f.soundSpeed = std::holds_alternative<MonaghanViscosityChoice>(viscosity_);
    f.xsph = terms_.xsphEpsilon > 0;
    return f;
  }

  // The terms this model constructed, by name (for tests and the summary).
  std::vector<std::string> termNames() const {
    std::vector<std::string> names{"summation_density", "equation_of_state", "symmetric_pressure"};
    if (std::holds_alternative<LaplacianViscosityChoice>(viscosity_)) names.push_back("laplacian_viscosity");
    if (std::holds_alternative<MonaghanViscosityChoice>(viscosity_)) names.push_back("monaghan_viscosity");
    if (terms_.gravity) names.push_back("gravity");
    if (terms_.star) names.push_back("star_attraction");
    if (terms_.damping) names.push_back("damping");
    if (terms_.xsphEpsilon > 0) names.push_back("xsph");
    return names;
  }

  void computeDensity(Particles<D>& P, const NeighbourList<D>& neighbours) const {
    std::visit([&](const auto& k) { computeSummationDensity(P, neighbours, DensityKernel<std::decay_t<decltype(k)>>{k}); },
               kernel_);
  }

  void computeDerived(Particles<D>& P, const NeighbourList<D>& neighbours) const {
    computeDensity(P, neighbours);
    std::visit([&](const auto& eos) { computePressure(P, eos); }, eos_);
    unsigned executed = term_bits::kSummationDensity | term_bits::kEquationOfState;
    std::visit(
        [&](const auto& k, const auto& visc) {
          using K = std::decay_t<decltype(k)>;
          using V = std::decay_t<decltype(visc)>;
          const Real s = k.support();
          const auto pressure = std::make_tuple(SymmetricPressure<K>{k});
          if constexpr (std::is_same_v<V, LaplacianViscosityChoice>)
            executed |= computeAccelerations(P, neighbours, s,
                                 std::tuple_cat(pressure, std::make_tuple(LaplacianViscosity<K>{k, visc.mu})),
                                 std::tuple<>());
          else if constexpr (std::is_same_v<V, MonaghanViscosityChoice>)
            executed |= computeAccelerations(P, neighbours, s,
                                 std::tuple_cat(pressure, std::make_tuple(MonaghanViscosity<K>{k, visc.alpha, visc.beta})),
                                 std::tuple<>());
          else
            executed |= computeAccelerations(P, neighbours, s, pressure, std::tuple<>());
          if (terms_.xsphEpsilon > 0) {
            computeXsphCorrection(P, neighbours, k, terms_.xsphEpsilon);
            executed |= term_bits::kXsph;
          }
        },
        kernel_, viscosity_);
    executed |= addBodyForce(P, terms_.gravity);
    executed |= addBodyForce(P, terms_.star);
    executed |= addBodyForce(P, terms_.damping);
    executed_ = executed;
  }

  // The passes the last computeDerived() ran (term_bits.hpp).
  unsigned executedTerms() const { return executed_; }

  Real potentialEnergy(const Particles<D>& P) const {
    Real e = 0;
    for (std::size_t i = 0; i < P.size(); ++i) {
      if (terms_.gravity) e += terms_.gravity->potential(i, P);
      if (terms_.star) e += terms_.star->potential(i, P);
    }
    return e;
  }

  // Largest sound speed over the particles (for the CFL time step). Every
  // EOS here has c monotonic in rho, so it is c at the lowest or the highest
  // density: one reduction instead of a pow() per particle.
  Real maxSoundSpeed(const Particles<D>& P) const {
    Real rhoMin = std::numeric_limits<Real>::infinity(), rhoMax = 0;
    const std::size_t n = P.size();
#pragma omp parallel for schedule(static) reduction(min : rhoMin) reduction(max : rhoMax) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      rhoMin = std::min(rhoMin, P.rho[i]);
      rhoMax = std::max(rhoMax, P.rho[i]);
    }
    return std::visit([&](const auto& eos) { return std::max(eos.soundSpeed(rhoMin), eos.soundSpeed(rhoMax)); },
                      eos_);
  }

  // Kinematic viscosity for the viscous time-step limit (0: no limit).
  Real kinematicViscosity() const {
    if (const auto* l = std::get_if<LaplacianViscosityChoice>(&viscosity_)) return l->mu / rho0_;
    return 0;
  }

 private:
  template <class Body>
  static unsigned addBodyForce(Particles<D>& P, const std::optional<Body>& body) {
    if (!body) return 0;
    const std::size_t n = P.size();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) P.a[i] += body->acceleration(i, P);
    return Body::bit;
  }

  Kernel<D> kernel_;
  EquationOfState eos_;
  ViscosityChoice viscosity_;
  Real rho0_;
  WcsphTerms<D> terms_;
  mutable unsigned executed_ = 0;
};

}  // namespace sph
