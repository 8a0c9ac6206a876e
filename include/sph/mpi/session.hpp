// mpi::Session: MPI for the lifetime of one object, and the communicator a
// run uses (its rank and size).
//
// The constructor calls MPI_Init_thread with MPI_THREAD_FUNNELED (OpenMP
// threads compute, only the thread that called it talks to MPI: MPI 4.0
// standard, section 11.2.1), the destructor MPI_Finalize. The communicator
// is a duplicate of MPI_COMM_WORLD, so that the simulator's messages never
// match a library's.
//
// Started by a launcher (mpirun, mpiexec, srun: it sets one of the variables
// in launchedByMpi()) the session initialises MPI. Started on its own, it
// does not: the process is rank 0 of 1, no MPI call is made, and `sph`
// behaves exactly as a build without MPI (OpenMPI's singleton start would
// otherwise fork a helper daemon at every run). Code that communicates asks
// size() first; with one rank there is nothing to send. A process that
// initialised MPI sets SPH_MPI_PARENT in its environment: the programs it
// starts (sph study's runs) inherit the launcher's variables but are not
// ranks, and would fail in MPI_Init; with it they run alone.
#pragma once

#include <mpi.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace sph::mpi {

// The ranks a computation spans: a communicator, this process's rank in it
// and their number. {MPI_COMM_SELF, 0, 1}: alone (no MPI call is then made).
struct Communicator {
  MPI_Comm comm = MPI_COMM_SELF;
  int rank = 0;
  int size = 1;
};

// Whether a launcher started this process (OpenMPI, PMIx, Hydra/PMI,
// Slurm), not a rank that did (SPH_MPI_PARENT).
inline bool launchedByMpi() {
  if (std::getenv("SPH_MPI_PARENT")) return false;
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

// The communicator of the process's run: the active Session's (set by its
// constructor, reset by its destructor), else {MPI_COMM_SELF, 0, 1}.
inline Communicator& worldSlot() {
  static Communicator world;
  return world;
}
inline const Communicator& world() { return worldSlot(); }

class Session {
 public:
  // initialise: false keeps MPI off whatever the environment (tests of the
  // single-rank path); by default it is on when a launcher started us.
  Session(int& argc, char**& argv, bool initialise = launchedByMpi()) {
    if (!initialise) return;
    int already = 0;
    MPI_Initialized(&already);
    if (already) throw std::logic_error("mpi::Session: MPI is already initialised");
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    initialised_ = true;
    if (provided < MPI_THREAD_FUNNELED) {
      MPI_Finalize();
      initialised_ = false;
      throw std::runtime_error("the MPI library does not support MPI_THREAD_FUNNELED (threads with MPI)");
    }
    setenv("SPH_MPI_PARENT", "1", 1);  // POSIX
    MPI_Comm_dup(MPI_COMM_WORLD, &comm_);
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &size_);
    worldSlot() = communicator();
  }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  ~Session() {
    if (!initialised_) return;
    worldSlot() = Communicator{};
    MPI_Comm_free(&comm_);
    MPI_Finalize();
  }

  // Whether MPI was initialised (false: one rank, no MPI call is made).
  bool active() const { return initialised_; }
  MPI_Comm comm() const { return comm_; }
  Communicator communicator() const { return {comm_, rank_, size_}; }
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  bool initialised_ = false;
  MPI_Comm comm_ = MPI_COMM_SELF;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace sph::mpi
