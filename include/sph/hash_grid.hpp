// HashGrid<D>: hashed cell grid for fixed-radius neighbour search.
//
// Space is cut into cubic cells of edge `cellSize` (the kernel support), so
// every neighbour of a particle lies in its own cell or one of the 3^D - 1
// adjacent cells. Cell coordinates c = floor(x / cellSize) are hashed into a
// table of buckets (spatial hashing as in Teschner et al. 2003, "Optimized
// spatial hashing for collision detection of deformable objects"), so the
// domain needs no bounds and memory grows with N, not with volume. The hash
// is the row-major index of the cell in the particles' bounding box, modulo
// the table size:
//   bucket = (c0 - m0 + 1) + (c1 - m1 + 1) s1 + (c2 - m2 + 1) s2   mod T
// (m: lowest cell, s: row and plane strides of the box; a cell outside the
// box, which holds no particle, wraps around as an unsigned 64-bit number
// first). Unlike the xor hash it keeps the three cells of a stencil row in
// consecutive buckets, so their particles are one contiguous run in
// memory. T is the box's cells exactly when they are at most 2 n (n: the
// particles of the table's kind, below): then the bucket is the cell's
// row-major index itself, collision-free; else the power of two at or
// above 2 n (at least 64).
//
// build() counting-sorts the particles by bucket; after the caller applies
// order() to the particle arrays, the particles of bucket b are the contiguous
// range [cellStart[b], cellStart[b+1]). A Stencil lists the particle ranges
// around one cell (NeighbourList scans them). Two cells may share a bucket:
// the distance test filters the extra candidates, and a bucket shared by two
// stencil cells is listed only once.
//
// The grid knows no periodic axes: across a periodic face the neighbours
// are ghost particles (periodic_ghosts.hpp), binned like any other.
//
// Kinds: each kind of particle present gets a table of buckets of its own,
// sized by its own count, after the previous kind's: fluid, walls (from
// index `fluidCount`), ghosts of fluid (from `ownedCount`), ghosts of walls
// (from `ghostFluidEnd`). So the sort keeps every wall after every fluid
// particle and every ghost after the owned ones, and a Stencil lists the
// fluid ranges (owned, then ghosts) and the wall ranges (owned, then
// ghosts) around a cell separately. Without walls and ghosts there is one
// table. (The walls of a tank are few beside its fluid and fill few of the
// box's cells: their table, the power of two at or above 2 n_walls instead
// of the box's cells, cut the grid of the 2D dam break at 214 910 particles
// from 27.5 to about 15 bytes per particle.) The particles' order, and so
// the order of every neighbour sum, is the row-major order of their cells
// wherever a kind's table is the box's cells; where it wraps around it is
// another (the walls' of a fine 2D tank: the same results by particle;
// the fluid's, when it fills less than half the box's cells: runs part at
// round-off from those with one table size for all kinds).
#pragma once

#include "sph/types.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace sph {

template <int D>
class HashGrid {
 public:
  static constexpr int stencilSize = D == 2 ? 9 : 27;

  // `support`: largest interaction distance. The cell is a hair larger so that
  // rounding in floor(x / cellSize) can never put a pair closer than `support`
  // two cells apart.
  explicit HashGrid(Real support)
      : cellSize_(support * (1 + 1e-9)), invCell_(1 / cellSize_) {
    for (int s = 0; s < stencilSize; ++s) {
      int rest = s;
      for (int d = 0; d < D; ++d, rest /= 3) stencil_[s][d] = rest % 3 - 1;
    }
  }

  // Sort particles by bucket. Afterwards order()[k] is the old index of the
  // particle that goes to position k; apply it with Particles::permute().
  // Particles [fluidCount, ownedCount) are walls, [ownedCount,
  // ghostFluidEnd) ghosts of fluid and [ghostFluidEnd, n) ghosts of walls
  // (none of each by default). bucketSpace: at least 4 n bytes the caller
  // lends for each particle's bucket number, which only the sort reads
  // (the scene lends the particles' re-sort scratch, idle until the
  // permute() that follows: 4 bytes per particle fewer); nullptr: the
  // grid's own array.
  void build(const std::vector<Vec<D>>& x, std::size_t fluidCount = SIZE_MAX, std::size_t ownedCount = SIZE_MAX,
             std::size_t ghostFluidEnd = SIZE_MAX, unsigned char* bucketSpace = nullptr) {
    const std::size_t n = x.size();
    ownedCount = std::min(ownedCount, n);
    fluidCount = std::min(fluidCount, ownedCount);
    ghostFluidEnd = std::clamp(ghostFluidEnd, ownedCount, n);
    setStrides(x);
    // The kinds' tables, one after the other: each sized by its count.
    const std::size_t end[kKinds] = {fluidCount, ownedCount, ghostFluidEnd, n};
    std::size_t used = 0, from = 0;
    for (int k = 0; k < kKinds; ++k) {
      const std::size_t count = end[k] - from;
      from = end[k];
      table_[k] = {};
      if (count == 0 && k != kFluid) continue;  // absent: size 0
      table_[k].offset = static_cast<std::uint32_t>(used);
      table_[k].size = tableSizeFor(count, boxCells_);
      used += table_[k].size;
    }
    if (used >= UINT32_MAX) throw std::length_error("HashGrid: 2^32 - 1 buckets or more");
    if (cellStart_.size() != used + 1) cellStart_.assign(used + 1, 0);
    if (!bucketSpace) {
      bucket_.resize(n);
      bucketSpace = reinterpret_cast<unsigned char*>(bucket_.data());
    }
    // (Through memcpy: the lent bytes held other types before.)
    const auto setBucket = [bucketSpace](std::size_t i, std::uint32_t b) {
      std::memcpy(bucketSpace + i * sizeof b, &b, sizeof b);
    };
    const auto bucketOf = [bucketSpace](std::size_t i) {
      std::uint32_t b;
      std::memcpy(&b, bucketSpace + i * sizeof b, sizeof b);
      return b;
    };
    order_.resize(n);
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i) {
      const Kind k = i < fluidCount ? kFluid : i < ownedCount ? kWalls : i < ghostFluidEnd ? kFluidGhosts : kWallGhosts;
      setBucket(i, bucketIn(table_[k], hashOf(cellOf(x[i]))));
    }

    // Counting sort, stable: count, inclusive prefix sum (cellStart_[b] = end
    // of bucket b), then scatter backwards so cellStart_[b] becomes its start.
    const std::size_t buckets = cellStart_.size() - 1;
    std::fill(cellStart_.begin(), cellStart_.end(), 0u);
    for (std::size_t i = 0; i < n; ++i) ++cellStart_[bucketOf(i)];
    for (std::size_t b = 1; b < buckets; ++b) cellStart_[b] += cellStart_[b - 1];
    cellStart_[buckets] = static_cast<std::uint32_t>(n);
    for (std::size_t i = n; i-- > 0;) order_[--cellStart_[bucketOf(i)]] = static_cast<std::uint32_t>(i);
  }

  const std::vector<std::uint32_t>& order() const { return order_; }
  // Whether the last build() had walls, owned or ghosts (a rank of a
  // decomposition may hold halos of walls and no walls of its own).
  bool hasWalls() const { return table_[kWalls].size != 0 || table_[kWallGhosts].size != 0; }

  // The particle ranges of the (distinct) buckets around one cell. Particles
  // of the same cell share it, so loops over sorted particles compute it once
  // per cell instead of once per particle.
  struct Stencil {
    IVec<D> cell;
    bool valid = false;
    int count = 0, wallCount = 0;  // fluid ranges, then wall ranges (owned, then ghosts)
    std::uint32_t begin[2 * stencilSize], end[2 * stencilSize];
    std::uint32_t wallBegin[2 * stencilSize], wallEnd[2 * stencilSize];
  };

  // Update `st` to the stencil of the cell holding x, recomputing only when
  // the cell differs from the one it already describes.
  void updateStencil(const Vec<D>& x, Stencil& st) const {
    const IVec<D> c = cellOf(x);
    if (!st.valid || c != st.cell) stencilAt(c, st);
  }

  std::size_t bytesAllocated() const {
    return (cellStart_.capacity() + bucket_.capacity() +
            order_.capacity()) * sizeof(std::uint32_t);
  }

 private:
  // A kind's table: the box's cells exactly when they are at most 2 n (no
  // two cells share a bucket, and each bucket is the cell's row-major index
  // in the box); else a power of two, at least 2 n buckets (at least 64).
  // The box's cells are far fewer than 2 n when n particles fill it (a tenth
  // of n when a cell holds ten).
  struct Table {
    std::uint32_t offset = 0;  // its first bucket
    std::size_t size = 0;      // its buckets
  };
  static std::size_t tableSizeFor(std::size_t n, double boxCells) {
    const double need = 2.0 * static_cast<double>(n);
    if (boxCells <= need) return static_cast<std::size_t>(boxCells);
    std::size_t t = 64;
    while (static_cast<double>(t) < need) t *= 2;
    return t;
  }

  // The bucket of a hash in a table: the hash itself in a table of the box's
  // cells (a cell outside the box, which holds no particle, wraps around).
  static std::uint32_t bucketIn(const Table& t, std::uint64_t hash) {
    const std::uint64_t inTable = hash < t.size ? hash : hash % t.size;
    return t.offset + static_cast<std::uint32_t>(inTable);
  }

  IVec<D> cellOf(const Vec<D>& x) const {
    IVec<D> c;
    for (int d = 0; d < D; ++d) c[d] = floorToInt(x[d] * invCell_);
    return c;
  }

  // floor() without the libm call: truncate, then step down for negatives.
  static std::int64_t floorToInt(Real s) {
    const auto t = static_cast<std::int64_t>(s);
    return t - (static_cast<Real>(t) > s);
  }

  void stencilAt(const IVec<D>& c, Stencil& st) const {
    st.cell = c;
    st.valid = true;
    std::uint64_t hash[stencilSize];
    for (int s = 0; s < stencilSize; ++s) hash[s] = hashOf(IVec<D>(c + stencil_[s]));
    st.count = ranges(hash, table_[kFluid], st.begin, st.end, 0);
    if (table_[kFluidGhosts].size) st.count = ranges(hash, table_[kFluidGhosts], st.begin, st.end, st.count);
    st.wallCount = table_[kWalls].size ? ranges(hash, table_[kWalls], st.wallBegin, st.wallEnd, 0) : 0;
    if (table_[kWallGhosts].size)
      st.wallCount = ranges(hash, table_[kWallGhosts], st.wallBegin, st.wallEnd, st.wallCount);
  }

  // Append to begin/end[count...] the non-empty particle ranges of the
  // stencil's buckets in table t (a bucket two cells share, once), merged
  // where one directly follows the previous one. Returns the new number of
  // ranges.
  int ranges(const std::uint64_t (&hash)[stencilSize], const Table& t, std::uint32_t* begin, std::uint32_t* end,
             int count) const {
    std::uint32_t seen[stencilSize];
    int nSeen = 0;
    for (int s = 0; s < stencilSize; ++s) {
      const std::uint32_t b = bucketIn(t, hash[s]);
      bool dup = false;
      for (int k = 0; k < nSeen; ++k) dup |= seen[k] == b;
      if (dup) continue;
      seen[nSeen++] = b;
      if (cellStart_[b] == cellStart_[b + 1]) continue;
      if (count > 0 && end[count - 1] == cellStart_[b]) {
        end[count - 1] = cellStart_[b + 1];
        continue;
      }
      begin[count] = cellStart_[b];
      end[count] = cellStart_[b + 1];
      ++count;
    }
    return count;
  }

  // Lowest cell and strides of the particles' bounding box (one cell of
  // margin on each side, for the stencil).
  void setStrides(const std::vector<Vec<D>>& x) {
    const std::size_t n = x.size();
    Real lo[D], hi[D];
    for (int d = 0; d < D; ++d) lo[d] = hi[d] = n ? x[0][d] : 0;
#pragma omp parallel for schedule(static) reduction(min : lo[:D]) reduction(max : hi[:D]) if (n >= kMinParallelSize)
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < D; ++d) {
        lo[d] = std::min(lo[d], x[i][d]);
        hi[d] = std::max(hi[d], x[i][d]);
      }
    const IVec<D> cLo = cellOf(Eigen::Map<const Vec<D>>(lo)), cHi = cellOf(Eigen::Map<const Vec<D>>(hi));
    origin_ = cLo - IVec<D>::Ones();
    std::uint64_t stride = 1;
    boxCells_ = 1;
    for (int d = 0; d < D; ++d) {
      stride_[d] = stride;
      stride *= static_cast<std::uint64_t>(cHi[d] - cLo[d] + 3);
      boxCells_ *= static_cast<double>(cHi[d] - cLo[d] + 3);  // exact below 2^53, never wraps
    }
  }

  // The cell's row-major index in the box (wrapping around, as unsigned,
  // for a cell outside it).
  std::uint64_t hashOf(const IVec<D>& c) const {
    std::uint64_t hash = 0;
    for (int d = 0; d < D; ++d) hash += static_cast<std::uint64_t>(c[d] - origin_[d]) * stride_[d];
    return hash;
  }

  Real cellSize_;
  Real invCell_;
  IVec<D> stencil_[stencilSize];  // cell offsets {-1, 0, 1}^D, x fastest
  IVec<D> origin_ = IVec<D>::Zero();
  std::uint64_t stride_[D] = {};
  double boxCells_ = 0;  // cells of the bounding box, margins included
  // The kinds' tables, in this order; a kind absent from the last build has
  // a table of size 0 (the fluid's is always there).
  enum Kind { kFluid, kWalls, kFluidGhosts, kWallGhosts, kKinds };
  Table table_[kKinds];
  std::vector<std::uint32_t> cellStart_;  // bucket b: [cellStart_[b], cellStart_[b+1])
  std::vector<std::uint32_t> bucket_;  // the bucket numbers when build() is lent no space
  std::vector<std::uint32_t> order_;
};

}  // namespace sph
