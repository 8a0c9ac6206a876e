// One whole run, stage by stage: the checked start (run_start.hpp), the
// threads, the scene, Catalyst, the output folder (run_folder.hpp), the
// record (run_report.hpp), the files (run_output.hpp), the time loop
// (run_driver.hpp) and the summary. See run_case.hpp for the exit codes.
#include "sph/run_case.hpp"

#include "sph/case_file.hpp"
#include "sph/io/catalyst.hpp"
#include "sph/io/run_output.hpp"
#include "sph/model_registry.hpp"
#include "sph/mpi/collectives.hpp"
#include "sph/run_driver.hpp"
#include "sph/run_report.hpp"
#include "sph/run_start.hpp"
#include "sph/scene.hpp"
#include "sph/thread_tuner.hpp"

#include <omp.h>
#include <malloc.h>

#include <cstdlib>
#include <memory>
#include <ostream>
#include <stdexcept>

namespace sph {

template <int D>
int runCase(const CaseConfig& given, std::ostream& out, std::ostream& err) {
  std::optional<RunStart<D>> start = startRun<D>(given, err);
  if (!start) return kBadInput;
  const ResolvedCase& c = start->c;
  const bool resuming = start->resuming;
  InitialState<D>& init = start->init;
  // Several MPI ranks (docs/developer/mpi.md): every rank read the same case
  // and built the same particles; the scene keeps each rank's share. Only
  // rank 0 writes (but the snapshot pieces) and prints (main gives the other
  // ranks silent streams).
  const mpi::Communicator& comm = mpi::world();

  const std::size_t n = init.particles.size();
  // Particles the reflecting walls will move on the first step (a note).
  std::size_t nearWall = 0;
  if (const auto walls = makeReflectingWalls<D>(c); walls && !resuming)
    for (const auto& x : init.particles.x) nearWall += walls->clamps(x);

  // Threads: an explicit count (or OMP_NUM_THREADS) is obeyed; auto is tuned.
  const int asked = requestedThreads(c);
  const bool autoThreads = asked == 0 && std::getenv("OMP_NUM_THREADS") == nullptr;
  if (asked > 0) omp_set_num_threads(asked);
  ThreadTuner tuner = autoThreads ? ThreadTuner(n) : ThreadTuner::fixed(omp_get_max_threads());

  // The run's clock: a new run starts at the time of its particles (0, or a
  // particle_file's); a resumed one at the original run's start.
  const Real startTime = resuming ? start->previous.startTime : init.startTime;
  const Real resumeTime = init.startTime;
  const long resumeStep = init.startStep;
  const bool massesGiven = init.massesGiven;
  const bool inSortOrder = init.inSortOrder;
  Scene<D> scene = makeScene<D>(c, std::move(init), startTime);
  scene.setDecomposition(comm, c.rebalanceTolerance);
  try {
    const auto failure = resuming ? scene.resume(resumeStep, resumeTime, inSortOrder) : scene.initialise(!massesGiven);
    if (failure) {
      err << "sph: error: the initial state is not valid: particle id " << failure->id << ": " << failure->detail
          << "\n";
      return kBadInput;
    }
  } catch (const std::runtime_error& e) {
    err << "sph: error: resume: " << start->resumeSnapshot << ": " << e.what() << "\n";
    return kBadInput;
  }

  // The Catalyst script, when given: loaded (ParaView's start-up) after the
  // case's own checks and before anything is written, so that a missing or
  // broken script is refused with no folder made.
  // On several ranks every rank loads it, and fails when any rank fails.
  std::unique_ptr<Catalyst> catalyst;
  if (!c.catalyst.empty()) {
    try {
      catalyst = std::make_unique<Catalyst>(c.catalyst, c.output, c.name, comm);
    } catch (const CaseError& e) {
      err << "sph: error: " << escapeControl(e.what()) << "\n";
      return kBadInput;
    }
  }

  // Everything that can be checked has been: now, and only now, write.
  int folderMade = comm.rank == 0 ? makeRunFolder(c.output, c.overwrite, err) : 0;
  if (comm.size > 1) MPI_Bcast(&folderMade, 1, MPI_INT, 0, comm.comm);
  if (!folderMade) return kBadInput;
  if (!c.particleFile.empty() && !resuming && (!c.blockMin.empty() || !c.discCenter.empty() || !c.points.empty()))
    err << "sph: note: particles come from particle_file " << c.particleFile
        << "; the case's block, disc and points generators are not used\n";
  if (nearWall > 0)
    err << "sph: note: " << nearWall << " particle(s) start closer than h = " << c.h
        << " to a wall; the walls move them to distance h on the first step\n";

  const std::filesystem::path dir(c.output);
  RunReport report(dir, c, start->previous, resuming, resumeStep, resumeTime, startTime, n,
                   scene.globalFluidCount());
  const SnapshotInfo info = snapshotInfo<D>(c, n);
  RunOutput<D> output(dir, c.name, info, report.record(), c.cfl > 0, ProbeFiles<D>(c, makeProbeKernel<D>(c)));
  if (resuming) output.resumeAfter(resumeStep, resumeTime);

  // The set-up's freed heap (the particle generator's arrays, the first
  // sort's) goes back to the system before the run: nothing trims the
  // heap later (vtp_io.cpp keeps zlib's buffers on it), so it would stay
  // resident to the end. 2D dam break, packed list, 24 818 -> 214 910
  // particles: peak RSS 192.7 -> 186.9 bytes per added particle.
  malloc_trim(0);
  const RunTotals totals =
      driveRun<D>(c, scene, output, report, tuner, catalyst, info, startTime, resumeTime, resuming, err);
  if (totals.status == kWriteFailed) return kWriteFailed;
  try {
    if (totals.status == kSuccess) {
      report.record().status = "finished";
      if (c.starMass > 0) writeStarProfiles(scene, c, dir, out, report.record());
    }
    report.finish(scene, c, totals, tuner, autoThreads, resumeTime, output, out, err);
  } catch (const std::runtime_error& e) {
    err << "sph: error: " << e.what() << "\n";
    return kWriteFailed;
  }
  return totals.status;
}

template int runCase<2>(const CaseConfig&, std::ostream&, std::ostream&);
template int runCase<3>(const CaseConfig&, std::ostream&, std::ostream&);

}  // namespace sph
