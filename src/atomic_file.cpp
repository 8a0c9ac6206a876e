#include "sph/io/atomic_file.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <filesystem>

namespace sph {

void commitTemporary(const std::string& path) {
  std::error_code ec;
  std::filesystem::rename(temporaryName(path), path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temporaryName(path), ignored);
    throw std::runtime_error("cannot write " + path + ": " + ec.message());
  }
}

void writeFileAtomically(const std::string& path, const std::string& content) {
  {
    std::ofstream out(temporaryName(path), std::ios::binary | std::ios::trunc);
    out << content;
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + temporaryName(path));
  }
  commitTemporary(path);
}

}  // namespace sph
