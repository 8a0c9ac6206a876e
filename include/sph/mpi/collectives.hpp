// Reductions over the ranks of a run: sums, minima and maxima every rank
// gets (MPI_Allreduce), and the first failure of any rank. With one rank
// they return their argument and make no MPI call, so the one-rank path is
// the code it was.
#pragma once

#include "sph/mpi/communication_time.hpp"
#include "sph/mpi/session.hpp"
#include "sph/types.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace sph::mpi {

// MPI_Allreduce in place, timed as a reduction (communication_time.hpp).
inline void allReduce(const Communicator& c, void* values, int n, MPI_Datatype type, MPI_Op op) {
  if (c.size == 1) return;
  Timed timed(&CommunicationTime::reductions);
  ++communicationTime().reductionCalls;
  MPI_Allreduce(MPI_IN_PLACE, values, n, type, op, c.comm);
}

inline double allSum(const Communicator& c, double value) {
  allReduce(c, &value, 1, MPI_DOUBLE, MPI_SUM);
  return value;
}
inline std::int64_t allSum(const Communicator& c, std::int64_t value) {
  allReduce(c, &value, 1, MPI_INT64_T, MPI_SUM);
  return value;
}
inline double allMax(const Communicator& c, double value) {
  allReduce(c, &value, 1, MPI_DOUBLE, MPI_MAX);
  return value;
}
inline double allMin(const Communicator& c, double value) {
  allReduce(c, &value, 1, MPI_DOUBLE, MPI_MIN);
  return value;
}
inline int allMax(const Communicator& c, int value) {
  allReduce(c, &value, 1, MPI_INT, MPI_MAX);
  return value;
}
// n values at once, in place (one message for several maxima / sums).
inline void allMax(const Communicator& c, double* values, int n) { allReduce(c, values, n, MPI_DOUBLE, MPI_MAX); }
inline void allSum(const Communicator& c, double* values, int n) { allReduce(c, values, n, MPI_DOUBLE, MPI_SUM); }
inline void allSum(const Communicator& c, std::int64_t* values, int n) {
  allReduce(c, values, n, MPI_INT64_T, MPI_SUM);
}

// Every rank's `mine`, in rank order, on every rank (T copied as bytes:
// plain data; MPI_Allgatherv of bytes, so at most 2 GiB in all). For data
// gathered once per run, not per step.
template <class T>
std::vector<T> allGather(const Communicator& c, const std::vector<T>& mine) {
  if (c.size == 1) return mine;
  Timed timed(&CommunicationTime::reductions);
  ++communicationTime().reductionCalls;
  const int bytes = static_cast<int>(mine.size() * sizeof(T));
  std::vector<int> counts(static_cast<std::size_t>(c.size)), displs(static_cast<std::size_t>(c.size));
  MPI_Allgather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, c.comm);
  long total = 0;
  for (int r = 0; r < c.size; ++r) displs[r] = static_cast<int>(total), total += counts[r];
  if (total > INT32_MAX) throw std::runtime_error("mpi::allGather: more than 2 GiB");
  std::vector<T> all(static_cast<std::size_t>(total) / sizeof(T));
  MPI_Allgatherv(mine.data(), bytes, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, c.comm);
  return all;
}

// A particle's value with its id.
template <class T>
struct ById {
  std::int64_t id;
  T value;
};

// Every rank's records on every rank, in the order of their ids (unique
// over the ranks): the same sequence however the particles are shared out,
// so that sums over it are the same double on any number of ranks.
template <class T>
std::vector<ById<T>> allGatherById(const Communicator& c, const std::vector<ById<T>>& mine) {
  std::vector<ById<T>> all = allGather(c, mine);
  std::sort(all.begin(), all.end(), [](const ById<T>& a, const ById<T>& b) { return a.id < b.id; });
  return all;
}

// Rank `root`'s text on every rank.
inline std::string broadcast(const Communicator& c, std::string text, int root) {
  if (c.size == 1) return text;
  long long length = static_cast<long long>(text.size());
  MPI_Bcast(&length, 1, MPI_LONG_LONG, root, c.comm);
  text.resize(static_cast<std::size_t>(length));
  if (length > 0) MPI_Bcast(text.data(), static_cast<int>(length), MPI_CHAR, root, c.comm);
  return text;
}

// The lowest of the ranks' keys (INT64_MAX: none) and the lowest rank that
// holds it (-1 when no rank has one): a failure found on any rank, named the
// same on every rank.
struct FirstOfRanks {
  std::int64_t key = INT64_MAX;
  int rank = -1;
};
inline FirstOfRanks firstOfRanks(const Communicator& c, std::int64_t key) {
  FirstOfRanks first{key, key == INT64_MAX ? -1 : c.rank};
  if (c.size == 1) return first;
  allReduce(c, &first.key, 1, MPI_INT64_T, MPI_MIN);
  int mine = key == first.key && key != INT64_MAX ? c.rank : c.size;
  allReduce(c, &mine, 1, MPI_INT, MPI_MIN);
  first.rank = mine == c.size ? -1 : mine;
  return first;
}

}  // namespace sph::mpi
