// Particles<D>: the particle state as a structure of arrays.
//
// One contiguous array per field, indexed by particle. Fields that a model
// does not use are left empty (size 0) so they cost no memory.
//
// State fields (x, v, vHalf, m, id) define the particles; derived fields
// (rho, p, a) are recomputed from them after every neighbour sort. permute()
// therefore reorders the state fields only: derived fields are stale after a
// permute until the model recomputes them. The scratch buffers are kept
// between calls, so the step loop never allocates.
#pragma once

#include "sph/types.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sph {

template <int D>
struct Particles {
  std::vector<Vec<D>> x;       // position [m]
  std::vector<Vec<D>> v;       // velocity at integer time [m/s]
  std::vector<Vec<D>> vHalf;   // leap-frog half-step velocity [m/s]
  std::vector<Vec<D>> a;       // acceleration [m/s^2]
  std::vector<Real> rho;       // density [kg/m^D]
  std::vector<Real> p;         // pressure [Pa in 3D, Pa m in 2D]
  std::vector<Real> m;         // mass [kg]
  std::vector<std::int64_t> id;  // stable identity, kept through re-sorts

  std::size_t size() const { return x.size(); }

  // Size every field for n particles; x, v, m, id are expected to be set.
  void resize(std::size_t n) {
    x.resize(n);
    v.resize(n, Vec<D>::Zero());
    vHalf.resize(n, Vec<D>::Zero());
    a.resize(n, Vec<D>::Zero());
    rho.resize(n, 0);
    p.resize(n, 0);
    m.resize(n, 0);
    id.resize(n, 0);
  }

  void shrinkToFit() {
    x.shrink_to_fit(), v.shrink_to_fit(), vHalf.shrink_to_fit(), a.shrink_to_fit();
    rho.shrink_to_fit(), p.shrink_to_fit(), m.shrink_to_fit(), id.shrink_to_fit();
  }

  // Reorder all fields so that new particle k is old particle order[k].
  void permute(const std::vector<std::uint32_t>& order) {
    permuteField(x, order, scratchVec_);
    permuteField(v, order, scratchVec_);
    permuteField(vHalf, order, scratchVec_);
    permuteField(m, order, scratchReal_);
    permuteField(id, order, scratchId_);
  }

  std::size_t bytesAllocated() const {
    return (x.capacity() + v.capacity() + vHalf.capacity() + a.capacity() +
            scratchVec_.capacity()) * sizeof(Vec<D>) +
           (rho.capacity() + p.capacity() + m.capacity() +
            scratchReal_.capacity()) * sizeof(Real) +
           (id.capacity() + scratchId_.capacity()) * sizeof(std::int64_t);
  }

 private:
  template <class T>
  static void permuteField(std::vector<T>& field,
                           const std::vector<std::uint32_t>& order,
                           std::vector<T>& scratch) {
    if (field.empty()) return;
    scratch.resize(field.size());
    const std::size_t n = field.size();
#pragma omp parallel for schedule(static) if (n >= kMinParallelSize)
    for (std::size_t k = 0; k < n; ++k) scratch[k] = field[order[k]];
    field.swap(scratch);
  }

  std::vector<Vec<D>> scratchVec_;
  std::vector<Real> scratchReal_;
  std::vector<std::int64_t> scratchId_;
};

}  // namespace sph
