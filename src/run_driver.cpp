// The time loop of a run (run_driver.hpp).
#include "sph/run_driver.hpp"

#include "sph/case_file.hpp"
#include "sph/case_keys.hpp"
#include "sph/io/atomic_file.hpp"
#include "sph/io/catalyst.hpp"
#include "sph/io/number_format.hpp"
#include "sph/io/run_output.hpp"
#include "sph/regime_check.hpp"
#include "sph/run_case.hpp"
#include "sph/run_signals.hpp"
#include "sph/scene.hpp"

#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <sstream>

namespace sph {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string formatDuration(double s) {
  char buf[32];
  if (!std::isfinite(s)) return "?";
  if (s < 120) std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 7200) std::snprintf(buf, sizeof buf, "%.0f min", s / 60);
  else std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  return buf;
}

std::string failureMessage(const StateFailure& f, long step, Real time) {
  std::ostringstream s;
  s << "the run blew up at step " << step << ", t = " << time << " s: particle id " << f.id << ": " << f.detail;
  return s.str();
}

// The progress line: live on a terminal (redrawn in place), else a line
// every 10 s.
template <int D>
void printProgress(const Scene<D>& scene, Real endTime, std::size_t n, const RunTotals& totals, Real resumeTime,
                   bool showLiveLine, std::ostream& err) {
  const double elapsed = secondsSince(totals.wall0);
  const double rate = totals.stepSeconds > 0 ? static_cast<double>(n) * static_cast<double>(scene.stepIndex() - totals.firstStep) / totals.stepSeconds : 0;
  char line[200];
  std::snprintf(line, sizeof line, "t = %.4g / %.4g s   step %ld   %.3g M particle-steps/s   %d thread(s)   ETA %s",
                scene.time(), endTime, scene.stepIndex(), rate / 1e6, omp_get_max_threads(),
                formatDuration(elapsed / (scene.time() - resumeTime) * (endTime - scene.time())).c_str());
  if (showLiveLine) err << "\r  " << line << "   " << std::flush;
  else err << "sph: " << line << "\n" << std::flush;
}

// The regime check of a run (regime_check.hpp) against the model's sound
// speed and rest density, unless regime_check = off.
template <int D>
class RegimeWatch {
 public:
  RegimeWatch(const CaseConfig& c, const Scene<D>& scene)
      : soundSpeed_(scene.model().regimeSoundSpeed()), densityRef_(scene.model().regimeDensity()),
        regime_(soundSpeed_, c.spacing,
                static_cast<std::size_t>(mpi::allSum(scene.communicator(),
                                                     static_cast<std::int64_t>(scene.particles().fluidCount())))),
        on_(c.regimeCheck != "off") {
    if (on_) regime_.start(measure(scene, c));
  }

  // Judges the scene now: warnings to err; with regime_check = stop, the
  // message to stop the run with when it left its regime (with warn, that
  // message once as a warning), else "".
  std::string judge(const Scene<D>& scene, const CaseConfig& c, bool showLiveLine, std::ostream& err) {
    if (!on_) return "";
    const auto verdict = regime_.judge(measure(scene, c), scene.lastTimeStep().dt, c.h);
    if (!verdict.warning.empty()) {
      if (showLiveLine) err << "\n";
      err << "sph: warning: at step " << scene.stepIndex() << ", t = " << shortestDecimal(scene.time()) << " s: " << verdict.warning << "\n";
    }
    // With warn, a run that left its regime says so once, not at every check.
    if (verdict.stop.empty() || (warned_ && c.regimeCheck != "stop")) return "";
    if (showLiveLine) err << "\n";
    const std::string message = "the run left its regime at step " + std::to_string(scene.stepIndex()) +
                                ", t = " + shortestDecimal(scene.time()) + " s: " + verdict.stop;
    if (c.regimeCheck == "stop") return message;
    err << "sph: warning: " << message << "\n";
    warned_ = true;
    return "";
  }

 private:
  RegimeState measure(const Scene<D>& scene, const CaseConfig& c) const {
    return measureRegime(scene.particles(), scene.neighbours(), soundSpeed_, c.spacing, densityRef_, scene.support(),
                         scene.communicator());
  }

  Real soundSpeed_, densityRef_;
  RegimeCheck regime_;
  bool on_;
  bool warned_ = false;
};

// Hands the particles to Catalyst; a script that fails during the run is
// reported once and left out for the rest of it (the run and its files go
// on: they are what the run is for).
template <int D>
void offerToCatalyst(std::unique_ptr<Catalyst>& catalyst, const Scene<D>& scene, SnapshotInfo info, bool last,
                     std::ostream& err) {
  if (!catalyst) return;
  info.time = scene.time();
  info.step = scene.stepIndex();
  const std::string failure = catalyst->offer<D>(scene.particles(), info, last);
  if (failure.empty()) return;
  err << "sph: warning: catalyst: script " << escapeControl(catalyst->script()) << " failed at step "
      << scene.stepIndex() << ": " << escapeControl(failure) << "; Catalyst is off for the rest of the run\n";
  catalyst.reset();
}

}  // namespace

template <int D>
RunTotals driveRun(const ResolvedCase& c, Scene<D>& scene, RunOutput<D>& output, RunReport& report,
                   ThreadTuner& tuner, std::unique_ptr<Catalyst>& catalyst, const SnapshotInfo& info,
                   Real startTime, Real resumeTime, bool resuming, std::ostream& err) {
  const std::filesystem::path dir(c.output);
  RunRecord& record = report.record();
  const std::size_t n = record.particles;
  const bool adaptive = c.cfl > 0;
  // Steps of a fixed-dt run: ceil((end - start) / dt), counted from the start.
  const long steps = adaptive ? 0 : static_cast<long>(std::ceil((c.endTime - startTime) / c.dt - 1e-9));
  auto finished = [&] {
    return adaptive ? scene.time() >= c.endTime * (1 - 1e-12) : scene.stepIndex() >= steps;
  };
  // Output: every output_every steps, or at every multiple of output_interval
  // after the start (adaptive steps land on them). The k-th output time is
  // the double nearest the decimal start + k interval (15 digits), so that
  // it reads 0.3, not 0.30000000000000004.
  const bool byInterval = c.outputInterval > 0;
  auto outputIndex = [&](Real t) { return std::floor((t - startTime) / c.outputInterval * (1 + 1e-12) + 1e-9); };
  auto outputTime = [&](Real k) {
    char text[32];
    std::snprintf(text, sizeof text, "%.15g", startTime + k * c.outputInterval);
    return std::strtod(text, nullptr);
  };
  Real nextOutput = byInterval ? outputTime(outputIndex(scene.time()) + 1) : std::numeric_limits<Real>::infinity();

  RegimeWatch<D> regime(c, scene);
  const bool terminal = isatty(STDERR_FILENO);
  const bool showLiveLine = c.progress && terminal;
  const double progressEvery = terminal ? 0.25 : 10.0;
  installStopHandlers();
  RunTotals totals;
  totals.wall0 = Clock::now();
  totals.firstStep = scene.stepIndex();
  totals.status = kSuccess;
  auto lastProgress = totals.wall0;
  auto saveRecord = [&] { report.save(scene.time(), scene.stepIndex(), scene.wallGuardActions(), tuner); };
  // A stop that keeps the outputs so far: the message to err and the record.
  auto stop = [&](const std::string& message) {
    record.status = "blew_up";
    record.message = message;
    totals.status = kBlewUp;
  };
  try {
    // run.json first: a folder holding any file of this run holds its record,
    // so that a run killed at any moment can be resumed or overwritten.
    if (scene.communicator().rank == 0) writeFileAtomically((dir / "run.case").string(), resolvedCaseText(c));
    saveRecord();
    if (!resuming) output.write(scene);
    saveRecord();
    offerToCatalyst(catalyst, scene, info, finished(), err);
    // A stop signal ends the run after the step it arrived in, with that
    // step's check and snapshot (`last` below), never between them.
    bool lastDone = false;
    while (!finished() && !lastDone) {
      const auto t0 = Clock::now();
      const mpi::CommunicationTime before = mpi::communicationTime();
      const auto failure = scene.step(nextOutput);
      const double dtWall = secondsSince(t0);
      totals.stepSeconds += dtWall;
      totals.communication += mpi::communicationTime() - before;
      tuner.record(dtWall);
      totals.dtStats.add(scene.lastTimeStep());
      output.addTimeStep(scene);
      if (!failure) output.sampleProbes(scene);
      if (failure) {
        if (showLiveLine) err << "\n";
        const std::string message = failureMessage(*failure, scene.stepIndex(), scene.time());
        err << "sph: error: " << message << "\nsph: the outputs up to step " << output.lastStep()
            << " (t = " << output.lastTime() << " s) are intact in " << output.seriesPath() << "\n";
        output.flushTimeSteps();  // the dt history up to the failure is what explains it
        stop(message);
        break;
      }
      // An adaptive dt that no longer lets the run end stops it (below).
      // The last step of the run: the end reached or a stop asked for, read
      // once, so the snapshot, the check and Catalyst agree on it (and every
      // MPI rank: a signal to one rank stops them all after this step).
      const bool last = finished() || mpi::allMax(scene.communicator(), stopSignal()) != 0;
      lastDone = last;
      const bool collapsed =
          adaptive && !finished() && (c.endTime - scene.time()) / scene.lastTimeStep().dt > kMaxSteps;
      const bool outputDue = (byInterval ? scene.time() >= nextOutput * (1 - 1e-12) - 1e-12 * c.outputInterval
                                         : scene.stepIndex() % c.outputEvery == 0) ||
                             last;
      const bool catalystDue =
          catalyst && (scene.stepIndex() % c.catalystEvery == 0 || last);
      // Still physics? Every 10 steps, and before anything is written or
      // shown: a snapshot, a Catalyst hand-over, the last step, a stop
      // signal, a collapsed dt (regime_check.hpp). So however few its steps,
      // no run writes or shows a snapshot of nonsense.
      if (scene.stepIndex() % 10 == 0 || outputDue || catalystDue || collapsed) {
        const std::string message = regime.judge(scene, c, showLiveLine, err);
        if (!message.empty()) {
          err << "sph: error: " << message << "\nsph: the outputs up to step " << output.lastStep()
              << " (t = " << output.lastTime() << " s) are intact in " << output.seriesPath()
              << " (regime_check = \"warn\" lets such a run go on)\n";
          output.flushTimeSteps();
          stop(message);
          break;
        }
      }
      // An adaptive dt that no longer lets the run end stops it, named.
      if (collapsed) {
        if (showLiveLine) err << "\n";
        const std::string message = "the adaptive time step collapsed at step " +
                                    std::to_string(scene.stepIndex()) + ", t = " + shortestDecimal(scene.time()) +
                                    " s: dt = " + shortestDecimal(scene.lastTimeStep().dt) + " s, set by the " +
                                    scene.lastTimeStep().criterion +
                                    " criterion, would need more than 1e12 steps to reach end_time";
        err << "sph: error: " << message << "\n";
        output.write(scene);
        stop(message);
        break;
      }
      if (outputDue) {
        output.write(scene);
        saveRecord();
        if (byInterval) nextOutput = outputTime(outputIndex(scene.time()) + 1);
      }
      if (catalystDue)
        offerToCatalyst(catalyst, scene, info, last, err);
      if (c.progress && secondsSince(lastProgress) > progressEvery) {
        lastProgress = Clock::now();
        printProgress(scene, c.endTime, n, totals, resumeTime, showLiveLine, err);
      }
    }
  } catch (const std::runtime_error& e) {
    // On several MPI ranks a file one rank could not write stops every rank:
    // the others wait in a collective call, so the cause is printed here and
    // the job aborted (mpirun ends every rank, the exit status non-zero).
    const mpi::Communicator& comm = scene.communicator();
    if (comm.size > 1) {
      std::fprintf(stderr, "sph: error: MPI rank %d: %s\n", comm.rank, e.what());
      std::fflush(stderr);
      MPI_Abort(comm.comm, kWriteFailed);
    }
    if (showLiveLine) err << "\n";
    err << "sph: error: " << e.what() << "\n";
    record.status = "write_failed";
    record.message = e.what();
    try {
      saveRecord();
    } catch (const std::runtime_error&) {
    }
    totals.status = kWriteFailed;
    return totals;
  }
  if (showLiveLine) err << "\r" << std::string(100, ' ') << "\r" << std::flush;
  totals.signal = mpi::allMax(scene.communicator(), stopSignal());
  if (totals.signal != 0 && totals.status == kSuccess) {
    totals.status = 128 + totals.signal;
    record.status = "interrupted";
    record.message = std::string("stopped by ") + (totals.signal == SIGINT ? "SIGINT" : "SIGTERM") + " at step " +
                     std::to_string(scene.stepIndex()) + ", t = " + shortestDecimal(scene.time()) + " s";
  }
  return totals;
}

template RunTotals driveRun<2>(const ResolvedCase&, Scene<2>&, RunOutput<2>&, RunReport&, ThreadTuner&,
                               std::unique_ptr<Catalyst>&, const SnapshotInfo&, Real, Real, bool, std::ostream&);
template RunTotals driveRun<3>(const ResolvedCase&, Scene<3>&, RunOutput<3>&, RunReport&, ThreadTuner&,
                               std::unique_ptr<Catalyst>&, const SnapshotInfo&, Real, Real, bool, std::ostream&);

}  // namespace sph
