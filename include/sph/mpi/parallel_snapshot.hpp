// writeParallelSnapshot: one snapshot of R ranks as NAME.pvtp and its R
// pieces (io/pvtp_io.hpp), every rank writing its own particles.
//
// Order, so that an interrupted run never leaves a .pvtp naming a piece that
// does not exist: (1) each rank writes its piece NAME_r.vtp atomically
// (writeVtp: a temporary renamed), (2) all ranks agree that every piece was
// written (MPI_Allreduce of a flag: also the barrier), (3) rank 0 writes the
// summary, atomically, and (4) tells the others whether it could. A failure
// anywhere makes every rank throw (no rank is left waiting in a collective
// call); the rank that failed names its file, the others the rank.
//
// On one rank (no launcher, or mpirun -n 1) a run writes today's NAME.vtp
// with writeVtp instead (run_output.cpp): no summary, no piece.
#pragma once

#include "sph/io/pvtp_io.hpp"
#include "sph/io/vtp_io.hpp"
#include "sph/mpi/session.hpp"

#include <filesystem>
#include <stdexcept>
#include <string>

namespace sph::mpi {

template <int D>
void writeParallelSnapshot(const std::string& pvtpPath, const Particles<D>& P, const SnapshotInfo& info,
                           const Communicator& c) {
  const std::string piece =
      (std::filesystem::path(pvtpPath).parent_path() / pvtpPieceName(pvtpPath, c.rank)).string();
  std::string error;
  try {
    writeVtp<D>(piece, P, info);
  } catch (const std::exception& e) {
    error = e.what();
  }
  int written = error.empty() ? 1 : 0, everyPiece = written;
  if (c.size > 1) MPI_Allreduce(&written, &everyPiece, 1, MPI_INT, MPI_MIN, c.comm);
  if (!written) throw std::runtime_error(error);
  if (!everyPiece) throw std::runtime_error("cannot write " + pvtpPath + ": another rank could not write its piece");
  int summary = 1;
  if (c.rank == 0) {
    try {
      writePvtpSummary<D>(pvtpPath, P, info, c.size);
    } catch (const std::exception& e) {
      error = e.what();
      summary = 0;
    }
  }
  if (c.size > 1) MPI_Bcast(&summary, 1, MPI_INT, 0, c.comm);
  if (!summary) throw std::runtime_error(c.rank == 0 ? error : "cannot write " + pvtpPath + " (rank 0 could not)");
}

}  // namespace sph::mpi
