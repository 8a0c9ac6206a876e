// Helpers of the test suites that run the real `sph` executable: scratch
// folders, running sph, and the paths of the shipped cases and reference
// data. No simulator header: a suite that only runs sph includes this and
// is not rebuilt when the physics headers change (test_support.hpp adds
// scenes built in code).
#pragma once

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace sph::test {

// The scratch folders this test process made, removed when it exits
// (after main returns), unless the environment has SPH_KEEP_TEST_OUTPUT
// (to look at a failing test's files: its messages name the folders).
struct ScratchFolders {
  std::vector<std::filesystem::path> made;
  ScratchFolders() = default;
  ScratchFolders(const ScratchFolders&) = delete;
  ScratchFolders& operator=(const ScratchFolders&) = delete;
  ~ScratchFolders() {
    if (std::getenv("SPH_KEEP_TEST_OUTPUT")) return;
    std::error_code ignored;
    for (const auto& dir : made) std::filesystem::remove_all(dir, ignored);
  }
};
inline ScratchFolders& scratchFolders() {
  static ScratchFolders folders;
  return folders;
}

// A fresh, empty scratch folder under the system temp folder (removed when
// the test process exits: ScratchFolders).
inline std::filesystem::path scratchDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("sph_test_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ScratchFolders& folders = scratchFolders();
  if (std::find(folders.made.begin(), folders.made.end(), dir) == folders.made.end()) folders.made.push_back(dir);
  return dir;
}

struct Result {
  int exitCode;
  std::string output;  // stdout and stderr together
};

// Run a shell command line; its stdout and stderr together.
inline Result runCommandLine(std::string cmd) {
  cmd += " 2>&1";
  Result r{-1, ""};
  FILE* pipe = ::popen(cmd.c_str(), "r");
  BOOST_REQUIRE(pipe != nullptr);
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe)) r.output += buf.data();
  const int status = ::pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Run the real sph executable with the given arguments (shell-quoted here).
inline Result runSph(const std::vector<std::string>& args) {
  // SPH_TEST_EXECUTABLE runs the suites against another build of sph (the
  // seed_bitwise digests were recorded that way from the program before the
  // core was reshaped).
  const char* other = std::getenv("SPH_TEST_EXECUTABLE");
  std::string cmd = std::string("'") + (other ? other : SPH_EXECUTABLE) + "'";
  for (const auto& a : args) cmd += " '" + a + "'";
  return runCommandLine(cmd);
}

// A shipped case file, cases/NAME.case.
inline std::string caseFile(const std::string& name) {
  return std::string(SPH_SOURCE_DIR) + "/cases/" + name + ".case";
}

// A file of the reference data, tests/reference/NAME.
inline std::string referenceFile(const std::string& name) {
  return std::string(SPH_REFERENCE_DIR) + "/" + name;
}

}  // namespace sph::test
