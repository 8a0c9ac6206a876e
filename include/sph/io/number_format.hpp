// Numbers as text: the shortest decimal that reads back as the same double
// (std::to_chars), so 0.58 is written "0.58", not "0.58000000000000007".
#pragma once

#include <charconv>
#include <string>

namespace sph {

inline std::string shortestDecimal(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

}  // namespace sph
