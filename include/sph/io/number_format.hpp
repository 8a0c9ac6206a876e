// Numbers as text, the two ways sph writes them:
//  - shortestDecimal: the shortest decimal that reads back as the same double
//    (std::to_chars), so 0.58 is written "0.58", not "0.58000000000000007"
//    (files that are read again: run.case, the .pvd times);
//  - significant: printf's %.Ng, N significant digits (6 by default, as an
//    ostream writes a double), for messages and tables.
#pragma once

#include <charconv>
#include <cstdio>
#include <string>

namespace sph {

inline std::string shortestDecimal(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

inline std::string significant(double x, int digits = 6) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

}  // namespace sph
