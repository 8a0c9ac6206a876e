// NeighbourList<D>: every pair (i, j != i) closer than the support radius,
// found once per build from the hashed grid and shared by all passes
// (density, forces, diagnostics), so the cell stencil is scanned once, not
// per pass (unless the cells are walked instead: below).
//
// Storage is CSR per thread: the particles are split into one contiguous
// chunk per OpenMP thread; thread t appends the neighbours of its chunk to its
// own flat buffer and records where each particle's run begins. Buffers keep
// their capacity between steps, so a steady run does not allocate.
// Each particle's neighbours keep the order of the grid scan, so results do
// not depend on the number of threads.
//
// With walls (particles from fluidCount on, or only ghosts of walls: a rank
// of a decomposition may hold halos of walls and no walls of its own), a
// fluid particle lists its fluid neighbours, then its wall neighbours
// (forEachFluid / forEachWall visit each run); a wall particle lists only
// its fluid neighbours: no method here couples two wall particles.
//
// Ghosts (periodic_ghosts.hpp): particles from `ownedCount` on are ghosts;
// they get no row of their own (no pass computes anything for them) but
// appear in the owned particles' rows like any neighbour, ghosts of fluid
// among the fluid neighbours and ghosts of walls among the wall ones, so
// every pass forms the plain r_ij = x_i - x_j.
//
// Cell walk (neighbour_walk = cells): no list is stored; each visit of a
// particle's neighbours scans the grid's stencil around it again, as
// in DualSPHysics' cell-linked list, into a small per-thread buffer
// that the visit then walks (DualSPHysics walks the cells' particles
// directly, without such a row). The scan is the build's own (scan(), the same
// stencil of the particle's cell at the positions of the last build, the
// same distance test there), so it yields the list's pairs in the list's
// order and every result is bit for bit the stored list's; it trades the
// list's memory (about 150 bytes per particle in 2D) for a scan of the
// 3^D cells at every walk.
//
// Order by id (`byId`, given on several MPI ranks): each run of a row
// (fluid neighbours, wall neighbours) is sorted by the neighbours' ids (a
// periodic image after its source's other images by position at the
// build). A row then no longer depends on where its particles are stored:
// on any number of ranks (each its own share and halos, in its own sort)
// every particle sums its neighbours in the same order, so a run's results
// are bit for bit the same on 2, 3 or 64 ranks (docs/developer/mpi.md).
// One rank keeps the grid's order (the seed digests): it is the scan's.
#pragma once

#include "sph/hash_grid.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

namespace sph {

template <int D>
class NeighbourList {
 public:
  // Rows for the owned particles [0, ownedCount): fluid below fluidCount.
  // (Cell walk: nothing is stored; `x` must stay, unchanged, the positions
  // of this build until the next one: the scene passes its list_build_position.)
  // byId: order each run by these ids (above; nullptr: the scan's order).
  void build(const HashGrid<D>& grid, const std::vector<Vec<D>>& x, Real radius,
             std::size_t fluidCount = SIZE_MAX, std::size_t ownedCount = SIZE_MAX,
             const std::vector<std::int64_t>* byId = nullptr) {
    const std::size_t n = std::min(ownedCount, x.size());
    fluidCount = std::min(fluidCount, n);
    const bool walls = fluidCount < n || grid.hasWalls();
    byId_ = byId;
    if (cellWalk_) {
      static std::atomic<std::uint64_t> builds{0};
      cells_.grid = &grid;
      cells_.x = &x;
      cells_.radius2 = radius * radius;
      cells_.fluidCount = fluidCount;
      cells_.n = n;
      cells_.walls = walls;
      cells_.build = ++builds;  // the grid changed
      return;
    }
    if (walls) wallBegin_.resize(n);
    else std::vector<std::uint32_t>().swap(wallBegin_);
    const Real radius2 = radius * radius;
    const int threads = omp_get_max_threads();
    if (static_cast<int>(chunks_.size()) < threads) {
      chunks_.resize(static_cast<std::size_t>(threads));
      used_.resize(static_cast<std::size_t>(threads));
    }
    begin_.resize(n + 1);
    chunkStart_.assign(static_cast<std::size_t>(threads) + 1, n);
    usedChunks_ = 0;
#pragma omp parallel if (n >= kMinParallelSize)
    {
      const auto t = static_cast<std::size_t>(omp_get_thread_num());
      const auto nt = static_cast<std::size_t>(omp_get_num_threads());
      const std::size_t lo = n * t / nt, hi = n * (t + 1) / nt;
      std::vector<std::uint32_t>& list = chunks_[t];
      std::size_t used = 0;
      typename HashGrid<D>::Stencil stencil;
      for (std::size_t i = lo; i < hi; ++i) {
        const std::size_t start = used;
        begin_[i] = static_cast<std::uint32_t>(start);
        const Vec<D> xi = x[i];
        grid.updateStencil(xi, stencil);
        used = scan(list, used, i, xi, x, radius2, stencil.begin, stencil.end, stencil.count);
        if (byId) orderById(list.data() + start, list.data() + used, *byId, x);
        if (!walls) continue;
        const std::size_t split = used;
        wallBegin_[i] = static_cast<std::uint32_t>(split);
        if (i < fluidCount)
          used = scan(list, used, i, xi, x, radius2, stencil.wallBegin, stencil.wallEnd, stencil.wallCount);
        if (byId) orderById(list.data() + split, list.data() + used, *byId, x);
      }
      used_[t] = used;
      chunkStart_[t] = lo;
#pragma omp single
      usedChunks_ = nt;
    }
    chunkStart_[usedChunks_] = n;
  }

 public:
  // Append to list[used...] the neighbours of xi in the particle ranges
  // [begin[s], end[s]); returns the new fill. Branch-free: write always,
  // advance only for a neighbour.
  static std::size_t scan(std::vector<std::uint32_t>& list, std::size_t used, std::size_t i, const Vec<D>& xi,
                          const std::vector<Vec<D>>& x, Real radius2, const std::uint32_t* begin,
                          const std::uint32_t* end, int ranges) {
    for (int s = 0; s < ranges; ++s) {
      const std::uint32_t b = begin[s], e = end[s];
      if (used + (e - b) > list.size()) grow(list, used + (e - b) + used / 4 + 64);
      std::uint32_t* out = list.data();
      for (std::uint32_t j = b; j < e; ++j) {
        out[used] = j;
        used += (Vec<D>(xi - x[j]).squaredNorm() < radius2) & (j != i);
      }
    }
    return used;
  }

  // Sort the run [first, last) of neighbour indices by (id, position at
  // the build): the images of one particle share its id.
  static void orderById(std::uint32_t* first, std::uint32_t* last, const std::vector<std::int64_t>& id,
                        const std::vector<Vec<D>>& x) {
    std::sort(first, last, [&](std::uint32_t a, std::uint32_t b) {
      if (id[a] != id[b]) return id[a] < id[b];
      for (int d = 0; d < D; ++d)
        if (x[a][d] != x[b][d]) return x[a][d] < x[b][d];
      return false;
    });
  }

  // Resize to n with capacity n: a quarter more than the fill is the growth
  // (resize alone would double the capacity, and the buffer is the largest
  // array of a run).
  static void grow(std::vector<std::uint32_t>& list, std::size_t n) {
    list.reserve(n);
    list.resize(n);
  }

  // Call f(j) for every neighbour j of particle i (fluid ones first).
  template <class F>
  [[gnu::always_inline]] void forEach(std::size_t i, F&& f) const {
    const Run r = run(i);
    for (std::uint32_t k = r.begin; k < r.end; ++k) f(r.list[k]);
  }

  // Call f(j) for the fluid neighbours of i, then g(j) for its wall
  // neighbours (none without walls).
  template <class F, class G>
  [[gnu::always_inline]] void forEachByKind(std::size_t i, F&& f, G&& g) const {
    const Run r = run(i);
    for (std::uint32_t k = r.begin; k < r.split; ++k) f(r.list[k]);
    for (std::uint32_t k = r.split; k < r.end; ++k) g(r.list[k]);
  }

  // The neighbours of particle i as one index array: the fluid ones in
  // [row.begin, row.walls), the wall ones in [row.walls, row.end) (none
  // without walls). For a loop that takes them in blocks
  // (pair_loop_blocks.hpp); the same visit as forEachByKind.
  struct Row {
    const std::uint32_t *begin, *walls, *end;
  };
  [[gnu::always_inline]] Row row(std::size_t i) const {
    const Run r = run(i);
    return {r.list + r.begin, r.list + r.split, r.list + r.end};
  }

  // Store the list (false, the default) or walk the cells at every visit
  // (true); takes effect at the next build.
  void setCellWalk(bool on) {
    cellWalk_ = on;
    if (!on) return;
    decltype(chunks_)().swap(chunks_);
    decltype(begin_)().swap(begin_);
    decltype(wallBegin_)().swap(wallBegin_);
    used_.clear();
    usedChunks_ = 0;
  }
  bool cellWalk() const { return cellWalk_; }
  // Whether a cell walk has the grid and positions of a build (not after a
  // copy or a move of the list).
  bool bound() const { return !cellWalk_ || cells_.grid != nullptr; }

  // The neighbours of particle i (fluid and walls).
  std::uint32_t rowLength(std::size_t i) const {
    const Run r = run(i);
    return r.end - r.begin;
  }

  std::size_t pairCount() const {
    std::size_t total = 0;
    if (cellWalk_) {
      for (std::size_t i = 0; i < cells_.n; ++i) total += run(i).end;
      return total;
    }
    for (std::size_t t = 0; t < usedChunks_; ++t) total += used_[t];
    return total;
  }

  std::size_t bytesAllocated() const {
    std::size_t b = (begin_.capacity() + wallBegin_.capacity()) * sizeof(std::uint32_t) +
                    chunkStart_.capacity() * sizeof(std::size_t);
    for (const auto& c : chunks_) b += c.capacity() * sizeof(std::uint32_t);
    return b;
  }

 private:
  struct Run {
    const std::uint32_t* list;
    std::uint32_t begin, split, end;  // fluid neighbours [begin, split), walls [split, end)
  };
  [[gnu::always_inline]] Run run(std::size_t i) const {
    if (cellWalk_) return scanCells(i);
    std::size_t t = 0;
    while (i >= chunkStart_[t + 1]) ++t;
    const std::vector<std::uint32_t>& list = chunks_[t];
    const std::uint32_t end =
        i + 1 < chunkStart_[t + 1] ? begin_[i + 1] : static_cast<std::uint32_t>(used_[t]);
    return {list.data(), begin_[i], wallBegin_.empty() ? end : wallBegin_[i], end};
  }

  // The cell walk's row of particle i, scanned into the calling thread's
  // buffer exactly as build() would have listed it. (So a visit of one
  // particle's neighbours must not start another visit in the same thread:
  // no pass nests them.)
  [[gnu::noinline]] Run scanCells(std::size_t i) const {
    static thread_local Slot s;
    if (s.build != cells_.build) {
      s.build = cells_.build;
      s.stencil.valid = false;
    }
    const std::vector<Vec<D>>& x = *cells_.x;
    const Vec<D> xi = x[i];
    cells_.grid->updateStencil(xi, s.stencil);
    std::size_t used = scan(s.list, 0, i, xi, x, cells_.radius2, s.stencil.begin, s.stencil.end, s.stencil.count);
    if (byId_) orderById(s.list.data(), s.list.data() + used, *byId_, x);
    const auto split = static_cast<std::uint32_t>(used);
    if (cells_.walls && i < cells_.fluidCount)
      used = scan(s.list, used, i, xi, x, cells_.radius2, s.stencil.wallBegin, s.stencil.wallEnd,
                  s.stencil.wallCount);
    if (byId_) orderById(s.list.data() + split, s.list.data() + used, *byId_, x);
    return {s.list.data(), 0, split, static_cast<std::uint32_t>(used)};
  }

  // The cell walk's state: what build() was given. Not carried by a copy
  // or a move (it points at the grid and positions of its owner's build):
  // a moved list is unbound until its next build.
  struct CellWalk {
    CellWalk() = default;
    CellWalk(const CellWalk&) {}
    CellWalk& operator=(const CellWalk&) {
      grid = nullptr;
      x = nullptr;
      return *this;
    }
    const HashGrid<D>* grid = nullptr;
    const std::vector<Vec<D>>* x = nullptr;
    Real radius2 = 0;
    std::size_t fluidCount = 0, n = 0;
    bool walls = false;
    std::uint64_t build = 0;  // unique over every list's builds
  };
  // A thread's (thread_local: whatever the thread count, which the
  // thread tuner may change between builds); `build` tells whether its
  // stencil belongs to the current build of this list.
  struct Slot {
    std::uint64_t build = 0;
    typename HashGrid<D>::Stencil stencil;
    std::vector<std::uint32_t> list;
  };
  bool cellWalk_ = false;
  CellWalk cells_;
  const std::vector<std::int64_t>* byId_ = nullptr;  // the last build's (order by id), or nullptr

  std::vector<std::vector<std::uint32_t>> chunks_;  // one flat buffer per thread
  std::vector<std::size_t> used_;                   // entries in use per chunk
  std::vector<std::uint32_t> begin_;                // start of i's run in its chunk
  std::vector<std::uint32_t> wallBegin_;            // start of i's wall neighbours (walls only)
  std::vector<std::size_t> chunkStart_;             // first particle of each chunk
  std::size_t usedChunks_ = 0;
};

}  // namespace sph
