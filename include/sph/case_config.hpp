// CaseConfig: the typed content of a case file (and of its command-line
// overrides). One field per key; the key names, units, defaults and allowed
// ranges are listed once, in src/main.cpp, where CLI11 reads them.
//
// validateCase() checks every range before anything runs or is written and
// throws CaseError naming the key and what is allowed.
#pragma once

#include "sph/types.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace sph {

class CaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CaseConfig {
  std::string caseFile;  // path of the case file ("" when none)
  std::string name;      // run name: output files are <name>.pvd, <name>_NNNNN.vtp
  std::string output;    // output folder
  std::string model = "seed_wcsph";
  int dimension = 2;

  // seed_wcsph physics
  Real h = 0.01;
  Real k = 2000;
  Real rho0 = 1000;
  Real mu = 1;
  Real g = 9.81;
  Real restitution = 0.5;

  // time
  Real dt = 1e-4;
  Real endTime = 1.0;
  long outputEvery = 100;

  // domain (walls)
  std::vector<Real> domainMin{0, 0};
  std::vector<Real> domainMax{1, 1};

  // initial particles: any combination of the generators below
  Real spacing = 0;                  // lattice spacing for block and disc
  std::vector<Real> blockMin, blockMax;
  std::vector<Real> discCenter;
  Real discRadius = 0;
  std::vector<Real> points;          // x0 y0 [z0] x1 y1 [z1] ...
  std::vector<Real> velocity;        // initial velocity of generated particles
  std::string particleFile;          // .csv (x,y[,z][,vx,vy[,vz]]) or .vtp from sph

  int threads = 0;                   // 0: OpenMP default
  bool progress = true;              // progress line when stderr is a terminal
};

void validateCase(const CaseConfig& c);

// The first D values of a validated vector key as a Vec<D>.
template <int D>
Vec<D> toVec(const std::vector<Real>& v) {
  Vec<D> out;
  for (int d = 0; d < D; ++d) out[d] = v[static_cast<std::size_t>(d)];
  return out;
}

// Number of steps that reach end_time: ceil(end_time / dt) up to round-off.
long stepsFor(const CaseConfig& c);

}  // namespace sph
