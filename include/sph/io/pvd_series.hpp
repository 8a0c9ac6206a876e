// PvdSeries: the ParaView collection file (.pvd) listing one .vtp per output
// step with its time. It is rewritten (atomically) after every output step so
// that a run stopped at any moment leaves a series ParaView opens. A resumed
// run loads the series it continues. Times are written as the shortest
// decimal that reads back exactly.
// VTK has no standalone writer for this tiny XML format, so we write it.
#pragma once

#include "sph/types.hpp"

#include <string>
#include <utility>
#include <vector>

namespace sph {

class PvdSeries {
 public:
  struct Entry {
    Real time;
    long step;
    std::string file;  // relative to the .pvd
  };

  explicit PvdSeries(std::string path) : path_(std::move(path)) {}

  // The series a run wrote; throws std::runtime_error naming the file if it
  // cannot be read or is not one sph writes.
  static PvdSeries load(const std::string& path);

  // Append a dataset (file name relative to the .pvd) and rewrite the file.
  // `step` is written as an extra attribute; ParaView's PVD reader ignores it.
  // (write = false: the entry only, the file left to the process that writes
  // it: MPI rank 0 of a run on several ranks.)
  void add(Real time, long step, const std::string& relativeFile, bool write = true);

  const std::string& path() const { return path_; }
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  std::string path_;
  std::vector<Entry> entries_;
};

}  // namespace sph
