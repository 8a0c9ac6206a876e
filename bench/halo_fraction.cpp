// sph-halo-fraction: how many halo particles the domain decomposition
// (include/sph/mpi/domain_decomposition.hpp) gives a set of particles.
//
//   mpirun -n R build/sph-halo-fraction SNAPSHOT.vtp RADIUS [DIMENSION]
//
// Every rank reads the snapshot (an sph .vtp: fluid and walls) and keeps
// every R-th particle; the ranks balance (particle count per cell), migrate
// and make the halos within RADIUS (the neighbour list's: the kernel support
// times 1 + neighbour_skin). Rank 0 prints, per rank and in all, the owned
// particles, the halo particles and their ratio (the halo fraction), and the
// particles sent; then what the messages cost without waiting: the ranks
// meet at a barrier, refresh the halos of every field they hold 200 times
// (packing, MPI_Isend/Irecv, MPI_Waitall, unpacking) and make 1 000
// MPI_Allreduce of one number; the slowest rank's mean per call. A
// measurement, not a test.
#include "sph/mpi/communication_time.hpp"
#include "sph/mpi/domain_decomposition.hpp"
#include "sph/mpi/session.hpp"
#include "sph/particle_sources.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

namespace {

// The slowest rank's mean seconds per call of f, called n times after a barrier.
template <class F>
double secondsPerCall(const sph::mpi::Communicator& c, int n, F&& f) {
  MPI_Barrier(c.comm);
  const double t0 = MPI_Wtime();
  for (int k = 0; k < n; ++k) f();
  double t = (MPI_Wtime() - t0) / n;
  MPI_Allreduce(MPI_IN_PLACE, &t, 1, MPI_DOUBLE, MPI_MAX, c.comm);
  return t;
}

template <int D>
int measure(const sph::mpi::Communicator& c, const std::string& file, sph::Real radius) {
  const sph::Particles<D> all = sph::resumeState<D>(file).particles;
  sph::Particles<D> P;
  std::size_t fluid = 0;
  for (std::size_t i = static_cast<std::size_t>(c.rank); i < all.size(); i += static_cast<std::size_t>(c.size)) {
    P.x.push_back(all.x[i]);
    P.v.push_back(all.v[i]);
    P.m.push_back(all.m[i]);
    P.id.push_back(all.id[i]);
    fluid += i < all.fluidCount();
  }
  P.resize(P.x.size(), fluid);
  P.allocate(0);
  sph::mpi::DomainDecomposition<D> dd(c, radius);
  dd.balance(P);
  dd.migrate(P);
  dd.makeHalos(P, radius);
  double refresh = 0, allreduce = 0, bytes = 0;
  if (c.size > 1) {
    const sph::FieldSet fields = P.allocated();
    const double before = sph::mpi::communicationTime().haloBytesSent;
    refresh = secondsPerCall(c, 200, [&] { dd.refreshHalos(P, fields); });
    bytes = (sph::mpi::communicationTime().haloBytesSent - before) / 200;
    double one = 1;
    allreduce = secondsPerCall(c, 1000, [&] { MPI_Allreduce(MPI_IN_PLACE, &one, 1, MPI_DOUBLE, MPI_MAX, c.comm); });
  }
  long mine[4] = {static_cast<long>(P.size()), static_cast<long>(dd.haloCount()), static_cast<long>(dd.sentCount()),
                  static_cast<long>(P.fluidCount())};
  std::vector<long> every(4 * static_cast<std::size_t>(c.size));
  if (c.size > 1) MPI_Gather(mine, 4, MPI_LONG, every.data(), 4, MPI_LONG, 0, c.comm);
  else every.assign(mine, mine + 4);
  if (c.size > 1) MPI_Allreduce(MPI_IN_PLACE, &bytes, 1, MPI_DOUBLE, MPI_MAX, c.comm);
  if (c.rank != 0) return 0;
  std::printf("%s: %zu particles (%zu fluid), radius %g, %d ranks\n", file.c_str(), all.size(), all.fluidCount(),
              static_cast<double>(radius), c.size);
  std::printf("rank,owned,fluid,halo,halo_fraction,sent\n");
  long owned = 0, halo = 0;
  for (int r = 0; r < c.size; ++r) {
    const long* e = &every[4 * static_cast<std::size_t>(r)];
    std::printf("%d,%ld,%ld,%ld,%.4f,%ld\n", r, e[0], e[3], e[1], e[0] ? double(e[1]) / double(e[0]) : 0.0, e[2]);
    owned += e[0];
    halo += e[1];
  }
  std::printf("all,%ld,,%ld,%.4f,\n", owned, halo, owned ? double(halo) / double(owned) : 0.0);
  if (c.size > 1)
    std::printf("a halo refresh of every field (at most %.0f bytes sent by a rank): %.1f us; an MPI_Allreduce of "
                "one number: %.2f us (slowest rank, mean of 200 and 1 000 calls after a barrier)\n",
                bytes, 1e6 * refresh, 1e6 * allreduce);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  sph::mpi::Session session(argc, argv);
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: mpirun -n R sph-halo-fraction SNAPSHOT.vtp RADIUS [DIMENSION (2)]\n");
    return 2;
  }
  try {
    const sph::Real radius = std::stod(argv[2]);
    const int dimension = argc == 4 ? std::atoi(argv[3]) : 2;
    if (dimension == 3) return measure<3>(session.communicator(), argv[1], radius);
    return measure<2>(session.communicator(), argv[1], radius);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sph-halo-fraction: %s\n", e.what());
    if (session.active()) MPI_Abort(session.comm(), 1);  // the others may wait in a collective call
    return 1;
  }
}
