// Wall-clock seconds this rank spends communicating, by kind:
//   halo        the halo refreshes (packing, the non-blocking sends and
//               receives, MPI_Waitall, unpacking: DomainDecomposition::
//               refreshHalos);
//   reductions  the collectives of mpi/collectives.hpp (time step, checks,
//               energies, probes, the work measure...);
//   resort      the re-sort's exchanges: sharing out by work, migration and
//               making the halos (the halo refresh inside them counts here).
// Each includes the time spent waiting for the other ranks to get there, so
// it is the time this rank could not compute: load imbalance shows up in it.
// Only calls made with several ranks are timed (with one no MPI call is
// made); MPI_Wtime costs tens of nanoseconds against microseconds a call.
// The clocks are per process, touched only by the thread that talks to MPI
// (MPI_THREAD_FUNNELED, session.hpp).
#pragma once

#include <mpi.h>

namespace sph::mpi {

struct CommunicationTime {
  double halo = 0, reductions = 0, resort = 0;
  long haloRefreshes = 0, reductionCalls = 0;
  double haloBytesSent = 0;  // sent by the halo refreshes (the one filling new halos at a re-sort too)

  double total() const { return halo + reductions + resort; }
  CommunicationTime& operator+=(const CommunicationTime& o) {
    halo += o.halo, reductions += o.reductions, resort += o.resort;
    haloRefreshes += o.haloRefreshes, reductionCalls += o.reductionCalls;
    haloBytesSent += o.haloBytesSent;
    return *this;
  }
  CommunicationTime operator-(const CommunicationTime& o) const {
    return {halo - o.halo,
            reductions - o.reductions,
            resort - o.resort,
            haloRefreshes - o.haloRefreshes,
            reductionCalls - o.reductionCalls,
            haloBytesSent - o.haloBytesSent};
  }
};

// This process's clocks since it started.
inline CommunicationTime& communicationTime() {
  static CommunicationTime clocks;
  return clocks;
}

// Adds the seconds of its lifetime to one clock, unless another Timed is
// already running (the outermost counts: a halo refresh made inside the
// re-sort is the re-sort's).
class Timed {
 public:
  explicit Timed(double CommunicationTime::*clock) : clock_(depth()++ == 0 ? clock : nullptr) {
    if (clock_) start_ = MPI_Wtime();
  }
  Timed(const Timed&) = delete;
  Timed& operator=(const Timed&) = delete;
  ~Timed() {
    --depth();
    if (clock_) communicationTime().*clock_ += MPI_Wtime() - start_;
  }

 private:
  static int& depth() {
    static int d = 0;
    return d;
  }
  double CommunicationTime::*clock_;
  double start_ = 0;
};

}  // namespace sph::mpi
