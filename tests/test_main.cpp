// The Boost.Test module; each suite lives in its own test_<suite>.cpp.
#define BOOST_TEST_MODULE sph
#include <boost/test/unit_test.hpp>
