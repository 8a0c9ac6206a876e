#include "sph/version.hpp"

#include "sph_git_commit.hpp"  // generated at every build (cmake/git_commit.cmake)

namespace sph {

std::string gitCommit() { return SPH_GIT_COMMIT; }

}  // namespace sph
