// PvdSeries: the ParaView collection file (.pvd) listing one .vtp per output
// step with its time. It is rewritten (atomically) after every output step so
// that a run stopped at any moment leaves a series ParaView opens.
// VTK has no standalone writer for this tiny XML format, so we write it.
#pragma once

#include "sph/types.hpp"

#include <string>
#include <utility>
#include <vector>

namespace sph {

class PvdSeries {
 public:
  explicit PvdSeries(std::string path) : path_(std::move(path)) {}

  // Append a dataset (file name relative to the .pvd) and rewrite the file.
  // `step` is written as an extra attribute; ParaView's PVD reader ignores it.
  void add(Real time, long step, const std::string& relativeFile);

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  struct Entry {
    Real time;
    long step;
    std::string file;
  };
  std::vector<Entry> entries_;
};

}  // namespace sph
