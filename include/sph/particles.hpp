// Particles<D>: the particle state as a structure of arrays.
//
// One contiguous array per field, indexed by particle. The core fields (x, v,
// a, rho, p, m, id) always exist; the optional ones are allocated only when
// the model or the integrator of a scene asks for them (FieldNeeds), so a
// scene pays no memory for what it does not use.
//
// State fields (x, v, m, id, and the integrator's own arrays vHalf, x0, v0,
// dx, dv) define the particles; derived fields (a, rho, p, c, vXsph) are
// recomputed from them after every neighbour sort. permute() therefore
// reorders the state fields only: derived fields are stale after a permute
// until the model recomputes them. The scratch buffers are kept between
// calls, so the step loop never allocates.
#pragma once

#include "sph/types.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sph {

// Optional per-particle arrays, requested by a model or an integrator.
struct FieldNeeds {
  bool halfStepVelocity = false;  // leap-frog: vHalf
  bool soundSpeed = false;        // Monaghan viscosity, adaptive dt: c
  bool xsph = false;              // XSPH: vXsph
  bool rungeKutta = false;        // RK4: x0, v0, dx, dv

  FieldNeeds operator|(const FieldNeeds& o) const {
    return {halfStepVelocity || o.halfStepVelocity, soundSpeed || o.soundSpeed, xsph || o.xsph,
            rungeKutta || o.rungeKutta};
  }
};

template <int D>
struct Particles {
  // core
  std::vector<Vec<D>> x;         // position [m]
  std::vector<Vec<D>> v;         // velocity at integer time [m/s]
  std::vector<Vec<D>> a;         // acceleration [m/s^2]
  std::vector<Real> rho;         // density [kg/m^D]
  std::vector<Real> p;           // pressure
  std::vector<Real> m;           // mass [kg]
  std::vector<std::int64_t> id;  // stable identity, kept through re-sorts
  // optional (empty unless a FieldNeeds flag asks for them)
  std::vector<Vec<D>> vHalf;     // leap-frog half-step velocity
  std::vector<Real> c;           // sound speed
  std::vector<Vec<D>> vXsph;     // XSPH velocity correction, added to the drift
  std::vector<Vec<D>> x0, v0;    // RK4: state at the start of the step
  std::vector<Vec<D>> dx, dv;    // RK4: weighted sums of the stage derivatives

  std::size_t size() const { return x.size(); }

  // Size the core fields for n particles; x, v, m, id are expected to be set.
  void resize(std::size_t n) {
    x.resize(n);
    v.resize(n, Vec<D>::Zero());
    a.resize(n, Vec<D>::Zero());
    rho.resize(n, 0);
    p.resize(n, 0);
    m.resize(n, 0);
    id.resize(n, 0);
  }

  // The velocity particle i drifts with when its velocity is `velocity`:
  // that, plus the XSPH correction when the scene has one.
  Vec<D> driftVelocity(std::size_t i, const Vec<D>& velocity) const {
    return vXsph.empty() ? velocity : Vec<D>(velocity + vXsph[i]);
  }

  // Allocate exactly the optional fields asked for; release the others.
  void allocate(const FieldNeeds& needs) {
    const std::size_t n = size();
    const Vec<D> zero = Vec<D>::Zero();
    sizeIf(vHalf, needs.halfStepVelocity, n, zero);
    sizeIf(c, needs.soundSpeed, n, Real(0));
    sizeIf(vXsph, needs.xsph, n, zero);
    for (auto* f : {&x0, &v0, &dx, &dv}) sizeIf(*f, needs.rungeKutta, n, zero);
  }

  void shrinkToFit() {
    for (auto* f : {&x, &v, &a, &vHalf, &vXsph, &x0, &v0, &dx, &dv}) f->shrink_to_fit();
    for (auto* f : {&rho, &p, &m, &c}) f->shrink_to_fit();
    id.shrink_to_fit();
  }

  // Reorder the state fields so that new particle k is old particle order[k].
  void permute(const std::vector<std::uint32_t>& order) {
    for (auto* f : {&x, &v, &vHalf, &x0, &v0, &dx, &dv}) permuteField(*f, order, scratchVec_);
    permuteField(m, order, scratchReal_);
    permuteField(id, order, scratchId_);
  }

  std::size_t bytesAllocated() const {
    std::size_t b = 0;
    for (const auto* f : {&x, &v, &a, &vHalf, &vXsph, &x0, &v0, &dx, &dv, &scratchVec_})
      b += f->capacity() * sizeof(Vec<D>);
    for (const auto* f : {&rho, &p, &m, &c, &scratchReal_}) b += f->capacity() * sizeof(Real);
    return b + (id.capacity() + scratchId_.capacity()) * sizeof(std::int64_t);
  }

 private:
  template <class T>
  static void sizeIf(std::vector<T>& f, bool wanted, std::size_t n, const T& zero) {
    if (wanted) f.resize(n, zero);
    else std::vector<T>().swap(f);
  }

  template <class T>
  static void permuteField(std::vector<T>& field, const std::vector<std::uint32_t>& order,
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
