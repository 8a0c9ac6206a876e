// For the bad-input checks of the suites: validateCase(c) refuses the case
// with a CaseError whose message names `key` (or any text the test expects).
#pragma once

#include "sph/case_config.hpp"

#include <boost/test/unit_test.hpp>

#include <string>

namespace sph::test {

inline bool refusedNaming(const CaseConfig& c, const std::string& key) {
  try {
    validateCase(c);
  } catch (const CaseError& e) {
    BOOST_TEST_MESSAGE(e.what());
    return std::string(e.what()).find(key) != std::string::npos;
  }
  return false;
}

}  // namespace sph::test
