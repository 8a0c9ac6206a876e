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
// Packed list (neighbour_walk = packed): the build scans the same stencil
// and keeps, instead of each neighbour's index, one bit per candidate of
// the stencil's particle ranges (1: closer than the radius and not i), a
// particle's bits starting at a byte. A visit finds the particle's stencil
// again (at the positions of the build, like the cell walk) and turns the
// set bits back into indices, in the scan's order, in a small per-thread
// row: the list's pairs in the list's order, so every result is bit for bit
// the stored list's, for about an eighth of its bytes in 2D and a sixth in
// 3D (the stencil holds 3^D / (volume of the unit ball) times the
// neighbours within the radius: about 2.9 times in 2D, 6.4 in 3D, one bit
// each, against 32 bits per neighbour; plus 4 bytes a particle). Order by
// id cannot be packed: with byId the build stores the plain list.
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
#include "sph/neighbour_storage.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <vector>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace sph {

// (The packed list's bits are written and read as little-endian words.)
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the packed neighbour list assumes a little-endian machine");

template <int D>
class NeighbourList {
 public:
  // Rows for the owned particles [0, ownedCount): fluid below fluidCount.
  // (Packed list and cell walk: `x` must stay, unchanged, the positions of
  // this build until the next one: the scene passes its list_build_position.)
  // byId: order each run by these ids (above; nullptr: the scan's order).
  void build(const HashGrid<D>& grid, const std::vector<Vec<D>>& x, Real radius,
             std::size_t fluidCount = SIZE_MAX, std::size_t ownedCount = SIZE_MAX,
             const std::vector<std::int64_t>* byId = nullptr) {
    const std::size_t n = std::min(ownedCount, x.size());
    fluidCount = std::min(fluidCount, n);
    const bool walls = fluidCount < n || grid.hasWalls();
    byId_ = byId;
    packed_ = storage_ == NeighbourStorage::kPacked && !byId;
    if (storage_ != NeighbourStorage::kList) {
      static std::atomic<std::uint64_t> builds{0};
      cells_.grid = &grid;
      cells_.x = &x;
      cells_.radius2 = radius * radius;
      cells_.fluidCount = fluidCount;
      cells_.n = n;
      cells_.walls = walls;
      cells_.build = ++builds;  // the grid changed
      if (storage_ == NeighbourStorage::kCells) return;
    }
    if (packed_) {
      buildPacked(grid, x, radius * radius, fluidCount, n, walls);
      return;
    }
    if (walls) wallBegin_.resize(n);
    else std::vector<std::uint32_t>().swap(wallBegin_);
    const Real radius2 = radius * radius;
    const auto bound = [&](std::size_t i, typename HashGrid<D>::Stencil& stencil) {
      grid.updateStencil(x[i], stencil);
      return candidates(stencil, walls && i < fluidCount);
    };
    buildChunks(chunks_, n, kListShare, bound, [&](std::size_t i, std::vector<std::uint32_t>& list, std::size_t used,
                                       typename HashGrid<D>::Stencil& stencil) {
      const std::size_t start = used;
      const Vec<D> xi = x[i];
      grid.updateStencil(xi, stencil);
      used = scan(list, used, i, xi, x, radius2, stencil.begin, stencil.end, stencil.count);
      if (byId) orderById(list.data() + start, list.data() + used, *byId, x);
      if (!walls) return used;
      const std::size_t split = used;
      wallBegin_[i] = static_cast<std::uint32_t>(split);
      if (i < fluidCount)
        used = scan(list, used, i, xi, x, radius2, stencil.wallBegin, stencil.wallEnd, stencil.wallCount);
      if (byId) orderById(list.data() + split, list.data() + used, *byId, x);
      return used;
    });
  }

 private:
  // The particles split into one contiguous chunk per thread, each chunk's
  // rows appended to the thread's buffer: fill = row(i, buffer, fill,
  // stencil) for each particle i of the chunk, in order, begin_[i] the fill
  // before it.
  //
  // A buffer's first build reserves `share` of the sum of bound(i,
  // stencil), its particles' candidates, over its chunk: about what it will
  // fill, a quarter more. Grown a quarter at a time from nothing instead,
  // the buffer was copied a dozen times, and each copy held the old buffer
  // and the new at once, twice the list's memory at the run's peak (70
  // bytes per particle in 2D). The part never filled is not written and
  // takes no memory (grow()); reserving every candidate would take address
  // space, 3 (2D) to 6 (3D) times the list's, which an address-space limit
  // (ulimit -v, strict overcommit) refuses.
  template <class Buffer, class Bound, class Row>
  void buildChunks(std::vector<Buffer>& buffers, std::size_t n, double share, Bound&& bound, Row&& row) {
    const auto threads = static_cast<std::size_t>(omp_get_max_threads());
    if (buffers.size() < threads) buffers.resize(threads);
    if (used_.size() < threads) used_.resize(threads);
    begin_.resize(n + 1);
    chunkStart_.assign(threads + 1, n);
    usedChunks_ = 0;
#pragma omp parallel if (n >= kMinParallelSize)
    {
      const auto t = static_cast<std::size_t>(omp_get_thread_num());
      const auto nt = static_cast<std::size_t>(omp_get_num_threads());
      const std::size_t lo = n * t / nt, hi = n * (t + 1) / nt;
      Buffer& buffer = buffers[t];
      std::size_t used = 0;
      typename HashGrid<D>::Stencil stencil;
      if (buffer.capacity() == 0) {
        std::size_t entries = 0;
        for (std::size_t i = lo; i < hi; ++i) entries += bound(i, stencil);
        buffer.reserve(static_cast<std::size_t>(share * static_cast<double>(entries)) + kAhead + 64);
      }
      for (std::size_t i = lo; i < hi; ++i) {
        begin_[i] = static_cast<std::uint32_t>(used);
        used = row(i, buffer, used, stencil);
      }
      used_[t] = used;
      chunkStart_[t] = lo;
#pragma omp single
      usedChunks_ = nt;
    }
    chunkStart_[usedChunks_] = n;
  }

  // The packed build: as the list's, but each candidate of a particle's
  // stencil ranges leaves one bit, fluid ranges then wall ranges (walls only
  // for a fluid particle), in the order of the scan; a particle's bits start
  // at a byte of its thread's buffer (begin_), which keeps 8 spare bytes at
  // its end for the visit's 8-byte reads.
  void buildPacked(const HashGrid<D>& grid, const std::vector<Vec<D>>& x, Real radius2, std::size_t fluidCount,
                   std::size_t n, bool walls) {
    std::vector<std::uint32_t>().swap(wallBegin_);
    // A particle's bits fill whole bytes, 16 more for the 8-byte writes.
    const auto bound = [&](std::size_t i, typename HashGrid<D>::Stencil& stencil) {
      grid.updateStencil(x[i], stencil);
      return candidates(stencil, walls && i < fluidCount) / 8 + 1;
    };
    buildChunks(packedChunks_, n, 1.0, bound, [&](std::size_t i, std::vector<std::uint8_t>& bytes, std::size_t used,
                                             typename HashGrid<D>::Stencil& stencil) {
      const Vec<D> xi = x[i];
      grid.updateStencil(xi, stencil);
      const bool wallRanges = walls && i < fluidCount;
      const std::size_t need = used + candidates(stencil, wallRanges) / 8 + 16;
      if (need > bytes.size()) grow(bytes, need);
      BitWriter out{bytes.data() + used};
      packBits(out, i, xi, x, radius2, stencil.begin, stencil.end, stencil.count);
      if (wallRanges) packBits(out, i, xi, x, radius2, stencil.wallBegin, stencil.wallEnd, stencil.wallCount);
      return static_cast<std::size_t>(out.flush() - bytes.data());
    });
  }

  // Bits appended one at a time, whole 64-bit words written as they fill.
  struct BitWriter {
    std::uint8_t* out;
    std::uint64_t word = 0;
    unsigned bits = 0;
    [[gnu::always_inline]] void put(std::uint64_t bit) {
      word |= bit << bits;
      if (++bits == 64) {
        std::memcpy(out, &word, 8);
        out += 8;
        word = 0;
        bits = 0;
      }
    }
    // Write the last, partial word's bytes; returns the end.
    std::uint8_t* flush() {
      std::memcpy(out, &word, 8);  // the buffer has 8 spare bytes
      return out + (bits + 7) / 8;
    }
  };

  static void packBits(BitWriter& out, std::size_t i, const Vec<D>& xi, const std::vector<Vec<D>>& x, Real radius2,
                       const std::uint32_t* begin, const std::uint32_t* end, int ranges) {
    for (int s = 0; s < ranges; ++s)
      for (std::uint32_t j = begin[s]; j < end[s]; ++j)
        out.put(static_cast<std::uint64_t>((Vec<D>(xi - x[j]).squaredNorm() < radius2) & (j != i)));
  }

 public:
  // Append to row[used...] the indices whose bits are set among the
  // candidates of the ranges [begin[s], end[s]), read from `bits` at bit
  // `position` (advanced past them); returns the new fill. `bits` has 8
  // readable bytes past the last one it holds (the build keeps them).
  [[gnu::always_inline]] static std::size_t unpackBits(std::vector<std::uint32_t>& row, std::size_t used,
                                                       const std::uint8_t* bits, std::size_t& position,
                                                       const std::uint32_t* begin, const std::uint32_t* end,
                                                       int ranges) {
#if defined(__AVX512F__)
    for (int s = 0; s < ranges; ++s) {
      const std::uint32_t b = begin[s], e = end[s];
      if (used + (e - b) + 16 > row.size()) row.resize(used + (e - b) + 64);
      std::uint32_t* out = row.data();
      // 16 candidates at a time, without a branch per neighbour: the lanes
      // j0 + 0..15, compressed by their bits, stored whole (the row keeps 16
      // spare entries), the fill advanced by the count.
      const __m512i lanes = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
      for (std::uint32_t j0 = b; j0 < e; j0 += 16) {
        const unsigned length = std::min<std::uint32_t>(16, e - j0);
        std::uint32_t word;
        std::memcpy(&word, bits + position / 8, 4);
        const auto mask = static_cast<__mmask16>((word >> (position % 8)) & ((1u << length) - 1));
        position += length;
        const __m512i j = _mm512_add_epi32(lanes, _mm512_set1_epi32(static_cast<int>(j0)));
        _mm512_storeu_si512(out + used, _mm512_maskz_compress_epi32(mask, j));
        used += static_cast<std::size_t>(__builtin_popcount(mask));
      }
    }
    return used;
#else
    return unpackBitsLoop(row, used, bits, position, begin, end, ranges);
#endif
  }

  // The same, one set bit at a time (the portable build's; tests compare
  // the two).
  static std::size_t unpackBitsLoop(std::vector<std::uint32_t>& row, std::size_t used, const std::uint8_t* bits,
                                    std::size_t& position, const std::uint32_t* begin, const std::uint32_t* end,
                                    int ranges) {
    for (int s = 0; s < ranges; ++s) {
      const std::uint32_t b = begin[s], e = end[s];
      if (used + (e - b) + 16 > row.size()) row.resize(used + (e - b) + 64);
      std::uint32_t* out = row.data();
      for (std::uint32_t j0 = b; j0 < e; j0 += 56) {
        const unsigned length = std::min<std::uint32_t>(56, e - j0);
        std::uint64_t word;
        std::memcpy(&word, bits + position / 8, 8);
        word = (word >> (position % 8)) & ((std::uint64_t(1) << length) - 1);
        position += length;
        for (; word; word &= word - 1) out[used++] = j0 + static_cast<std::uint32_t>(__builtin_ctzll(word));
      }
    }
    return used;
  }

  // The particles a stencil's ranges hold (the wall ranges too if asked):
  // every candidate a row scans.
  static std::size_t candidates(const typename HashGrid<D>::Stencil& stencil, bool wallRanges) {
    std::size_t c = 0;
    for (int s = 0; s < stencil.count; ++s) c += stencil.end[s] - stencil.begin[s];
    if (wallRanges)
      for (int s = 0; s < stencil.wallCount; ++s) c += stencil.wallEnd[s] - stencil.wallBegin[s];
    return c;
  }

  // Append to list[used...] the neighbours of xi in the particle ranges
  // [begin[s], end[s]); returns the new fill. Branch-free: write always,
  // advance only for a neighbour.
  static std::size_t scan(std::vector<std::uint32_t>& list, std::size_t used, std::size_t i, const Vec<D>& xi,
                          const std::vector<Vec<D>>& x, Real radius2, const std::uint32_t* begin,
                          const std::uint32_t* end, int ranges) {
    for (int s = 0; s < ranges; ++s) {
      const std::uint32_t b = begin[s], e = end[s];
      if (used + (e - b) > list.size()) grow(list, used + (e - b));
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

  // Room for `need` entries. The size (the part ever written) runs 4096
  // entries ahead of the need; the capacity, when it must grow, a quarter
  // more (resize alone would double it, and the buffer is the largest array
  // of a run). So a steady run does not reallocate at every build, and the
  // capacity it never fills is never written: its memory pages are never
  // touched, and take no memory.
  static constexpr std::size_t kAhead = 4096;
  // The share of a particle's candidates (the 3^D cells of edge R around
  // it) closer than R, in a uniform fluid: the disc's pi R^2 over 9 R^2,
  // the ball's 4/3 pi R^3 over 27 R^3; a quarter more for what a list
  // reserves at its first build (buildChunks; packed, one bit per
  // candidate, reserves them all).
  static constexpr double kListShare = 1.25 * (D == 2 ? M_PI / 9 : 4 * M_PI / 81);
  template <class T>
  static void grow(std::vector<T>& list, std::size_t need) {
    if (need + kAhead > list.capacity()) list.reserve(need + kAhead + need / 4);
    list.resize(need + kAhead);
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

  // Store the list (the default), pack it, or walk the cells at every
  // visit; takes effect at the next build.
  // Until then the list is empty and, packed or cells, unbound.
  void setStorage(NeighbourStorage storage) {
    storage_ = storage;
    packed_ = false;
    cells_ = CellWalk();
    usedChunks_ = 0;
    if (storage != NeighbourStorage::kPacked) decltype(packedChunks_)().swap(packedChunks_);
    if (storage == NeighbourStorage::kList) return;
    decltype(chunks_)().swap(chunks_);
    decltype(wallBegin_)().swap(wallBegin_);
    if (storage == NeighbourStorage::kCells) decltype(begin_)().swap(begin_);
    used_.clear();
  }
  NeighbourStorage storage() const { return storage_; }
  bool cellWalk() const { return storage_ == NeighbourStorage::kCells; }
  // Whether the visits need the positions of the build (xList) unchanged
  // until the next one: the packed list and the cell walk find a
  // particle's stencil from them.
  bool visitsBuildPositions() const { return storage_ != NeighbourStorage::kList; }
  // Whether a packed list or a cell walk has the grid and positions of a
  // build (not after a copy or a move of the list).
  bool bound() const { return !visitsBuildPositions() || cells_.grid != nullptr; }

  // The neighbours of particle i (fluid and walls).
  std::uint32_t rowLength(std::size_t i) const {
    const Run r = run(i);
    return r.end - r.begin;
  }

  std::size_t pairCount() const {
    std::size_t total = 0;
    if (cellWalk()) {
      for (std::size_t i = 0; i < cells_.n; ++i) total += run(i).end;
      return total;
    }
    if (packed_) {
      for (std::size_t t = 0; t < usedChunks_; ++t)
        for (std::size_t k = 0; k < used_[t]; ++k) total += static_cast<std::size_t>(__builtin_popcount(packedChunks_[t][k]));
      return total;
    }
    for (std::size_t t = 0; t < usedChunks_; ++t) total += used_[t];
    return total;
  }

  // The buffers count by their size, the part ever written: the capacity
  // beyond it is reserved, never touched, and takes no memory (grow()).
  std::size_t bytesAllocated() const {
    std::size_t b = (begin_.capacity() + wallBegin_.capacity()) * sizeof(std::uint32_t) +
                    chunkStart_.capacity() * sizeof(std::size_t);
    for (const auto& c : chunks_) b += c.size() * sizeof(std::uint32_t);
    for (const auto& c : packedChunks_) b += c.size();
    return b;
  }

 private:
  struct Run {
    const std::uint32_t* list;
    std::uint32_t begin, split, end;  // fluid neighbours [begin, split), walls [split, end)
  };
  [[gnu::always_inline]] Run run(std::size_t i) const {
    if (cellWalk()) return scanCells(i);
    std::size_t t = 0;
    while (i >= chunkStart_[t + 1]) ++t;
    if (packed_) return unpackRow(i, t);
    const std::vector<std::uint32_t>& list = chunks_[t];
    const std::uint32_t end =
        i + 1 < chunkStart_[t + 1] ? begin_[i + 1] : static_cast<std::uint32_t>(used_[t]);
    return {list.data(), begin_[i], wallBegin_.empty() ? end : wallBegin_[i], end};
  }

  // The row of particle i, rebuilt from its stencil at the build's
  // positions into the calling thread's buffer: used = fill(row, used,
  // begin, end, ranges) for the fluid ranges, then (a fluid particle) the
  // wall ranges. (So a visit of one particle's neighbours must not start
  // another visit in the same thread: no pass nests them.)
  template <class Fill>
  [[gnu::always_inline]] Run rowFromStencil(std::size_t i, Fill&& fill) const {
    static thread_local Slot s;
    if (s.build != cells_.build) {
      s.build = cells_.build;
      s.stencil.valid = false;
    }
    cells_.grid->updateStencil((*cells_.x)[i], s.stencil);
    std::size_t used = fill(s.list, 0, s.stencil.begin, s.stencil.end, s.stencil.count);
    const auto split = static_cast<std::uint32_t>(used);
    if (cells_.walls && i < cells_.fluidCount)
      used = fill(s.list, used, s.stencil.wallBegin, s.stencil.wallEnd, s.stencil.wallCount);
    return {s.list.data(), 0, split, static_cast<std::uint32_t>(used)};
  }

  // The cell walk's row: the build's own scan (and order by id), again.
  [[gnu::noinline]] Run scanCells(std::size_t i) const {
    const std::vector<Vec<D>>& x = *cells_.x;
    const Vec<D> xi = x[i];
    return rowFromStencil(i, [&](std::vector<std::uint32_t>& row, std::size_t used, const std::uint32_t* begin,
                                 const std::uint32_t* end, int ranges) {
      const std::size_t filled = scan(row, used, i, xi, x, cells_.radius2, begin, end, ranges);
      if (byId_) orderById(row.data() + used, row.data() + filled, *byId_, x);
      return filled;
    });
  }

  // The packed list's row: particle i's bits (in chunk t), unpacked.
  [[gnu::noinline]] Run unpackRow(std::size_t i, std::size_t t) const {
    const std::uint8_t* bits = packedChunks_[t].data() + begin_[i];
    std::size_t position = 0;
    return rowFromStencil(i, [&](std::vector<std::uint32_t>& row, std::size_t used, const std::uint32_t* begin,
                                 const std::uint32_t* end, int ranges) {
      return unpackBits(row, used, bits, position, begin, end, ranges);
    });
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
  NeighbourStorage storage_ = NeighbourStorage::kList;
  bool packed_ = false;  // the last build packed its pairs
  CellWalk cells_;
  const std::vector<std::int64_t>* byId_ = nullptr;  // the last build's (order by id), or nullptr

  std::vector<std::vector<std::uint32_t>> chunks_;  // one flat buffer per thread
  std::vector<std::vector<std::uint8_t>> packedChunks_;  // packed: one bit buffer per thread
  std::vector<std::size_t> used_;                   // entries in use per chunk
  std::vector<std::uint32_t> begin_;                // start of i's run in its chunk
  std::vector<std::uint32_t> wallBegin_;            // start of i's wall neighbours (walls only)
  std::vector<std::size_t> chunkStart_;             // first particle of each chunk
  std::size_t usedChunks_ = 0;
};

}  // namespace sph
