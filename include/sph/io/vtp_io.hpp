// Particle snapshots as VTK XML PolyData (.vtp), written with VTK's own
// vtkXMLPolyDataWriter (binary, zlib-compressed) and read back with
// vtkXMLPolyDataReader (for continuing a run from any output step).
//
// Points are 3D (z = 0 in 2D) with one vertex cell each. Point data: every
// allocated field of the field table that has a snapshot name (fields.hpp):
// velocity, acceleration (3 components, also in 2D), density, pressure,
// mass, id, and when present density_rate, kind, xsph_velocity, colour,
// colour_normal, curvature, velocity_previous, density_previous,
// list_build_position, each with its SI unit as the UNITS_LABEL
// information key (Pa or N/m, ...: snapshot_polydata.hpp). Field data:
// TimeValue (ParaView's time key), step, smoothing_length, dimension,
// particle_spacing, and domain_min/domain_max (D values each) when the
// scene has walls.
#pragma once

#include "sph/particles.hpp"

#include <array>
#include <string>
#include <vector>

namespace sph {

struct SnapshotInfo {
  Real time = 0;
  long step = 0;
  Real smoothingLength = 0;
  Real particleSpacing = 0;
  std::vector<Real> domainMin, domainMax;  // empty: no walls
};

// Written to a temporary name and renamed; throws std::runtime_error on failure.
template <int D>
void writeVtp(const std::string& path, const Particles<D>& P, const SnapshotInfo& info);

struct VtpParticles {
  std::vector<std::array<Real, 3>> x, v;
  std::vector<Real> m;           // empty if the file has no mass array
  std::vector<std::int64_t> id;  // empty if the file has no id array
  Real time = 0;
  long step = 0;
  bool hasVelocity = false;
  // What a resume restores besides (empty when the file lacks the array).
  std::vector<std::array<Real, 3>> a, vXsph;
  std::vector<Real> rho, drho;
  std::vector<std::uint8_t> kind;
  std::vector<Real> colour;      // surface tension: the particles' phase colour
  std::vector<std::array<Real, 3>> vPrev;  // two-step leap-frog: filtered velocity and density of the step before
  std::vector<Real> rhoPrev;
  // positions at the neighbour list's last build (neighbour_skin > 0 or neighbour_walk = cells)
  std::vector<std::array<Real, 3>> xList;
};

// Reads the particles of a .vtp (src/vtp_read.cpp): one PolyData piece, in
// any data mode VTK and ParaView write (ascii, binary, appended raw or
// base64, compressed or not), decoded by VTK. The layout is checked
// against the file before VTK reads it, VTK prints nothing, and the values
// are checked (finite positions and velocities, masses > 0, unique ids,
// TimeValue finite and >= 0). A .pvtp (a parallel snapshot, pvtp_io.hpp):
// every piece it lists read so, in its order, and appended (a piece may be
// empty; all must have the same arrays, TimeValue and step; ids unique
// across them). Throws std::runtime_error, one line starting with the path
// (and naming the piece), on any damaged or unsuitable file.
VtpParticles readVtp(const std::string& path);

}  // namespace sph
