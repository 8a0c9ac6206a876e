// Model "seed_wcsph": the seed 2D weakly-compressible Navier-Stokes scheme.
//
//   rho_i = sum_j m 4/(pi h^2) (1 - q^2)^3                (self term included)
//   p_i   = k (rho_i - rho0)
//   a_i   = (F_p,i + F_v,i + F_g,i) / rho_i
//   F_p,i = - sum_{j!=i} (m/rho_j) (p_i + p_j)/2 (-30/(pi h^3)) r_ij (1-q)^2/q
//   F_v,i = - mu sum_{j!=i} (m/rho_j) v_ij 40/(pi h^4) (1 - q)
//   F_g,i = -rho_i g e_up
// with support radius h, mass scaled once so the mean density is rho0, leap-
// frog time stepping and damped reflecting walls (see the files of each part).
//
// The terms a case switches off (mu = 0, g = 0) are left out of the pair loop
// at compile time; the choice is made once per step, never per pair.
#pragma once

#include "sph/neighbour_list.hpp"
#include "sph/kernels/seed_kernels.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "sph/terms/pair_accelerations.hpp"
#include "sph/terms/seed_pressure.hpp"
#include "sph/terms/seed_viscosity.hpp"
#include "sph/terms/summation_density.hpp"
#include "sph/terms/uniform_gravity.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <vector>
#include <tuple>

namespace sph {

struct SeedWcsphParameters {
  Real h = 0.01;      // support radius [m]
  Real k = 2000;      // EOS stiffness
  Real rho0 = 1000;   // rest density
  Real mu = 1;        // dynamic viscosity (0: no viscosity term)
  Real g = 9.81;      // gravity along -e_up (0: no gravity term)
};

template <int D>
class SeedWcsph {
 public:
  explicit SeedWcsph(const SeedWcsphParameters& prm)
      : kernels_(prm.h), eos_{prm.k, prm.rho0}, pressure_{kernels_} {
    if (prm.mu > 0) viscosity_ = SeedViscosity{kernels_, prm.mu};
    if (prm.g != 0) gravity_ = UniformGravity<D>{prm.g};
  }

  Real support() const { return kernels_.support(); }
  Real smoothingLength() const { return kernels_.support(); }
  FieldNeeds needs() const { return {}; }
  std::vector<std::string> termNames() const {
    std::vector<std::string> names{"seed_density", "linear_eos", "seed_pressure"};
    if (viscosity_) names.push_back("seed_viscosity");
    if (gravity_) names.push_back("gravity");
    return names;
  }
  // dp/drho = k for the linear EOS.
  Real maxSoundSpeed(const Particles<D>&) const { return std::sqrt(eos_.k); }
  Real kinematicViscosity() const { return viscosity_ ? viscosity_->mu / eos_.rho0 : 0; }
  Real restDensity() const { return eos_.rho0; }
  bool hasViscosity() const { return viscosity_.has_value(); }
  bool hasGravity() const { return gravity_.has_value(); }

  // rho, p and a from the current positions and velocities. The neighbour
  // list must have been built on these positions.
  void computeDerived(Particles<D>& P, const NeighbourList<D>& neighbours) const {
    computeDensity(P, neighbours);
    computePressure(P, eos_);
    executed_ = term_bits::kSummationDensity | term_bits::kEquationOfState;
    const auto pair = std::make_tuple(pressure_);
    if (viscosity_ && gravity_)
      executed_ |= computeAccelerations(P, neighbours, support(), std::tuple_cat(pair, std::make_tuple(*viscosity_)),
                           std::make_tuple(*gravity_));
    else if (viscosity_)
      executed_ |= computeAccelerations(P, neighbours, support(), std::tuple_cat(pair, std::make_tuple(*viscosity_)),
                           std::tuple<>());
    else if (gravity_)
      executed_ |= computeAccelerations(P, neighbours, support(), pair, std::make_tuple(*gravity_));
    else
      executed_ |= computeAccelerations(P, neighbours, support(), pair, std::tuple<>());
  }

  // The passes the last computeDerived() ran (term_bits.hpp).
  unsigned executedTerms() const { return executed_; }

  void computeDensity(Particles<D>& P, const NeighbourList<D>& neighbours) const {
    computeSummationDensity(P, neighbours, kernels_);
  }

  // Sum of m g y, zero without gravity.
  Real potentialEnergy(const Particles<D>& P) const {
    if (!gravity_) return 0;
    Real e = 0;
    for (std::size_t i = 0; i < P.size(); ++i) e += gravity_->potential(i, P);
    return e;
  }

 private:
  SeedKernels kernels_;
  LinearEos eos_;
  SeedPressure pressure_;
  std::optional<SeedViscosity> viscosity_;
  std::optional<UniformGravity<D>> gravity_;
  mutable unsigned executed_ = 0;
};

}  // namespace sph
