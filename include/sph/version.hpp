// sph's version and the git commit it was built from.
#pragma once

#include <string>

namespace sph {

// "abc1234", "abc1234-dirty" (uncommitted changes at build time), or
// "unknown" when built outside a git checkout.
std::string gitCommit();

}  // namespace sph
