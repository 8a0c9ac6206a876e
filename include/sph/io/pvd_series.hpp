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
  void add(Real time, const std::string& relativeFile);

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<std::pair<Real, std::string>> entries_;
};

}  // namespace sph
