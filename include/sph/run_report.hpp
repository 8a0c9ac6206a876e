// The report of a run: its record (run.json: the case, how it ran, what it
// wrote, how it ended), kept up to date while it runs, and the summary
// printed at its end (particles, steps, dt, times, throughput, threads,
// neighbours, output, and what the kernel corrections, the wall guard and
// the density re-initialisations did).
#pragma once

#include "sph/case_config.hpp"
#include "sph/io/run_folder.hpp"
#include "sph/mpi/communication_time.hpp"
#include "sph/thread_tuner.hpp"
#include "sph/time_step.hpp"

#include <chrono>
#include <filesystem>
#include <iosfwd>
#include <limits>
#include <map>
#include <string>

namespace sph {

template <int D>
class Scene;
template <int D>
class RunOutput;

// dt actually used: range and how often each criterion set it.
struct TimeStepStats {
  Real dtMin = std::numeric_limits<Real>::infinity(), dtMax = 0;
  std::map<std::string, long> criteria;
  void add(const TimeStepChoice& c);
  std::string mostOften() const;
  long steps() const;
};

// What a run's time loop measured (run_driver.hpp).
struct RunTotals {
  int status = 0;              // an ExitCode (run_case.hpp) or 128 + signal
  int signal = 0;              // the stop signal received, 0 if none
  long firstStep = 0;          // the step this process started at
  double stepSeconds = 0;      // wall time inside the steps
  std::chrono::steady_clock::time_point wall0;  // when the loop started
  mpi::CommunicationTime communication;  // this rank's, inside the steps (several ranks)
  TimeStepStats dtStats;
};

class RunReport {
 public:
  // The record at the start of a run into `dir`: a new one, or, resuming,
  // the run's `previous` one with the keys a resume may change and a line in
  // resumed_at. n particles, `fluid` of them fluid.
  RunReport(const std::filesystem::path& dir, const ResolvedCase& c, const RunRecord& previous, bool resuming,
            long resumeStep, Real resumeTime, Real startTime, std::size_t n, std::size_t fluid);

  RunRecord& record() { return record_; }

  // run.json now (the run at `time`, step `step`), with the threads, CPU
  // time and peak memory so far (a resume adds to what the run used
  // before); throws std::runtime_error.
  void save(Real time, long step, long wallGuardActions, const ThreadTuner& tuner);

  // At the end: the record's figures saved, and the summary to out (and the
  // resume hint of a stopped run to err); throws std::runtime_error.
  template <int D>
  void finish(const Scene<D>& scene, const ResolvedCase& c, const RunTotals& totals, const ThreadTuner& tuner,
              bool autoThreads, Real resumeTime, const RunOutput<D>& output, std::ostream& out, std::ostream& err);

 private:
  std::filesystem::path dir_;
  RunRecord record_, previous_;
  bool resuming_;
};

}  // namespace sph
