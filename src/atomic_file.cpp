// Atomic file replacement (see atomic_file.hpp). Every failure path removes
// the temporary it wrote, so a failed write leaves nothing behind.
#include "sph/io/atomic_file.hpp"

#include <fstream>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace sph {
namespace {

// Removes our temporary; never a directory of that name (not ours).
void removeTemporary(const std::string& tmp) {
  std::error_code ec;
  if (!std::filesystem::is_directory(std::filesystem::symlink_status(tmp, ec))) std::filesystem::remove(tmp, ec);
}

}  // namespace

void commitTemporary(const std::string& path) {
  std::error_code ec;
  std::filesystem::rename(temporaryName(path), path, ec);
  if (ec) {
    removeTemporary(temporaryName(path));
    throw std::runtime_error("cannot write " + path + ": " + ec.message());
  }
}

void writeFileAtomically(const std::string& path, const std::string& content) {
  const std::string tmp = temporaryName(path);
  bool written = false;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << content;
    out.close();  // flushes: a full disk shows here
    written = !out.fail();
  }
  if (!written) {
    removeTemporary(tmp);
    throw std::runtime_error("cannot write " + tmp);
  }
  commitTemporary(path);
}

void appendToFile(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::app);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path);
}

std::size_t removeStaleTemporaries(const std::filesystem::path& dir) {
  static const char* suffixes[] = {".vtp.tmp", ".pvtp.tmp", ".pvd.tmp", ".csv.tmp", ".json.tmp", ".case.tmp"};
  std::vector<std::filesystem::path> stale;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code typeError;
    if (!it->is_regular_file(typeError) || it->is_symlink(typeError)) continue;
    const std::string name = it->path().filename().string();
    for (const std::string suffix : suffixes)
      if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
        stale.push_back(it->path());
  }
  std::size_t removed = 0;
  for (const auto& p : stale) {
    std::error_code removeError;
    removed += std::filesystem::remove(p, removeError) ? 1 : 0;
  }
  return removed;
}

}  // namespace sph
