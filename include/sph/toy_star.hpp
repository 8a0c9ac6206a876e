// The polytropic toy star (Monaghan & Price 2004, "Toy stars in one
// dimension", MNRAS 350; P. Mocz, "Create your own SPH simulation"):
// particles with p = k rho^(1+1/n) held by the linear force -lambda x and
// relaxed by damping -nu v settle into the equilibrium
//
//   rho(r) = [ lambda / (2 k (1 + n)) (R^2 - r^2) ]^n ,
//
// whose mass inside R is M when
//
//   lambda = 2 k (1 + n) pi^(-D/(2n)) [ M Gamma(n + 1 + D/2) / (R^D Gamma(1 + n)) ]^(1/n) / R^2
//
// (2D, n = 1: lambda = 8 k M / (pi R^4)).
#pragma once

#include "sph/particles.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace sph {

inline Real toyStarLambda(int dimension, Real M, Real R, Real k, Real n) {
  const Real D = dimension;
  return 2 * k * (1 + n) * std::pow(M_PI, -D / (2 * n)) *
         std::pow(M * std::tgamma(n + 1 + D / 2) / (std::pow(R, D) * std::tgamma(1 + n)), 1 / n) /
         (R * R);
}

inline Real toyStarDensity(Real r, Real lambda, Real R, Real k, Real n) {
  return r < R ? std::pow(lambda / (2 * k * (1 + n)) * (R * R - r * r), n) : 0;
}

// `count` points uniformly at random inside the disc/ball of radius R about c.
template <int D>
std::vector<Vec<D>> randomPointsInBall(const Vec<D>& c, Real R, std::size_t count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Real> u(-1, 1);
  std::vector<Vec<D>> x;
  x.reserve(count);
  while (x.size() < count) {
    Vec<D> p;
    for (int d = 0; d < D; ++d) p[d] = u(rng);
    if (p.squaredNorm() <= 1) x.push_back(c + R * p);
  }
  return x;
}

struct StarProfile {
  std::vector<Real> r, rhoSph, rhoExact;  // per radial bin
  std::vector<std::size_t> count;
  Real l2Error = 0;  // relative L2 over particles with r < 0.9 R
  std::size_t inside = 0;
};

// Density of the particles against the equilibrium profile about `centre`.
template <int D>
StarProfile toyStarProfile(const Particles<D>& P, const Vec<D>& centre, Real lambda, Real R,
                           Real k, Real n, int bins = 30) {
  StarProfile s;
  s.r.resize(bins), s.rhoSph.assign(bins, 0), s.rhoExact.resize(bins), s.count.assign(bins, 0);
  const Real dr = R / bins;
  Real num = 0, den = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    const Real r = (P.x[i] - centre).norm();
    const auto b = static_cast<int>(r / dr);
    if (b < bins) {
      s.rhoSph[b] += P.rho[i];
      ++s.count[b];
    }
    if (r < 0.9 * R) {
      const Real exact = toyStarDensity(r, lambda, R, k, n);
      num += (P.rho[i] - exact) * (P.rho[i] - exact);
      den += exact * exact;
      ++s.inside;
    }
  }
  for (int b = 0; b < bins; ++b) {
    s.r[b] = (b + 0.5) * dr;
    s.rhoExact[b] = toyStarDensity(s.r[b], lambda, R, k, n);
    if (s.count[b]) s.rhoSph[b] /= static_cast<Real>(s.count[b]);
  }
  s.l2Error = den > 0 ? std::sqrt(num / den) : 0;
  return s;
}

}  // namespace sph
