// Initial particles: lattice block, lattice disc/ball, explicit points, and
// files (CSV with x,y[,z][,vx,vy[,vz]] columns; a .vtp written by sph).
//
// Lattice generators put particles at cell centres: a block [min, max] with
// spacing dx holds round((max - min)/dx) particles per axis at
// min + (i + 1/2) dx. The disc/ball holds the lattice points c + i dx with
// |x - c| <= R. A particle_file, when given, replaces the generators (so a
// case continues from any of its own snapshots with one extra flag); ids,
// masses, densities and the time come from a .vtp when it has them, and its
// wall particles (kind = 1) replace the case's (docs/running.md).
#pragma once

#include "sph/case_config.hpp"
#include "sph/particles.hpp"

#include <optional>
#include <string>

namespace sph {

template <int D>
struct InitialState {
  Particles<D> particles;
  bool massesGiven = false;   // masses came from a .vtp: do not rescale
  Real startTime = 0;         // time stored in a .vtp, else 0
  long startStep = 0;         // step stored in a snapshot (resume)
  bool inSortOrder = true;    // resume: one .vtp, in the order of a one-rank run's sort (not a .pvtp's pieces)
  std::vector<Real> surface;  // generated particles: the top of their body (hydrostatic start)
};

// Builds the initial particles of a validated case; throws CaseError on a
// missing or malformed file, zero particles, or a particle outside the domain.
template <int D>
InitialState<D> buildInitialState(const ResolvedCase& c);

// The particles of a snapshot sph wrote, with everything a resumed run needs
// to continue bit for bit: state (x, v, rho, m, id, kind) and the rates the
// integrator carries into the next step (a, and drho, the XSPH correction
// when present). Throws CaseError naming the file.
template <int D>
InitialState<D> resumeState(const std::string& snapshot);

}  // namespace sph
