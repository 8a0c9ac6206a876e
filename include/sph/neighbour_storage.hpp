// NeighbourStorage: how the neighbour list keeps its pairs between builds
// (the neighbour_walk key; neighbour_list.hpp): a 4-byte index per pair,
// one bit per candidate of the cells around a particle, or nothing (the
// cells scanned again at every visit). Its own header so that the method
// tables (methods.hpp) need not include the list.
#pragma once

namespace sph {

enum class NeighbourStorage { kList, kPacked, kCells };

}  // namespace sph
