// The MPI session of a test executable run under mpirun (the mpi label):
// started before the first test, ended after the last, always initialised
// (the tests are ranks). world() is the communicator the tests use.
// Include in one translation unit of the executable.
#pragma once

#include <boost/test/unit_test.hpp>

#include "sph/mpi/session.hpp"

#include <memory>

namespace sph::test {

inline std::unique_ptr<sph::mpi::Session> gSession;

struct MpiFixture {
  MpiFixture() {
    auto& suite = boost::unit_test::framework::master_test_suite();
    gSession = std::make_unique<sph::mpi::Session>(suite.argc, suite.argv, true);
  }
  ~MpiFixture() { gSession.reset(); }
};
BOOST_TEST_GLOBAL_FIXTURE(MpiFixture);

inline sph::mpi::Communicator world() { return gSession->communicator(); }

}  // namespace sph::test
