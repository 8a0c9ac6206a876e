// NeighbourList<D>: every pair (i, j != i) closer than the support radius,
// found once per step from the hashed grid and shared by all passes (density,
// forces, diagnostics), so the cell stencil is scanned once, not per pass.
//
// Storage is CSR per thread: the particles are split into one contiguous
// chunk per OpenMP thread; thread t appends the neighbours of its chunk to its
// own flat buffer and records where each particle's run begins. Buffers keep
// their capacity between steps, so a steady run does not allocate.
// Each particle's neighbours keep the order of the grid scan, so results do
// not depend on the number of threads.
#pragma once

#include "sph/hash_grid.hpp"

#include <omp.h>

#include <cstdint>
#include <vector>

namespace sph {

template <int D>
class NeighbourList {
 public:
  void build(const HashGrid<D>& grid, const std::vector<Vec<D>>& x, Real radius) {
    const std::size_t n = x.size();
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
        begin_[i] = static_cast<std::uint32_t>(used);
        const Vec<D> xi = x[i];
        grid.updateStencil(xi, stencil);
        for (int s = 0; s < stencil.count; ++s) {
          const std::uint32_t b = stencil.begin[s], e = stencil.end[s];
          if (used + (e - b) > list.size()) list.resize(used + (e - b) + used / 4 + 64);
          // Branch-free append: write always, advance only for a neighbour.
          for (std::uint32_t j = b; j < e; ++j) {
            list[used] = j;
            used += ((xi - x[j]).squaredNorm() < radius2) & (j != i);
          }
        }
      }
      used_[t] = used;
      chunkStart_[t] = lo;
#pragma omp single
      usedChunks_ = nt;
    }
    chunkStart_[usedChunks_] = n;
  }

  // Call f(j) for every neighbour j of particle i.
  template <class F>
  void forEach(std::size_t i, F&& f) const {
    std::size_t t = 0;
    while (i >= chunkStart_[t + 1]) ++t;
    const std::vector<std::uint32_t>& list = chunks_[t];
    const std::uint32_t end =
        i + 1 < chunkStart_[t + 1] ? begin_[i + 1] : static_cast<std::uint32_t>(used_[t]);
    for (std::uint32_t k = begin_[i]; k < end; ++k) f(list[k]);
  }

  std::size_t pairCount() const {
    std::size_t total = 0;
    for (std::size_t t = 0; t < usedChunks_; ++t) total += used_[t];
    return total;
  }

  std::size_t bytesAllocated() const {
    std::size_t b = begin_.capacity() * sizeof(std::uint32_t) + chunkStart_.capacity() * sizeof(std::size_t);
    for (const auto& c : chunks_) b += c.capacity() * sizeof(std::uint32_t);
    return b;
  }

 private:
  std::vector<std::vector<std::uint32_t>> chunks_;  // one flat buffer per thread
  std::vector<std::size_t> used_;                   // entries in use per chunk
  std::vector<std::uint32_t> begin_;                // start of i's run in its chunk
  std::vector<std::size_t> chunkStart_;             // first particle of each chunk
  std::size_t usedChunks_ = 0;
};

}  // namespace sph
