// PeriodicGhosts<D>: periodic boundaries by ghost particles, as DualSPHysics
// does with its periodic particles (Dominguez et al. 2022, "DualSPHysics:
// from fluid dynamics to multiphysics problems", Comp. Part. Mech. 9).
//
// At every sort (with a skin: every rebuild of the neighbour list; between
// two, a particle may stand up to half the skin outside the box, its
// ghosts following it) the owned particles are wrapped into the box [lo, hi) along
// the periodic axes (periodic_box.hpp); then every owned particle (fluid or
// wall) within one support `layer` of a periodic face is copied, shifted by
// the box length, to beyond the opposite face:
//   x_ghost = x_i + s,  s_a in {0, +L_a (x_i,a - lo_a < layer),
//                                  -L_a (hi_a - x_i,a < layer)}
// for every combination of the axes' shifts but s = 0, so a particle near
// an edge or a corner gets the combined shifts too (up to 3 ghosts in 2D,
// 7 in 3D). The ghosts are appended to the particles as their ghost range
// (particles.hpp: ghosts of fluid, then of walls), so the grid and the
// neighbour list see them as ordinary particles and every pass forms the
// plain r_ij = x_i - x_j. With L_a >= 2 x support (validateCase refuses
// narrower periodic boxes) a pair closer than the support is seen through
// exactly one of j and its ghosts, as the minimum image would see it.
//
// The layer is the neighbour list's radius: the support, or with a Verlet
// skin (scene.hpp) support (1 + skin), so that a pair the list must hold
// until its next rebuild has its ghost (times 1 + 1e-9, as the grid's cell, so
// that rounding in x_i - (x_j - L) against the minimum image (x_i - x_j) + L
// never loses a pair at the edge of the support; an extra ghost costs only
// a distance test). Ghosts compute nothing: the model's sync() between
// passes and the scene between stages refresh them from their sources
// (Particles::refreshGhosts).
#pragma once

#include "sph/hash_grid.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"
#include "sph/periodic_box.hpp"

#include <algorithm>
#include <stdexcept>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

namespace sph {

template <int D>
class PeriodicGhosts {
 public:
  PeriodicGhosts() = default;
  // `radius`: the neighbour list's (the support, times 1 + skin).
  PeriodicGhosts(const PeriodicBox<D>& box, Real radius) : box_(box), layer_(radius * (1 + 1e-9)) {}

  const PeriodicBox<D>& box() const { return box_; }
  Real layer() const { return layer_; }

  // Wrap the owned particles into the box (along its periodic axes).
  void wrap(Particles<D>& P) const {
    const std::size_t n = P.size();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) box_.wrap(P.x[i]);
  }

  // Drop the old ghosts, wrap the owned particles into the box and append
  // the ghosts of their current positions. byId: the ghosts of fluid, and
  // those of walls, in the order of their sources' ids (each source's
  // shifts in the order above), not of the sources' places, so that the
  // ghosts and the list built on them do not depend on the order the owned
  // particles had before the sort (a resumed run rebuilds the list of the
  // run that wrote the snapshot: scene.hpp).
  void make(Particles<D>& P, bool byId = false) {
    P.clearGhosts();
    const std::size_t n = P.size(), nFluid = P.fluidCount();
    wrap(P);
    source_.clear();
    shift_.clear();
    std::size_t fluidGhosts = 0;
    for (std::size_t i = 0; i < n; ++i) {
      addImages(P.x[i], static_cast<std::uint32_t>(i));
      if (i + 1 == nFluid) fluidGhosts = source_.size();
    }
    if (nFluid == n) fluidGhosts = source_.size();
    if (byId) orderById(P, fluidGhosts);
    P.addGhosts(source_, shift_, fluidGhosts);
  }

 private:
  // Reorder the ghost records [0, fluidGhosts) and [fluidGhosts, end) by
  // (id of the source, place): a source's records are consecutive, in the
  // order of its shifts. std::sort allocates nothing; the buffers are reused.
  void orderById(const Particles<D>& P, std::size_t fluidGhosts) {
    const std::size_t ng = source_.size();
    keys_.resize(ng);
    for (std::size_t g = 0; g < ng; ++g) keys_[g] = {P.id[source_[g]], static_cast<std::uint32_t>(g)};
    const auto split = keys_.begin() + static_cast<std::ptrdiff_t>(fluidGhosts);
    std::sort(keys_.begin(), split);
    std::sort(split, keys_.end());
    sourceSorted_.resize(ng);
    shiftSorted_.resize(ng);
    for (std::size_t g = 0; g < ng; ++g) {
      sourceSorted_[g] = source_[keys_[g].second];
      shiftSorted_[g] = shift_[keys_[g].second];
    }
    source_.swap(sourceSorted_);
    shift_.swap(shiftSorted_);
  }

  // The ghosts of one particle: every combination of the axes' shifts but none.
  void addImages(const Vec<D>& x, std::uint32_t i) {
    Real options[D][3];
    int count[D];
    int combinations = 1;
    for (int a = 0; a < D; ++a) {
      count[a] = 0;
      options[a][count[a]++] = 0;
      if (box_.periodic(a)) {
        const Real L = box_.length[a], lo = box_.lo[a];
        if (x[a] - lo < layer_) options[a][count[a]++] = L;
        if (lo + L - x[a] < layer_) options[a][count[a]++] = -L;
      }
      combinations *= count[a];
    }
    for (int k = 1; k < combinations; ++k) {
      Vec<D> s;
      int rest = k;
      for (int a = 0; a < D; ++a) {
        s[a] = options[a][rest % count[a]];
        rest /= count[a];
      }
      source_.push_back(i);
      shift_.push_back(s);
    }
  }

  PeriodicBox<D> box_;
  Real layer_ = 0;
  std::vector<std::uint32_t> source_;  // reused: no allocation once grown
  std::vector<Vec<D>> shift_;
  std::vector<std::pair<std::int64_t, std::uint32_t>> keys_;  // orderById's, reused
  std::vector<std::uint32_t> sourceSorted_;
  std::vector<Vec<D>> shiftSorted_;
};

// Sort the owned particles by cell, with the ghosts of a periodic box
// (ghosts == nullptr: none), and build the neighbour list of the sorted
// particles within `radius` (the support, times 1 + skin): the one sort
// every scene and test goes through. carryAll (a list with a skin): every
// field follows its particle, rates and derived fields too
// (Particles::permute()), and the ghosts are made in the order of ids.
// A cell walk (neighbour_list.hpp) keeps the positions of the build, the
// ghosts' included, in xList (allocated by the scene). halos (a domain
// decomposition's, mpi/domain_decomposition.hpp; nullptr: one rank): the
// other ranks' particles near this rank's cells, appended after the
// periodic ghosts, their send lists following the sort; each particle's
// neighbours then come in the order of their ids (neighbour_list.hpp), so
// that the results do not depend on the ranks' shares.
template <int D, class Halos = void>
void sortByCell(Particles<D>& P, HashGrid<D>& grid, NeighbourList<D>& neighbours, Real radius,
                PeriodicGhosts<D>* ghosts = nullptr, bool carryAll = false, Halos* halos = nullptr) {
  if (ghosts) ghosts->make(P, carryAll);
  if constexpr (!std::is_void_v<Halos>)
    if (halos) halos->makeHalos(P, radius);
  grid.build(P.x, P.fluidCount(), P.size(), P.ghostFluidEnd(),
             P.lendScratchBytes(sizeof(std::uint32_t) * P.totalSize()));
  P.permute(grid.order(), carryAll);
  if constexpr (!std::is_void_v<Halos>)
    if (halos) halos->followPermutation(grid.order(), P.size());
  const std::vector<std::int64_t>* byId = nullptr;
  if constexpr (!std::is_void_v<Halos>)
    if (halos) byId = &P.id;
  if (!neighbours.visitsBuildPositions()) {
    neighbours.build(grid, P.x, radius, P.fluidCount(), P.size(), byId);
    return;
  }
  if (P.xList.size() != P.x.size()) throw std::logic_error("sortByCell: a packed list or a cell walk needs xList allocated");
  std::copy(P.x.begin(), P.x.end(), P.xList.begin());
  neighbours.build(grid, P.xList, radius, P.fluidCount(), P.size(), byId);
}

}  // namespace sph
