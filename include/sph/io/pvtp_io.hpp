// Parallel snapshots: VTK's parallel PolyData format (.pvtp). One snapshot
// of R ranks is R .vtp pieces, each a rank's particles written by writeVtp
// (the arrays, units and field data of vtp_io.hpp; atomic), and one summary
// file NAME.pvtp listing them, written by VTK's vtkXMLPPolyDataWriter: the
// point arrays' names and types, the field data (TimeValue, step, ...) and
// one <Piece Source="NAME_r.vtp"/> per rank, r = 0 .. R-1 (VTK's own piece
// naming, next to the summary). Readers (ParaView, vtkXMLPPolyDataReader,
// readVtp) append the pieces in that order.
//
// The ranks' part (each writes its piece, then rank 0 the summary once every
// piece exists) is mpi/parallel_snapshot.hpp; here is what needs no MPI.
#pragma once

#include "sph/io/vtp_io.hpp"

#include <string>

namespace sph {

// The file name (no folder) of piece `rank` of the summary at `pvtpPath`:
// "NAME_<rank>.vtp" for ".../NAME.pvtp", as VTK names it.
std::string pvtpPieceName(const std::string& pvtpPath, int rank);

// The summary of a snapshot in `pieces` pieces whose arrays are those of `P`
// (any rank's particles: every rank has the same fields), written
// atomically; the pieces are not touched. Throws std::runtime_error naming
// the file on failure.
template <int D>
void writePvtpSummary(const std::string& pvtpPath, const Particles<D>& P, const SnapshotInfo& info, int pieces);

}  // namespace sph
