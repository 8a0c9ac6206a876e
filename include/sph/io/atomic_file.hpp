// Atomic file replacement: write to "<path>.tmp", then rename over <path>.
// A run killed at any moment leaves either the old or the new file, never a
// half-written one.
#pragma once

#include <string>

namespace sph {

// Throws std::runtime_error naming the file if it cannot be written.
void writeFileAtomically(const std::string& path, const std::string& content);

// Rename "<path>.tmp" (already written) over <path>.
void commitTemporary(const std::string& path);

inline std::string temporaryName(const std::string& path) { return path + ".tmp"; }

}  // namespace sph
