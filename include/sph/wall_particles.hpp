// Wall particles for the domain box and its obstacles, on the fluid lattice.
//
// Dummy and dynamic walls: `layers` layers of particles at spacing dx behind
// each wall of the box [lo, hi] (lo - (k + 1/2) dx, hi + (k + 1/2) dx for
// k < layers, corners filled), so that a fluid particle dx/2 from a wall
// sees a full kernel support of particles. The top of the box (the last
// axis) has none unless `lid`. An obstacle box gets the same layers inside
// its faces. The layers a kernel needs: ceil(support / dx).
//
// Repulsive walls: one layer on the walls themselves at spacing dx/2
// (seed document 004), and on the faces of each obstacle.
#pragma once

#include "sph/case_config.hpp"

#include <utility>
#include <vector>

namespace sph {

// Layers of dummy or dynamic wall particles the case's kernel support needs.
int wallLayersNeeded(const CaseConfig& c);
// The layers a case builds: wall_layers when given, else the ones needed.
int wallLayersUsed(const CaseConfig& c);

template <int D>
std::vector<Vec<D>> wallParticlePositions(const CaseConfig& c, int layers);

// [first, end) of obstacle k's (0-based) particles in
// wallParticlePositions(c, layers): the walls' ids are the fluid count plus
// these indices.
template <int D>
std::pair<std::size_t, std::size_t> obstacleParticleRange(const CaseConfig& c, int layers, std::size_t k);

}  // namespace sph
