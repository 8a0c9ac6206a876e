// Particles<D>: the particle state as a structure of arrays.
//
// One contiguous array per field of the field table (fields.hpp), indexed by
// particle. The core fields always exist; the others are allocated only when
// the model or the integrator of a scene asks for them, so a scene pays no
// memory for what it does not use.
//
// Ranges: one table (range(ParticleRange)) holds where each kind of
// particle lies, in index order: fluid [0, fluidCount()), walls
// [fluidCount(), size()) (the kind field, allocated only when there are
// walls, says which is which and the neighbour grid keeps walls after the
// fluid through every re-sort); these are the owned particles. After them,
// while a periodic box or other ranks have them (periodic_ghosts.hpp),
// come the ghosts [size(), totalSize()): copies of owned particles shifted
// by a box length, or halo particles; ghosts of fluid first, then ghosts
// of walls. Every array has totalSize() entries; size() counts the owned
// particles only, so the integrators, the checks, the energies and the
// output never see a ghost. The table changes only where the particles'
// number does (resize, resizeOwned, addGhosts, clearGhosts).
// A ghost is the output of no pass: refreshGhosts() copies its fields from
// its source (ghostSource) and puts it at the source's position plus its
// shift. A ghost whose source has the bit kRemoteSource set is a halo
// particle, a copy of a particle owned by another MPI rank
// (mpi/domain_decomposition.hpp): the rest of its source is its slot in the
// decomposition's receive buffer, which fills its fields; refreshGhosts()
// and permute() leave its fields and its record alone (the record moves with
// the particle). The decomposition refreshes them: refreshGhosts(fields)
// calls the remote refresh it was given (setRemoteRefresh) after the local
// copies, on every rank at the same points of a step.
//
// permute() reorders the state and stage fields in one parallel pass,
// through one scratch array of vectors, kept between calls so the step loop
// never allocates: a vector field is gathered into it and swapped with it,
// so its old buffer is the scratch of the next vector field; a narrower
// field (scalars, ids, kinds) is gathered into the scratch's bytes and
// copied back. (A shadow buffer per field cost 81 bytes per particle in 2D
// at full water physics, a scratch array per value type 33; this costs 16,
// 24 in 3D.) Matrices (CSPM's, carried by a rebuild) have a scratch of their
// own. Rates and derived fields are stale after it until the model
// evaluates again. Between re-sorts the scratch is lent to the pair loops
// for their per-particle arrays and to the grid's build for its bucket
// numbers (lendScratch).
#pragma once

#include "sph/fields.hpp"
#include "sph/types.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sph {

// The kinds of particle, in the order of their indices (Particles::range).
enum class ParticleRange : unsigned { kFluid, kWalls, kFluidGhosts, kWallGhosts };
constexpr unsigned kParticleRanges = 4;

// Indices [begin, end).
struct IndexRange {
  std::size_t begin = 0, end = 0;
  bool empty() const { return begin == end; }
};

// The arrays themselves, one per row of the field table.
template <int D>
struct FieldArrays {
  std::vector<Vec<D>> x, v, a;
  std::vector<Real> rho;
  std::vector<Narrow> drho, p, m;
  std::vector<std::int64_t> id;
  std::vector<std::uint8_t> kind;
  std::vector<Vec<D>> vHalf;
  std::vector<Narrow> c;
  std::vector<Vec<D>> vXsph, vWall;
  std::vector<Vec<D>> x0, v0;
  std::vector<Real> rho0;
  std::vector<Vec<D>> dx, dv;
  std::vector<Real> drhoSum;
  std::vector<Real> rhoReinit;
  std::vector<Mat<D>> cspmL;
  std::vector<Real> colour;
  std::vector<Vec<D>> colourNormal;
  std::vector<Real> curvature;
  std::vector<Vec<D>> vPrev;
  std::vector<Real> rhoPrev;
  std::vector<Vec<D>> xList;
  std::vector<Real> shiftSum;
  std::vector<Vec<D>> shiftGrad;

  // f(info, field of s0, field of s1, ...) for every row of the table, in
  // table order: the one place that lists the members.
  template <class F, class... S>
  static void zip(F&& f, S&... s) {
    f(kFieldTable[kFieldX], s.x...);
    f(kFieldTable[kFieldV], s.v...);
    f(kFieldTable[kFieldA], s.a...);
    f(kFieldTable[kFieldRho], s.rho...);
    f(kFieldTable[kFieldDrho], s.drho...);
    f(kFieldTable[kFieldP], s.p...);
    f(kFieldTable[kFieldM], s.m...);
    f(kFieldTable[kFieldId], s.id...);
    f(kFieldTable[kFieldKind], s.kind...);
    f(kFieldTable[kFieldVHalf], s.vHalf...);
    f(kFieldTable[kFieldC], s.c...);
    f(kFieldTable[kFieldVXsph], s.vXsph...);
    f(kFieldTable[kFieldVWall], s.vWall...);
    f(kFieldTable[kFieldX0], s.x0...);
    f(kFieldTable[kFieldV0], s.v0...);
    f(kFieldTable[kFieldRho0], s.rho0...);
    f(kFieldTable[kFieldDx], s.dx...);
    f(kFieldTable[kFieldDv], s.dv...);
    f(kFieldTable[kFieldDrhoSum], s.drhoSum...);
    f(kFieldTable[kFieldRhoReinit], s.rhoReinit...);
    f(kFieldTable[kFieldCspmL], s.cspmL...);
    f(kFieldTable[kFieldColour], s.colour...);
    f(kFieldTable[kFieldColourNormal], s.colourNormal...);
    f(kFieldTable[kFieldCurvature], s.curvature...);
    f(kFieldTable[kFieldVPrev], s.vPrev...);
    f(kFieldTable[kFieldRhoPrev], s.rhoPrev...);
    f(kFieldTable[kFieldXList], s.xList...);
    f(kFieldTable[kFieldShiftSum], s.shiftSum...);
    f(kFieldTable[kFieldShiftGrad], s.shiftGrad...);
  }

  // Call f(info, array) for every field.
  template <class F>
  void forEachField(F&& f) {
    zip(f, *this);
  }
  template <class F>
  void forEachField(F&& f) const {
    zip(f, *this);
  }

  // Size exactly the fields in `fields` to n (new entries zero), release the
  // others and any spare capacity.
  void sizeFields(FieldSet fields, std::size_t n) {
    forEachField([&](const FieldInfo& info, auto& field) {
      using Field = std::decay_t<decltype(field)>;
      if (((fields >> info.id) & 1u) == 0) Field().swap(field);
      else field.resize(n, zero<typename Field::value_type>());
      field.shrink_to_fit();
    });
  }

  std::size_t bytesAllocated() const {
    std::size_t b = 0;
    forEachField([&](const FieldInfo&, const auto& field) {
      b += field.capacity() * sizeof(typename std::decay_t<decltype(field)>::value_type);
    });
    return b;
  }

  template <class T>
  static T zero() {
    if constexpr (std::is_same_v<T, Vec<D>> || std::is_same_v<T, Mat<D>>) return T::Zero();
    else return T(0);
  }
};

static_assert([] {
  for (unsigned f = 0; f < kFieldCount; ++f)
    if (kFieldTable[f].id != f) return false;
  return true;
}(), "kFieldTable rows must be in FieldId order");

template <int D>
struct Particles : FieldArrays<D> {
  using FieldArrays<D>::x;
  using FieldArrays<D>::v;
  using FieldArrays<D>::a;
  using FieldArrays<D>::rho;
  using FieldArrays<D>::p;
  using FieldArrays<D>::m;
  using FieldArrays<D>::id;
  using FieldArrays<D>::kind;
  using FieldArrays<D>::vXsph;

  // The indices of one kind of particle (the range table, above).
  IndexRange range(ParticleRange r) const {
    const auto k = static_cast<unsigned>(r);
    return {bound_[k], bound_[k + 1]};
  }
  // Owned particles (fluid and walls); the ghosts follow them.
  std::size_t size() const { return bound_[kOwnedEnd]; }
  std::size_t totalSize() const { return bound_[kParticleRanges]; }
  // Fluid particles are [0, fluidCount()), walls [fluidCount(), size()).
  std::size_t fluidCount() const { return bound_[kFluidEnd]; }
  // Walls among the particles a pass sees: owned ones, or ghosts of walls
  // (on an MPI rank that owns no wall, the halo may hold some).
  bool hasWalls() const {
    return !range(ParticleRange::kWalls).empty() || !range(ParticleRange::kWallGhosts).empty();
  }
  // Ghosts of fluid particles are [size(), ghostFluidEnd()), of walls the rest.
  std::size_t ghostFluidEnd() const { return bound_[kGhostFluidEnd]; }
  const std::vector<std::uint32_t>& ghostSource() const { return ghostSource_; }
  const std::vector<Vec<D>>& ghostShift() const { return ghostShift_; }
  // A ghost source with this bit is a halo particle's receive slot.
  static constexpr std::uint32_t kRemoteSource = 0x80000000u;
  FieldSet allocated() const { return allocated_; }
  // The fields a ghost or halo particle takes from its source: all
  // allocated ones but the list's and those read only at their own
  // particle (fields.hpp).
  FieldSet refreshed() const { return allocated_ & ~kListFields & ~kOwnParticleFields; }
  bool has(FieldId f) const { return (allocated_ >> f) & 1u; }

  // Size the core fields for n particles (x, v, m, id are expected to be set
  // already), with walls from index `fluidCount` on (all fluid by default).
  // Other fields are left as they are until allocate().
  void resize(std::size_t n, std::size_t fluidCount = SIZE_MAX) {
    dropGhostRecords();
    x.resize(n);
    v.resize(n, Vec<D>::Zero());
    a.resize(n, Vec<D>::Zero());
    rho.resize(n, 0);
    p.resize(n, 0);
    m.resize(n, 0);
    id.resize(n, 0);
    setOwned(n, fluidCount);
    if (hasWalls()) {
      kind.resize(n);
      markKinds();
      allocated_ |= fieldBit(kFieldKind);
    }
    allocated_ |= kCoreFields;
    setPermuted();
  }

  // The velocity particle i drifts with when its velocity is `velocity`:
  // that, plus the XSPH correction when the scene has one.
  Vec<D> driftVelocity(std::size_t i, const Vec<D>& velocity) const {
    return vXsph.empty() ? velocity : Vec<D>(velocity + vXsph[i]);
  }

  // Allocate exactly the core fields and the optional ones in `wanted` (the
  // kind field too when there are walls), release the others, and give the
  // permuted fields' types their scratch arrays.
  void allocate(FieldSet wanted) {
    clearGhosts();
    wanted |= kCoreFields;
    if (hasWalls()) wanted |= fieldBit(kFieldKind);
    const std::size_t n = size();
    this->sizeFields(wanted, n);
    if (hasWalls()) markKinds();
    allocated_ = wanted;
    setPermuted();
  }

  // Drop the ghosts and make the owned particles n, with walls from
  // `fluidCount` on: every allocated field keeps its first n entries (new
  // ones zero) and its capacity; when it needs more room, an eighth more
  // than n (not the vector's doubling: a migration moves a few particles at
  // each sort). The caller fills the fields (migration between MPI ranks,
  // mpi/domain_decomposition.hpp).
  void resizeOwned(std::size_t n, std::size_t fluidCount) {
    clearGhosts();
    this->forEachField([&](const FieldInfo& info, auto& field) {
      using Field = std::decay_t<decltype(field)>;
      if (((allocated_ >> info.id) & 1u) == 0) return;
      if (n > field.capacity()) field.reserve(n + n / 8 + 16);
      field.resize(n, FieldArrays<D>::template zero<typename Field::value_type>());
    });
    setOwned(n, fluidCount);
  }

  // Drop the ghosts (the arrays keep their capacity).
  void clearGhosts() {
    if (ghostSource_.empty()) return;
    const std::size_t n = size();
    dropGhostRecords();
    this->forEachField([&](const FieldInfo& info, auto& field) {
      if ((allocated_ >> info.id) & 1u) field.resize(n);
    });
  }

  // Append ghosts of the owned particles: ghost g copies source[g] shifted
  // by shift[g]; the sources of fluid ghosts must come first (the first
  // `fluidGhosts`). Fields are filled by refreshGhosts().
  void addGhosts(const std::vector<std::uint32_t>& source, const std::vector<Vec<D>>& shift,
                 std::size_t fluidGhosts) {
    clearGhosts();
    const std::size_t total = size() + source.size();
    ghostSource_ = source;
    ghostShift_ = shift;
    setGhosts(fluidGhosts, source.size() - fluidGhosts);
    this->forEachField([&](const FieldInfo& info, auto& field) {
      if ((allocated_ >> info.id) & 1u) growTo(field, total);
    });
    refreshLocalGhosts();
  }

  // Copy the fields in `fields` (all refreshed() ones by default) of every
  // ghost from its source; x becomes the source's x plus the shift. Then the
  // halo particles' from their ranks (the remote refresh, when one is set:
  // a collective call, made by every rank at the same point).
  void refreshGhosts(FieldSet fields = ~FieldSet(0)) {
    refreshLocalGhosts(fields);
    refreshRemoteGhosts(fields);
  }

  // The local ghosts only (periodic images of owned particles).
  void refreshLocalGhosts(FieldSet fields = ~FieldSet(0)) {
    if (ghostSource_.empty() || (fields & refreshed()) == 0) return;
#pragma omp parallel if (ghostSource_.size() >= kMinParallelSize)
    refreshGhostsInTeam(fields);
  }

  // The halo particles only (collective; nothing without a remote refresh).
  void refreshRemoteGhosts(FieldSet fields = ~FieldSet(0)) {
    if (remoteRefresh_ && (fields & refreshed()) != 0) remoteRefresh_(remoteContext_, *this, fields);
  }

  // The decomposition's refresh of the halo particles' fields (nullptr: none).
  using RemoteRefresh = void (*)(void* context, Particles& P, FieldSet fields);
  void setRemoteRefresh(RemoteRefresh refresh, void* context) {
    remoteRefresh_ = refresh;
    remoteContext_ = context;
  }
  bool hasRemoteRefresh() const { return remoteRefresh_ != nullptr; }

  // The same, called by every thread of a parallel region (the work is
  // shared, with a barrier at the end); outside one it runs serially.
  void refreshGhostsInTeam(FieldSet fields = ~FieldSet(0)) {
    const std::size_t ng = ghostSource_.size();
    if (ng == 0) return;
    const std::size_t owned = size();
    fields &= refreshed();
    const std::uint32_t* src = ghostSource_.data();
    this->forEachField([&](const FieldInfo& info, auto& field) {
      if (((fields >> info.id) & 1u) == 0 || info.id == kFieldX) return;
#pragma omp for schedule(static) nowait
      for (std::size_t g = 0; g < ng; ++g)
        if ((src[g] & kRemoteSource) == 0) field[owned + g] = field[src[g]];
    });
    if (fields & fieldBit(kFieldX)) {
#pragma omp for schedule(static) nowait
      for (std::size_t g = 0; g < ng; ++g)
        if ((src[g] & kRemoteSource) == 0) x[owned + g] = x[src[g]] + ghostShift_[g];
    }
#pragma omp barrier
  }

  // The same, then the halo particles' (collective): the team's master, the
  // thread that talks to MPI (MPI_THREAD_FUNNELED), refreshes the halos
  // while the others wait. For a pass that needs its own output on the
  // neighbours between two of its loops (the colour field's normals).
  void refreshGhostsAndHalosInTeam(FieldSet fields) {
    refreshGhostsInTeam(fields);
    if (!remoteRefresh_) return;  // (the same for every thread)
#pragma omp master
    refreshRemoteGhosts(fields);
#pragma omp barrier
  }

  // Reorder the state and stage fields so that new particle k is old
  // particle order[k]: one parallel region, one gather loop per field into
  // the scratch, then a swap (vectors) or a copy back (narrower fields). The
  // grid sorts walls after the fluid and ghosts after the owned particles,
  // so the ranges do not change. The
  // ghosts' sources follow their particles and are then refreshed (all
  // fields: the non-permuted ones of a ghost were never its own).
  //
  // carryAll: the rates and derived fields follow their particles too (the
  // neighbour list's rebuilds with a skin, scene.hpp: they happen between
  // a field's computation and its use). They go through the same scratch
  // (the matrices of CSPM: one more, grown once).
  void permute(const std::vector<std::uint32_t>& order, bool carryAll = false) {
    gather(permuted_, order);
    // (id and kind, the integer fields, are state: always permuted.)
    if (carryAll) gather(allocated_ & ~permuted_ & ~kListFields, order);
    if (ghostSource_.empty()) return;
    const std::size_t owned = size(), ng = ghostSource_.size();
    newIndex_.resize(owned);
    for (std::size_t k = 0; k < owned; ++k) newIndex_[order[k]] = static_cast<std::uint32_t>(k);
    sourceShadow_.resize(ng);
    shiftShadow_.resize(ng);
    for (std::size_t g = 0; g < ng; ++g) {
      const std::size_t old = order[owned + g] - owned;
      const std::uint32_t source = ghostSource_[old];
      sourceShadow_[g] = (source & kRemoteSource) ? source : newIndex_[source];
      shiftShadow_[g] = ghostShift_[old];
    }
    ghostSource_.swap(sourceShadow_);
    ghostShift_.swap(shiftShadow_);
    refreshLocalGhosts();
  }

  // The re-sort's scratch lent as `reals` numbers (nullptr for none), to
  // arrays that live only between two uses of the scratch, as its own use
  // lives only inside permute(): the pair loops' per-particle arrays
  // (p/rho^2, m/rho; pairArrays in pair_scratch.hpp), formed and read
  // inside one pass, and the grid's bucket numbers, written and read by the
  // grid's build before the permute() that applies its order
  // (sortByCell). Grown when it holds fewer, to at least the vectors the
  // next permute() needs (one per particle, ghosts included), so that a
  // lend and the permute after it do not grow it twice (the step loop does
  // not allocate once the particle count settles); call it outside a
  // parallel region. The numbers do not survive the next permute() or
  // lendScratch().
  Real* lendScratch(std::size_t reals) {
    static_assert(sizeof(Vec<D>) == D * sizeof(Real), "the scratch's vectors must be unpadded to lend their numbers");
    const std::size_t entries = std::max((reals + D - 1) / D, totalSize());
    if (scratch_.vector.size() < entries) growTo(scratch_.vector, entries);
    return scratch_.vector.empty() ? nullptr : scratch_.vector.data()->data();
  }
  // The same, as `bytes` raw bytes (for values of another type, written and
  // read through memcpy).
  unsigned char* lendScratchBytes(std::size_t bytes) {
    return reinterpret_cast<unsigned char*>(lendScratch((bytes + sizeof(Real) - 1) / sizeof(Real)));
  }

  // The fields' arrays alone [bytes].
  std::size_t fieldBytes() const { return FieldArrays<D>::bytesAllocated(); }
  // Every array of the particles, the scratch arrays included [bytes].
  std::size_t bytesAllocated() const {
    const auto bytes = [](const auto& array) {
      return array.capacity() * sizeof(typename std::decay_t<decltype(array)>::value_type);
    };
    return FieldArrays<D>::bytesAllocated() + bytes(scratch_.vector) + bytes(scratch_.matrix) +
           (ghostSource_.capacity() + sourceShadow_.capacity() + newIndex_.capacity()) * sizeof(std::uint32_t) +
           (ghostShift_.capacity() + shiftShadow_.capacity()) * sizeof(Vec<D>);
  }

 private:
  // Gather the fields in `fields` (with order[k] the old index of new
  // particle k): a vector (or matrix) field into the scratch of its type,
  // swapped in; a narrower one into the vector scratch's bytes, copied back.
  void gather(FieldSet fields, const std::vector<std::uint32_t>& order) {
    const std::size_t n = totalSize();
    if (fields == 0) return;
    growTo(scratch_.vector, n);
    this->forEachField([&](const FieldInfo& info, auto& field) {
      using T = typename std::decay_t<decltype(field)>::value_type;
      if constexpr (std::is_same_v<T, Mat<D>>)
        if ((fields >> info.id) & 1u) growTo(scratch_.matrix, n);
    });
#pragma omp parallel if (n >= kMinParallelSize)
    this->forEachField([&](const FieldInfo& info, auto& field) {
      if (((fields >> info.id) & 1u) == 0) return;
      using T = typename std::decay_t<decltype(field)>::value_type;
      if constexpr (std::is_same_v<T, Vec<D>> || std::is_same_v<T, Mat<D>>) {
        auto& scratch = scratchFor(field);
#pragma omp for schedule(static)
        for (std::size_t k = 0; k < n; ++k) scratch[k] = field[order[k]];
#pragma omp single
        field.swap(scratch);
      } else {
        static_assert(std::is_trivially_copyable_v<T> && sizeof(T) <= sizeof(Vec<D>));
        auto* bytes = reinterpret_cast<unsigned char*>(scratch_.vector.data());
#pragma omp for schedule(static)
        for (std::size_t k = 0; k < n; ++k) std::memcpy(bytes + k * sizeof(T), &field[order[k]], sizeof(T));
#pragma omp for schedule(static)
        for (std::size_t k = 0; k < n; ++k) std::memcpy(&field[k], bytes + k * sizeof(T), sizeof(T));
      }
    });
  }

  // The scratch arrays: vectors for every field but the matrices.
  struct Scratch {
    std::vector<Vec<D>> vector;
    std::vector<Mat<D>> matrix;
  };
  std::vector<Vec<D>>& scratchFor(const std::vector<Vec<D>>&) { return scratch_.vector; }
  std::vector<Mat<D>>& scratchFor(const std::vector<Mat<D>>&) { return scratch_.matrix; }

  // The permuted fields (allocated, with a permuted role), and the vector
  // scratch sized now (the matrices' is released: a rebuild grows it).
  void setPermuted() {
    permuted_ = 0;
    for (const FieldInfo& info : kFieldTable)
      if (isPermuted(info.role) && ((allocated_ >> info.id) & 1u)) permuted_ |= fieldBit(info.id);
    // Density is a state variable only when it is integrated (a density
    // rate exists); summation density recomputes it after every sort.
    if (((allocated_ >> kFieldDrho) & 1u) == 0) permuted_ &= ~fieldBit(kFieldRho);
    // Leap-frog and symplectic Euler compute d rho/dt before the step's
    // sort (their density-rate pass, at the half-step or new velocity), so
    // it must travel with its particle to the snapshot after the sort.
    if ((allocated_ >> kFieldDrho) & 1u) permuted_ |= fieldBit(kFieldDrho);
    scratch_ = Scratch();
    scratch_.vector.resize(size());
    scratch_.vector.shrink_to_fit();
  }

  // Resize to n; when that needs more room, reserve a quarter of the ghosts
  // more (not the vector's doubling: the ghosts are a fraction of the
  // particles, and their number changes a little at every sort).
  template <class V>
  void growTo(V& array, std::size_t n) {
    if (n > array.capacity()) array.reserve(n + ghostSource_.size() / 4 + 16);
    array.resize(n);
  }

  // The kind of each owned particle, from the range table.
  void markKinds() {
    for (std::size_t i = 0; i < size(); ++i) kind[i] = i < fluidCount() ? kFluid : kWall;
  }

  void dropGhostRecords() {
    ghostSource_.clear();
    ghostShift_.clear();
    setGhosts(0, 0);
  }

  // The range table's entries: bound_[r] and bound_[r + 1] enclose range r.
  static constexpr unsigned kFluidEnd = 1, kOwnedEnd = 2, kGhostFluidEnd = 3;
  void setOwned(std::size_t n, std::size_t fluidCount) {
    bound_[kFluidEnd] = std::min(fluidCount, n);
    bound_[kOwnedEnd] = n;
    setGhosts(0, 0);
  }
  void setGhosts(std::size_t fluidGhosts, std::size_t wallGhosts) {
    bound_[kGhostFluidEnd] = bound_[kOwnedEnd] + fluidGhosts;
    bound_[kParticleRanges] = bound_[kGhostFluidEnd] + wallGhosts;
  }

  std::array<std::size_t, kParticleRanges + 1> bound_{};  // the range table
  std::vector<std::uint32_t> ghostSource_;  // ghost g copies owned particle ghostSource_[g]
  std::vector<Vec<D>> ghostShift_;          // ... shifted by ghostShift_[g]
  std::vector<std::uint32_t> sourceShadow_, newIndex_;
  std::vector<Vec<D>> shiftShadow_;
  FieldSet allocated_ = 0;
  FieldSet permuted_ = 0;
  Scratch scratch_;
  RemoteRefresh remoteRefresh_ = nullptr;
  void* remoteContext_ = nullptr;
};

}  // namespace sph
