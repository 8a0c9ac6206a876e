// Reductions over the ranks of a run: sums, minima and maxima every rank
// gets (MPI_Allreduce), and the first failure of any rank. With one rank
// they return their argument and make no MPI call, so the one-rank path is
// the code it was.
#pragma once

#include "sph/mpi/session.hpp"
#include "sph/types.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sph::mpi {

inline double allSum(const Communicator& c, double value) {
  if (c.size > 1) MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_SUM, c.comm);
  return value;
}
inline std::int64_t allSum(const Communicator& c, std::int64_t value) {
  if (c.size > 1) MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_INT64_T, MPI_SUM, c.comm);
  return value;
}
inline double allMax(const Communicator& c, double value) {
  if (c.size > 1) MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MAX, c.comm);
  return value;
}
inline double allMin(const Communicator& c, double value) {
  if (c.size > 1) MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MIN, c.comm);
  return value;
}
inline int allMax(const Communicator& c, int value) {
  if (c.size > 1) MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_INT, MPI_MAX, c.comm);
  return value;
}
// n values at once, in place (one message for several maxima / sums).
inline void allMax(const Communicator& c, double* values, int n) {
  if (c.size > 1) MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_MAX, c.comm);
}
inline void allSum(const Communicator& c, double* values, int n) {
  if (c.size > 1) MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, c.comm);
}
inline void allSum(const Communicator& c, std::int64_t* values, int n) {
  if (c.size > 1) MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_INT64_T, MPI_SUM, c.comm);
}

// Every rank's `mine`, in rank order, on every rank (T trivially
// copyable; MPI_Allgatherv of bytes, so at most 2 GiB in all). For data
// gathered once per run, not per step.
template <class T>
std::vector<T> allGather(const Communicator& c, const std::vector<T>& mine) {
  if (c.size == 1) return mine;
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

// The sum of every rank's values, added in the order of their ids (unique
// over the ranks): the same double however the values are shared out
// (sum() in any other order differs by round-off). Gathers every value on
// every rank: for a sum made once per run, not per step.
inline double allSumInIdOrder(const Communicator& c, const std::vector<std::int64_t>& id,
                              const std::vector<double>& value) {
  const std::vector<std::int64_t> ids = allGather(c, id);
  const std::vector<double> values = allGather(c, value);
  std::vector<std::pair<std::int64_t, double>> all;
  all.reserve(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k) all.emplace_back(ids[k], values[k]);
  std::sort(all.begin(), all.end());
  double sum = 0;
  for (const auto& iv : all) sum += iv.second;
  return sum;
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
  MPI_Allreduce(MPI_IN_PLACE, &first.key, 1, MPI_INT64_T, MPI_MIN, c.comm);
  int mine = key == first.key && key != INT64_MAX ? c.rank : c.size;
  MPI_Allreduce(MPI_IN_PLACE, &mine, 1, MPI_INT, MPI_MIN, c.comm);
  first.rank = mine == c.size ? -1 : mine;
  return first;
}

}  // namespace sph::mpi
