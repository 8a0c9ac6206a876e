#include "sph/wall_particles.hpp"

#include "sph/methods.hpp"

#include <cmath>

namespace sph {
namespace {

// Coordinates along one axis of [a, b]: inside the box, then the layers
// below a and above b (when wanted).
struct AxisLattice {
  std::vector<Real> coords;
  std::vector<bool> inside;  // coords[k] lies in [a, b]
};

AxisLattice axis(Real a, Real b, Real dx, int layers, bool below, bool above, bool repulsive) {
  AxisLattice L;
  if (repulsive) {
    // The wall itself at dx/2 spacing, ends included.
    const long n = std::max(1L, std::lround((b - a) / (dx / 2)));
    for (long k = 0; k <= n; ++k) {
      L.coords.push_back(a + (b - a) * static_cast<Real>(k) / static_cast<Real>(n));
      L.inside.push_back((k > 0 || !below) && (k < n || !above));
    }
    return L;
  }
  const long n = std::lround((b - a) / dx);
  for (long k = 0; k < n; ++k) L.coords.push_back(a + (static_cast<Real>(k) + 0.5) * dx), L.inside.push_back(true);
  for (int k = 0; k < layers; ++k) {
    if (below) L.coords.push_back(a - (k + 0.5) * dx), L.inside.push_back(false);
    if (above) L.coords.push_back(b + (k + 0.5) * dx), L.inside.push_back(false);
  }
  return L;
}

// Every lattice point of the per-axis lists that is outside the box in at
// least one axis (the shell).
template <int D>
void addShell(std::vector<Vec<D>>& out, const AxisLattice (&axes)[D]) {
  long total = 1;
  for (int d = 0; d < D; ++d) total *= static_cast<long>(axes[d].coords.size());
  for (long k = 0; k < total; ++k) {
    long rest = k;
    Vec<D> x;
    bool shell = false;
    for (int d = 0; d < D; ++d) {
      const auto n = static_cast<long>(axes[d].coords.size());
      const auto i = static_cast<std::size_t>(rest % n);
      rest /= n;
      x[d] = axes[d].coords[i];
      shell |= !axes[d].inside[i];
    }
    if (shell) out.push_back(x);
  }
}

}  // namespace

int wallLayersNeeded(const CaseConfig& c) {
  if (c.spacing <= 0) return 0;
  const Real support = std::visit([](const auto& k) { return k.support(); }, chosenKernel<2>(c));
  return static_cast<int>(std::ceil(support / c.spacing - 1e-9));
}

template <int D>
std::vector<Vec<D>> wallParticlePositions(const CaseConfig& c, int layers) {
  std::vector<Vec<D>> out;
  const bool repulsive = boundaryChoice(c).particles == WallLattice::kOnSurface;
  const Real dx = c.spacing;
  {
    // No walls on periodic faces: along a periodic axis the lattice is the
    // box's own, [lo, hi) (repulsive walls: their points less the one on hi).
    const unsigned periodic = periodicAxes(c);
    AxisLattice axes[D];
    for (int d = 0; d < D; ++d) {
      const bool top = d == D - 1, wrap = (periodic >> d) & 1u;
      axes[d] = axis(c.domainMin[static_cast<std::size_t>(d)], c.domainMax[static_cast<std::size_t>(d)], dx, layers,
                     !wrap, (!top || c.lid) && !wrap, repulsive);
      if (wrap && repulsive) axes[d].coords.pop_back(), axes[d].inside.pop_back();
    }
    addShell<D>(out, axes);
  }
  // Obstacles: the layers are inside the box, so the lattice is the box's
  // own, less its core.
  for (std::size_t k = 0; k + D <= c.obstacleMin.size(); k += D) {
    if (repulsive) {
      AxisLattice axes[D];
      for (int d = 0; d < D; ++d) axes[d] = axis(c.obstacleMin[k + d], c.obstacleMax[k + d], dx, 0, true, true, true);
      addShell<D>(out, axes);
      continue;
    }
    AxisLattice axes[D];
    for (int d = 0; d < D; ++d) {
      const Real a = c.obstacleMin[k + d], b = c.obstacleMax[k + d];
      const long n = std::lround((b - a) / dx);
      for (long i = 0; i < n; ++i) {
        axes[d].coords.push_back(a + (static_cast<Real>(i) + 0.5) * dx);
        // "inside" here means: in the core, deeper than `layers` from both faces.
        axes[d].inside.push_back(i >= layers && i < n - layers);
      }
    }
    addShell<D>(out, axes);
  }
  return out;
}

int wallLayersUsed(const CaseConfig& c) {
  return c.wallLayers > 0 ? static_cast<int>(c.wallLayers) : wallLayersNeeded(c);
}

template <int D>
std::pair<std::size_t, std::size_t> obstacleParticleRange(const CaseConfig& c, int layers, std::size_t k) {
  CaseConfig upTo = c;
  upTo.obstacleMin.resize(k * D);
  upTo.obstacleMax.resize(k * D);
  const std::size_t first = wallParticlePositions<D>(upTo, layers).size();
  upTo.obstacleMin.assign(c.obstacleMin.begin(), c.obstacleMin.begin() + static_cast<long>((k + 1) * D));
  upTo.obstacleMax.assign(c.obstacleMax.begin(), c.obstacleMax.begin() + static_cast<long>((k + 1) * D));
  return {first, wallParticlePositions<D>(upTo, layers).size()};
}

template std::pair<std::size_t, std::size_t> obstacleParticleRange<2>(const CaseConfig&, int, std::size_t);
template std::pair<std::size_t, std::size_t> obstacleParticleRange<3>(const CaseConfig&, int, std::size_t);
template std::vector<Vec<2>> wallParticlePositions<2>(const CaseConfig&, int);
template std::vector<Vec<3>> wallParticlePositions<3>(const CaseConfig&, int);

}  // namespace sph
