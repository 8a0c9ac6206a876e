// Atomic file replacement: write to "<path>.tmp", then rename over <path>.
// A run killed at any moment leaves either the old or the new file, never a
// half-written one; a failed write removes its ".tmp". What a killed run
// leaves behind (a stray ".tmp") removeStaleTemporaries() cleans up later.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace sph {

// Throws std::runtime_error naming the file if it cannot be written; the
// temporary is removed then.
void writeFileAtomically(const std::string& path, const std::string& content);

// Rename "<path>.tmp" (already written) over <path>; on failure removes the
// temporary and throws std::runtime_error naming the file.
void commitTemporary(const std::string& path);

// Append `text` to the file at `path` (which exists) in one write: the way
// a log that only grows (energy.csv, timestep.csv, the probe files) is
// brought up to date without rewriting it. A run killed during the write may
// leave a last line without its newline; readers of these logs drop it.
// Throws std::runtime_error naming the file if it cannot be written.
void appendToFile(const std::string& path, const std::string& text);

inline std::string temporaryName(const std::string& path) { return path + ".tmp"; }

// Deletes the temporaries of the files sph writes ("*.vtp.tmp", "*.pvtp.tmp", "*.pvd.tmp",
// "*.csv.tmp", "*.json.tmp", "*.case.tmp": regular files only, in `dir` itself, not below)
// that a run killed while writing left behind; returns how many it deleted.
// Never throws: a folder that cannot be listed, or a file that cannot be
// deleted, is left as it is.
std::size_t removeStaleTemporaries(const std::filesystem::path& dir);

}  // namespace sph
