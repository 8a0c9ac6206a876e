// DomainDecomposition<D>: the particles split between MPI ranks by cells of
// a space-filling curve, their migration to the rank that owns them, and the
// halo: copies of other ranks' particles within a neighbour-list radius.
//
// Method (Warren and Salmon 1993, "A parallel hashed oct-tree N-body
// algorithm", Supercomputing '93: keys on a Morton curve cut into pieces of
// equal work; as in GADGET-2, Springel 2005, MNRAS 364, 1105, section 5.1,
// and DualSPHysics's multi-node version, Dominguez et al. 2013, Comput. Phys.
// Commun. 184, 1848):
//   - space is cut into the hash grid's cells (hash_grid.hpp: edge the
//     support times 1 + 1e-9, c = floor(x / edge)); a cell's key k(c) is the
//     Morton (Z-order) index of c - origin, the bits of the D cell indices
//     interleaved (Morton 1966), so that cells close on the curve are close in
//     space;
//   - balance(): every rank's cells and their weights (particles per cell, or
//     the sum of a cost per particle) are gathered, and the curve is cut into
//     R contiguous key ranges of equal weight: cell k goes to rank
//     floor((W_before(k) + w_k / 2) R / W) (W: the total weight, W_before(k):
//     the weight of the cells before k on the curve). Rank r owns the keys
//     [s_r, s_r+1) (s_0 = 0, s_R = infinity), so every point of space has an
//     owner, empty cells too;
//   - migrate(): every owned particle goes to the rank owning its cell, all
//     its allocated fields with it (MPI_Alltoallv; fluid before walls on
//     every rank, in the order of the sending ranks);
//   - makeHalos(): an owned particle, or a periodic ghost of one, closer than
//     `radius` (times 1 + 1e-9, as the periodic ghosts' layer) to a cell of
//     another rank is sent to that rank once, where it is appended to the ghost range of Particles as a
//     halo particle (a ghost with a remote source, particles.hpp), halos of
//     fluid among the ghosts of fluid and halos of walls among those of walls.
//     So a neighbour list built on owned + ghosts finds exactly the pairs of
//     the owned particles that one list over all ranks' particles finds;
//   - refreshHalos(): the given fields of the halos sent again, in the same
//     order, with MPI_Isend/MPI_Irecv (startHaloRefresh / finishHaloRefresh
//     let interior work run in between).
//
// Every MPI call is made from the thread that calls these functions, outside
// OpenMP regions (MPI_THREAD_FUNNELED). With one rank nothing is sent and no
// MPI call is made. balance() gathers the cell list of every rank on every
// rank (memory O(cells) per rank): a first step, not the distributed
// splitter search 10^9 particles need (docs/developer/mpi.md).
#pragma once

#include "sph/mpi/communication_time.hpp"
#include "sph/mpi/session.hpp"
#include "sph/particles.hpp"
#include "sph/types.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

namespace sph::mpi {

template <int D>
class DomainDecomposition {
 public:
  // `support`: the hash grid's (the neighbour list's radius); the cells are
  // the grid's.
  DomainDecomposition(const Communicator& comm, Real support)
      : comm_(comm), cellSize_(support * (1 + 1e-9)), invCell_(1 / cellSize_) {
    if (!(support > 0)) throw std::invalid_argument("DomainDecomposition: the support must be positive");
  }

  int rank() const { return comm_.rank; }
  int ranks() const { return comm_.size; }
  Real cellSize() const { return cellSize_; }
  // s_1 ... s_R-1: rank r owns the keys [s_r, s_r+1).
  const std::vector<std::uint64_t>& splitters() const { return splitters_; }

  // Cut the curve into R pieces of equal weight from the owned particles of
  // every rank (collective). cost: a weight per owned particle (nullptr: 1).
  void balance(const Particles<D>& P, const std::vector<Real>* cost = nullptr) {
    const std::size_t n = P.size();
    if (cost && cost->size() < n) throw std::invalid_argument("DomainDecomposition::balance: a cost per particle");
    if (comm_.size == 1) {
      setOrigin(P);
      splitters_.clear();
      return;
    }
    Timed timed(&CommunicationTime::resort);
    setOrigin(P);
    // This rank's cells: (key, weight), sorted, one entry per cell.
    cellWeights_.resize(n);
    for (std::size_t i = 0; i < n; ++i) cellWeights_[i] = {keyOf(P.x[i]), cost ? (*cost)[i] : Real(1)};
    std::sort(cellWeights_.begin(), cellWeights_.end());
    std::size_t cells = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (cells > 0 && cellWeights_[cells - 1].first == cellWeights_[i].first)
        cellWeights_[cells - 1].second += cellWeights_[i].second;
      else cellWeights_[cells++] = cellWeights_[i];
    }
    cellWeights_.resize(cells);
    // Every rank's cells on every rank.
    const int R = comm_.size;
    std::vector<int> counts(R), displs(R);
    const int mine = static_cast<int>(cells);
    MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_.comm);
    int total = 0;
    for (int r = 0; r < R; ++r) displs[r] = total, total += counts[r];
    std::vector<std::uint64_t> keys(cells), allKeys(static_cast<std::size_t>(total));
    std::vector<double> weights(cells), allWeights(static_cast<std::size_t>(total));
    for (std::size_t c = 0; c < cells; ++c) keys[c] = cellWeights_[c].first, weights[c] = cellWeights_[c].second;
    MPI_Allgatherv(keys.data(), mine, MPI_UINT64_T, allKeys.data(), counts.data(), displs.data(), MPI_UINT64_T,
                   comm_.comm);
    MPI_Allgatherv(weights.data(), mine, MPI_DOUBLE, allWeights.data(), counts.data(), displs.data(), MPI_DOUBLE,
                   comm_.comm);
    std::vector<std::pair<std::uint64_t, double>> all(static_cast<std::size_t>(total));
    for (int c = 0; c < total; ++c) all[c] = {allKeys[c], allWeights[c]};
    std::sort(all.begin(), all.end());  // the same order on every rank: the same cuts
    std::size_t distinct = 0;  // a cell several ranks hold: one entry
    for (std::size_t c = 0; c < all.size(); ++c) {
      if (distinct > 0 && all[distinct - 1].first == all[c].first) all[distinct - 1].second += all[c].second;
      else all[distinct++] = all[c];
    }
    all.resize(distinct);
    double W = 0;
    for (const auto& cw : all) W += cw.second;
    // s_r: the key of the first cell that goes to rank r or later.
    splitters_.assign(static_cast<std::size_t>(R - 1), ~std::uint64_t(0));
    double before = 0;
    int next = 1;  // the next splitter to set
    for (std::size_t c = 0; c < all.size() && next < R; ++c) {
      const double w = all[c].second;
      const int piece = W > 0 ? std::min(R - 1, static_cast<int>((before + w / 2) * R / W)) : 0;
      while (next <= piece) splitters_[static_cast<std::size_t>(next++ - 1)] = all[c].first;
      before += w;
    }
  }

  // The cell holding x (as the hash grid's).
  IVec<D> cellOf(const Vec<D>& x) const {
    IVec<D> c;
    for (int d = 0; d < D; ++d) c[d] = floorToInt(x[d] * invCell_);
    return c;
  }
  // The Morton key of a cell: 64 / D bits of each index from the origin set
  // by balance(), interleaved (cells beyond them share the key of the
  // nearest cell within).
  std::uint64_t keyOfCell(const IVec<D>& cell) const {
    constexpr int bits = 64 / D;
    constexpr std::int64_t top = (std::int64_t(1) << bits) - 1;
    std::uint64_t c[D];
    for (int d = 0; d < D; ++d) c[d] = static_cast<std::uint64_t>(std::clamp<std::int64_t>(cell[d] - origin_[d], 0, top));
    std::uint64_t key = 0;
    for (int b = 0; b < bits; ++b)
      for (int d = 0; d < D; ++d) key |= ((c[d] >> b) & 1u) << (b * D + d);
    return key;
  }
  std::uint64_t keyOf(const Vec<D>& x) const { return keyOfCell(cellOf(x)); }
  int ownerOfKey(std::uint64_t key) const {
    return static_cast<int>(std::upper_bound(splitters_.begin(), splitters_.end(), key) - splitters_.begin());
  }
  // The rank owning the cell holding x.
  int ownerOf(const Vec<D>& x) const { return comm_.size == 1 ? 0 : ownerOfKey(keyOf(x)); }
  int ownerOfCell(const IVec<D>& cell) const { return comm_.size == 1 ? 0 : ownerOfKey(keyOfCell(cell)); }

  // Send every owned particle to the rank owning its cell (collective). The
  // ghosts and halos are dropped first: make them again afterwards.
  void migrate(Particles<D>& P) {
    P.clearGhosts();
    clearHaloRecords();
    if (comm_.size == 1) return;
    Timed timed(&CommunicationTime::resort);
    const int R = comm_.size;
    // The records are the allocated fields: the same on every rank.
    FieldSet sets[2] = {P.allocated(), ~P.allocated()};
    MPI_Allreduce(MPI_IN_PLACE, sets, 2, MPI_UINT32_T, MPI_BAND, comm_.comm);
    if (sets[0] != P.allocated() || sets[1] != ~P.allocated())
      throw std::runtime_error("DomainDecomposition::migrate: the ranks allocate different particle fields");
    const std::size_t n = P.size(), nFluid = P.fluidCount();
    // Particles in the order of (destination, fluid then walls).
    std::vector<int> sendCount(2 * R, 0), recvCount(2 * R, 0);
    dest_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      dest_[i] = 2 * ownerOf(P.x[i]) + (i >= nFluid);
      ++sendCount[dest_[i]];
    }
    std::vector<std::size_t> start(2 * R + 1, 0);
    for (int b = 0; b < 2 * R; ++b) start[b + 1] = start[b] + static_cast<std::size_t>(sendCount[b]);
    order_.resize(n);
    for (std::size_t i = 0; i < n; ++i) order_[start[dest_[i]]++] = static_cast<std::uint32_t>(i);
    MPI_Alltoall(sendCount.data(), 2, MPI_INT, recvCount.data(), 2, MPI_INT, comm_.comm);

    const FieldSet fields = P.allocated();
    const std::size_t record = recordBytes(P, fields);
    pack(P, fields, record, order_, sendBuffer_);
    std::vector<int> sendN(R), sendAt(R), recvN(R), recvAt(R);
    int s = 0, r = 0;
    for (int q = 0; q < R; ++q) {
      sendN[q] = sendCount[2 * q] + sendCount[2 * q + 1], sendAt[q] = s, s += sendN[q];
      recvN[q] = recvCount[2 * q] + recvCount[2 * q + 1], recvAt[q] = r, r += recvN[q];
    }
    recvBuffer_.resize(static_cast<std::size_t>(r) * record);
    MPI_Datatype type = recordType(record);
    MPI_Alltoallv(sendBuffer_.data(), sendN.data(), sendAt.data(), type, recvBuffer_.data(), recvN.data(),
                  recvAt.data(), type, comm_.comm);
    MPI_Type_free(&type);

    // Fluid from every rank in rank order, then walls.
    std::size_t newFluid = 0;
    for (int q = 0; q < R; ++q) newFluid += static_cast<std::size_t>(recvCount[2 * q]);
    const std::size_t newN = static_cast<std::size_t>(r);
    slot_.resize(newN);  // slot_[k]: the received record of new particle k
    std::size_t fluidAt = 0, wallAt = newFluid;
    for (int q = 0; q < R; ++q) {
      for (int k = 0; k < recvCount[2 * q]; ++k) slot_[fluidAt++] = static_cast<std::uint32_t>(recvAt[q] + k);
      for (int k = 0; k < recvCount[2 * q + 1]; ++k)
        slot_[wallAt++] = static_cast<std::uint32_t>(recvAt[q] + recvCount[2 * q] + k);
    }
    P.resizeOwned(newN, newFluid);
    unpack(P, fields, record, 0, slot_);
  }

  // Append as halos the particles of other ranks within `radius` of this
  // rank's cells (collective), after any periodic ghosts' records (kept);
  // their fields are filled (all but the list fields). Old halos are dropped.
  void makeHalos(Particles<D>& P, Real radius) {
    const Real layer = radius * (1 + 1e-9), layer2 = layer * layer;
    const int R = comm_.size;
    if (R == 1) return;  // no halo
    Timed timed(&CommunicationTime::resort);
    // The periodic ghosts already there, without the old halos.
    std::vector<std::uint32_t>& source = localSource_;
    std::vector<Vec<D>>& shift = localShift_;
    source.clear();
    shift.clear();
    std::size_t fluidGhosts = 0;
    const std::size_t owned = P.size();
    for (std::size_t g = 0; g < P.ghostSource().size(); ++g) {
      if (P.ghostSource()[g] & Particles<D>::kRemoteSource) continue;
      if (owned + g < P.ghostFluidEnd()) ++fluidGhosts;
      source.push_back(P.ghostSource()[g]);
      shift.push_back(P.ghostShift()[g]);
    }
    // The periodic ghosts' slots: [owned, owned + ghosts), fluid first.
    std::vector<std::uint32_t>& localSlot = localSlot_;
    localSlot.clear();
    for (std::size_t g = 0; g < P.ghostSource().size(); ++g)
      if ((P.ghostSource()[g] & Particles<D>::kRemoteSource) == 0) localSlot.push_back(static_cast<std::uint32_t>(owned + g));
    clearHaloRecords();
    // The senders, in the order a rank receives them: owned fluid, periodic
    // ghosts of fluid, owned walls, ghosts of walls. A periodic ghost is sent
    // like an owned particle: a rank whose cells are near a periodic face gets
    // the images of another rank's particles across it (the ghosts' slots are
    // renumbered below, once the halos' place among them is known).
    std::vector<std::uint32_t>& senders = senders_;
    senders.clear();
    for (std::size_t i = 0; i < P.fluidCount(); ++i) senders.push_back(static_cast<std::uint32_t>(i));
    for (std::size_t g = 0; g < fluidGhosts; ++g) senders.push_back(localSlot[g]);
    for (std::size_t i = P.fluidCount(); i < owned; ++i) senders.push_back(static_cast<std::uint32_t>(i));
    for (std::size_t g = fluidGhosts; g < localSlot.size(); ++g) senders.push_back(localSlot[g]);
    const std::size_t fluidSenders = P.fluidCount() + fluidGhosts;
    // Which ranks each sender goes to.
    const int reach = static_cast<int>(std::ceil(layer * invCell_));
    int span = 1;
    for (int d = 0; d < D; ++d) span *= 2 * reach + 1;
    std::vector<std::vector<std::uint32_t>>& lists = lists_;
    lists.resize(static_cast<std::size_t>(R));
    for (auto& list : lists) list.clear();
    std::vector<int> fluidSent(R, 0);
    std::vector<char> marked(static_cast<std::size_t>(R), 0);
    std::vector<int> touched;
    touched.reserve(static_cast<std::size_t>(R));
    for (std::size_t s = 0; s < senders.size(); ++s) {
      const std::size_t i = senders[s];
      const Vec<D>& x = P.x[i];
      const IVec<D> c = cellOf(x);
      touched.clear();
      for (int k = 0; k < span; ++k) {
        IVec<D> o;
        int rest = k;
        bool self = true;
        for (int d = 0; d < D; ++d, rest /= 2 * reach + 1) {
          o[d] = c[d] + rest % (2 * reach + 1) - reach;
          self &= o[d] == c[d];
        }
        // (An owned particle's own cell is its rank's; a periodic ghost's
        // need not be: a cell across a periodic face may belong to any rank.)
        if (self && i < owned) continue;
        // Distance from x to the box of cell o.
        Real dist2 = 0;
        for (int d = 0; d < D; ++d) {
          const Real lo = static_cast<Real>(o[d]) * cellSize_, hi = lo + cellSize_;
          const Real gap = x[d] < lo ? lo - x[d] : x[d] > hi ? x[d] - hi : Real(0);
          dist2 += gap * gap;
        }
        if (dist2 > layer2) continue;
        const int owner = ownerOfCell(o);
        if (owner == comm_.rank || marked[owner]) continue;
        marked[owner] = 1;
        touched.push_back(owner);
      }
      for (int q : touched) {
        marked[q] = 0;
        lists[q].push_back(static_cast<std::uint32_t>(i));
        fluidSent[q] += s < fluidSenders;
      }
    }
    sendIndex_.clear();
    sendCount_.assign(R, 0);
    sendAt_.assign(R, 0);
    for (int q = 0; q < R; ++q) {
      sendAt_[q] = static_cast<int>(sendIndex_.size());
      sendCount_[q] = static_cast<int>(lists[q].size());
      sendIndex_.insert(sendIndex_.end(), lists[q].begin(), lists[q].end());
    }
    // What comes from each rank: (fluid, all).
    std::vector<int> sendPair(2 * R), recvPair(2 * R);
    for (int q = 0; q < R; ++q) sendPair[2 * q] = fluidSent[q], sendPair[2 * q + 1] = sendCount_[q];
    MPI_Alltoall(sendPair.data(), 2, MPI_INT, recvPair.data(), 2, MPI_INT, comm_.comm);
    recvCount_.assign(R, 0);
    recvAt_.assign(R, 0);
    int slots = 0;
    for (int q = 0; q < R; ++q) recvAt_[q] = slots, recvCount_[q] = recvPair[2 * q + 1], slots += recvCount_[q];
    // Records: periodic ghosts of fluid, halos of fluid, ghosts of walls, halos of walls.
    std::vector<std::uint32_t>& allSource = allSource_;
    std::vector<Vec<D>>& allShift = allShift_;
    allSource.assign(source.begin(), source.begin() + static_cast<std::ptrdiff_t>(fluidGhosts));
    allShift.assign(shift.begin(), shift.begin() + static_cast<std::ptrdiff_t>(fluidGhosts));
    for (int q = 0; q < R; ++q)
      for (int k = 0; k < recvPair[2 * q]; ++k)
        allSource.push_back(Particles<D>::kRemoteSource | static_cast<std::uint32_t>(recvAt_[q] + k));
    const std::size_t allFluid = allSource.size();
    allSource.insert(allSource.end(), source.begin() + static_cast<std::ptrdiff_t>(fluidGhosts), source.end());
    for (int q = 0; q < R; ++q)
      for (int k = recvPair[2 * q]; k < recvCount_[q]; ++k)
        allSource.push_back(Particles<D>::kRemoteSource | static_cast<std::uint32_t>(recvAt_[q] + k));
    allShift.resize(allSource.size(), Vec<D>::Zero());
    for (std::size_t g = fluidGhosts, k = allFluid; g < source.size(); ++g, ++k) allShift[k] = shift[g];
    haloCount_ = static_cast<std::size_t>(slots);
    // A periodic ghost of walls moves behind the halos of fluid.
    const std::uint32_t wallGhostsFrom = static_cast<std::uint32_t>(owned + fluidGhosts);
    const auto fluidHalos = static_cast<std::uint32_t>(allFluid - fluidGhosts);
    for (std::uint32_t& i : sendIndex_)
      if (i >= wallGhostsFrom) i += fluidHalos;
    P.addGhosts(allSource, allShift, allFluid);
    refreshHalos(P, P.refreshed());
  }

  // Keep this rank's share of particles every rank holds alike (a run's
  // start: every rank built the same particles): of the fluid and of the
  // walls each, the r-th of R contiguous blocks. balance() and migrate()
  // then give every particle its owner.
  void keepShare(Particles<D>& P) const {
    if (comm_.size == 1) return;
    const std::size_t n = P.size(), nFluid = P.fluidCount(), R = static_cast<std::size_t>(comm_.size),
                      r = static_cast<std::size_t>(comm_.rank);
    const std::size_t f0 = nFluid * r / R, f1 = nFluid * (r + 1) / R;
    const std::size_t w0 = nFluid + (n - nFluid) * r / R, w1 = nFluid + (n - nFluid) * (r + 1) / R;
    P.clearGhosts();
    P.forEachField([&](const FieldInfo& info, auto& field) {
      if (((P.allocated() >> info.id) & 1u) == 0 || field.size() < n) return;
      std::size_t k = 0;
      for (std::size_t i = f0; i < f1; ++i) field[k++] = field[i];
      for (std::size_t i = w0; i < w1; ++i) field[k++] = field[i];
    });
    P.resizeOwned((f1 - f0) + (w1 - w0), f1 - f0);
  }

  // The halo refresh as Particles' remote refresh (setRemoteRefresh).
  static void refreshRemote(void* self, Particles<D>& P, FieldSet fields) {
    static_cast<DomainDecomposition*>(self)->refreshHalos(P, fields);
  }

  std::size_t haloCount() const { return haloCount_; }
  // Owned particles sent as halos (a particle sent to two ranks counts twice).
  std::size_t sentCount() const { return sendIndex_.size(); }

  // The owned particles were reordered (Particles::permute(order): new k is
  // old order[k]); the halo's send lists follow them. Call it after every
  // sort between makeHalos() and the next migrate().
  // `order` may cover the ghosts too (the hash grid's does: a periodic
  // ghost that is sent follows its slot).
  void followPermutation(const std::vector<std::uint32_t>& order, std::size_t owned) {
    if (sendIndex_.empty()) return;
    if (order.size() < owned) throw std::logic_error("DomainDecomposition::followPermutation: an order per owned particle");
    newIndex_.resize(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) newIndex_[order[k]] = static_cast<std::uint32_t>(k);
    for (std::uint32_t& i : sendIndex_)
      if (i < order.size()) i = newIndex_[i];
  }

  // Send the fields in `fields` of the halos again (collective among the
  // ranks that exchange halos): start, then finish.
  void refreshHalos(Particles<D>& P, FieldSet fields) {
    startHaloRefresh(P, fields);
    finishHaloRefresh(P);
  }

  // Pack and post the sends and receives; return at once.
  void startHaloRefresh(const Particles<D>& P, FieldSet fields) {
    if (comm_.size == 1) return;
    if (!requests_.empty()) throw std::logic_error("DomainDecomposition: a halo refresh is already under way");
    Timed timed(&CommunicationTime::halo);
    refreshFields_ = fields & P.refreshed();  // (a halo's build positions are its rank's own)
    record_ = recordBytes(P, refreshFields_);
    if (record_ == 0) return;
    ++communicationTime().haloRefreshes;
    communicationTime().haloBytesSent += static_cast<double>(sendIndex_.size() * record_);
    pack(P, refreshFields_, record_, sendIndex_, sendBuffer_);
    recvBuffer_.resize(haloCount_ * record_);
    type_ = recordType(record_);
    for (int q = 0; q < comm_.size; ++q)
      if (recvCount_[q] > 0) {
        requests_.emplace_back();
        MPI_Irecv(recvBuffer_.data() + static_cast<std::size_t>(recvAt_[q]) * record_, recvCount_[q], type_, q,
                  kHaloTag, comm_.comm, &requests_.back());
      }
    for (int q = 0; q < comm_.size; ++q)
      if (sendCount_[q] > 0) {
        requests_.emplace_back();
        MPI_Isend(sendBuffer_.data() + static_cast<std::size_t>(sendAt_[q]) * record_, sendCount_[q], type_, q,
                  kHaloTag, comm_.comm, &requests_.back());
      }
  }

  // Wait for the halo's fields and copy them into the halo particles.
  void finishHaloRefresh(Particles<D>& P) {
    if (comm_.size == 1 || record_ == 0) return;
    Timed timed(&CommunicationTime::halo);
    MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
    requests_.clear();
    MPI_Type_free(&type_);
    const std::size_t owned = P.size();
    const auto& source = P.ghostSource();
    std::size_t offset = 0;
    P.forEachField([&](const FieldInfo& info, auto& field) {
      if (((refreshFields_ >> info.id) & 1u) == 0) return;
      using T = typename std::decay_t<decltype(field)>::value_type;
      for (std::size_t g = 0; g < source.size(); ++g)
        if (source[g] & Particles<D>::kRemoteSource) {
          const std::size_t slot = source[g] & ~Particles<D>::kRemoteSource;
          std::memcpy(static_cast<void*>(&field[owned + g]), recvBuffer_.data() + slot * record_ + offset, sizeof(T));
        }
      offset += sizeof(T);
    });
    record_ = 0;
  }

 private:
  static constexpr int kHaloTag = 2001;

  static std::int64_t floorToInt(Real s) {  // as HashGrid's
    const auto t = static_cast<std::int64_t>(s);
    return t - (static_cast<Real>(t) > s);
  }

  // The lowest cell of every rank's particles, less one, is the curve's origin.
  void setOrigin(const Particles<D>& P) {
    std::int64_t lo[D];
    for (int d = 0; d < D; ++d) lo[d] = INT64_MAX;
    for (std::size_t i = 0; i < P.size(); ++i)
      for (int d = 0; d < D; ++d) lo[d] = std::min(lo[d], floorToInt(P.x[i][d] * invCell_));
    if (comm_.size > 1) MPI_Allreduce(MPI_IN_PLACE, lo, D, MPI_INT64_T, MPI_MIN, comm_.comm);
    for (int d = 0; d < D; ++d) origin_[d] = lo[d] == INT64_MAX ? 0 : lo[d] - 1;
  }

  void clearHaloRecords() {
    sendIndex_.clear();
    sendCount_.assign(static_cast<std::size_t>(comm_.size), 0);
    recvCount_.assign(static_cast<std::size_t>(comm_.size), 0);
    haloCount_ = 0;
  }

  static std::size_t recordBytes(const Particles<D>& P, FieldSet fields) {
    std::size_t bytes = 0;
    P.forEachField([&](const FieldInfo& info, const auto& field) {
      if ((fields >> info.id) & 1u) bytes += sizeof(typename std::decay_t<decltype(field)>::value_type);
    });
    return bytes;
  }

  static MPI_Datatype recordType(std::size_t bytes) {
    MPI_Datatype type;
    MPI_Type_contiguous(static_cast<int>(bytes), MPI_BYTE, &type);
    MPI_Type_commit(&type);
    return type;
  }

  // Record k of `buffer` := the fields of particle index[k], in table order.
  static void pack(const Particles<D>& P, FieldSet fields, std::size_t record, const std::vector<std::uint32_t>& index,
                   std::vector<char>& buffer) {
    buffer.resize(index.size() * record);
    std::size_t offset = 0;
    P.forEachField([&](const FieldInfo& info, const auto& field) {
      if (((fields >> info.id) & 1u) == 0) return;
      using T = typename std::decay_t<decltype(field)>::value_type;
      for (std::size_t k = 0; k < index.size(); ++k)
        std::memcpy(buffer.data() + k * record + offset, static_cast<const void*>(&field[index[k]]), sizeof(T));
      offset += sizeof(T);
    });
  }

  // Particle first + k := record slot[k] of the receive buffer.
  void unpack(Particles<D>& P, FieldSet fields, std::size_t record, std::size_t first,
              const std::vector<std::uint32_t>& slot) {
    std::size_t offset = 0;
    P.forEachField([&](const FieldInfo& info, auto& field) {
      if (((fields >> info.id) & 1u) == 0) return;
      using T = typename std::decay_t<decltype(field)>::value_type;
      for (std::size_t k = 0; k < slot.size(); ++k)
        std::memcpy(static_cast<void*>(&field[first + k]), recvBuffer_.data() + slot[k] * record + offset, sizeof(T));
      offset += sizeof(T);
    });
  }

  Communicator comm_;
  Real cellSize_, invCell_;
  std::int64_t origin_[D] = {};
  std::vector<std::uint64_t> splitters_;
  std::vector<std::pair<std::uint64_t, double>> cellWeights_;
  // Migration's scratch.
  std::vector<int> dest_;
  std::vector<std::uint32_t> order_, slot_, newIndex_;
  // The halo: owned particles sent to rank q are sendIndex_[sendAt_[q] ...
  // + sendCount_[q]); those from rank q fill receive slots [recvAt_[q], ...
  // + recvCount_[q]).
  std::vector<std::uint32_t> sendIndex_;
  std::vector<int> sendCount_, sendAt_, recvCount_, recvAt_;
  // makeHalos' scratch, reused: no allocation once grown.
  std::vector<std::vector<std::uint32_t>> lists_;
  std::vector<std::uint32_t> localSource_, allSource_, localSlot_, senders_;
  std::vector<Vec<D>> localShift_, allShift_;
  std::size_t haloCount_ = 0;
  // A refresh under way.
  FieldSet refreshFields_ = 0;
  std::size_t record_ = 0;
  MPI_Datatype type_ = MPI_DATATYPE_NULL;
  std::vector<MPI_Request> requests_;
  std::vector<char> sendBuffer_, recvBuffer_;
};

}  // namespace sph::mpi
