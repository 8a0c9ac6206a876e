// The report of a run: run.json kept up to date, and the summary at the end
// (run_report.hpp).
#include "sph/run_report.hpp"

#include "sph/case_keys.hpp"
#include "sph/io/number_format.hpp"
#include "sph/io/run_output.hpp"
#include "sph/model_registry.hpp"
#include "sph/run_case.hpp"
#include "sph/scene.hpp"
#include "sph/version.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <ostream>
#include <utility>
#include <vector>

namespace sph {
namespace {

// What the run record says about the case: every key's value and the keys
// set. A resume changes only the keys it may (case_keys.hpp) and keeps the
// command line that started the run (its own goes to resumed_at).
void describeCase(RunRecord& r, const ResolvedCase& c, bool resuming) {
  for (const KeySpec& k : caseKeys())
    if (!isRunOnlyKey(k) && (!resuming || isResumeKey(k.name))) r.caseValues[k.name] = keyValueText(c, k);
  r.given.assign(c.given.begin(), c.given.end());
  if (!resuming) r.commandLine = c.commandLine;
  r.caseFile = c.caseFile;
  r.dimension = c.dimension;
  r.model = c.model;
  r.version = SPH_VERSION;
  r.gitCommit = gitCommit();
  r.threadMode = c.threads;
}

// "2", or with auto the count it ended with and the share of the stepping
// time of each count it timed: "2 (auto: 2 threads 96%, 1 4%)".
std::string threadsText(const ThreadTuner& tuner, bool autoThreads, double stepSeconds) {
  std::string threads = std::to_string(tuner.threads());
  if (autoThreads && stepSeconds > 0) {
    std::vector<std::pair<double, int>> shares;
    for (const auto& [t, seconds] : tuner.secondsWith()) shares.emplace_back(seconds, t);
    std::sort(shares.rbegin(), shares.rend());
    threads += " (auto:";
    for (std::size_t k = 0; k < shares.size(); ++k) {
      char part[64];
      std::snprintf(part, sizeof part, "%s %d%s %.0f%%", k ? "," : "", shares[k].second,
                    k ? "" : shares[k].second == 1 ? " thread" : " threads", 100 * shares[k].first / stepSeconds);
      threads += part;
    }
    threads += ")";
  } else if (autoThreads) {
    threads += " (auto)";
  }
  return threads;
}

// The dt part of the summary's steps line.
std::string timeStepText(const TimeStepStats& s, bool adaptive) {
  char dtLine[200];
  if (s.steps() == 0) std::snprintf(dtLine, sizeof dtLine, "(no step taken)");
  else if (!adaptive) std::snprintf(dtLine, sizeof dtLine, "(dt = %g s, fixed)", s.dtMax);
  else
    std::snprintf(dtLine, sizeof dtLine, "(dt %.3g to %.3g s; set by %s in %.0f%% of the steps)", s.dtMin, s.dtMax,
                  s.mostOften().c_str(),
                  100.0 * static_cast<double>(s.criteria.at(s.mostOften())) / static_cast<double>(s.steps()));
  return dtLine;
}

}  // namespace

void TimeStepStats::add(const TimeStepChoice& c) {
  dtMin = std::min(dtMin, c.dt);
  dtMax = std::max(dtMax, c.dt);
  ++criteria[c.criterion];
}

std::string TimeStepStats::mostOften() const {
  std::string best;
  long n = -1;
  for (const auto& [name, count] : criteria)
    if (count > n) best = name, n = count;
  return best;
}

long TimeStepStats::steps() const {
  long n = 0;
  for (const auto& [name, count] : criteria) n += count;
  return n;
}

RunReport::RunReport(const std::filesystem::path& dir, const ResolvedCase& c, const RunRecord& previous,
                     bool resuming, long resumeStep, Real resumeTime, Real startTime, std::size_t n,
                     std::size_t fluid)
    : dir_(dir), record_(resuming ? previous : RunRecord{}), previous_(previous), resuming_(resuming) {
  describeCase(record_, c, resuming);
  record_.name = c.name;
  record_.status = "running";
  record_.message.clear();
  if (resuming) {
    std::string command;
    for (const std::string& a : c.commandLine) command += (command.empty() ? "" : " ") + a;
    record_.resumedAt.push_back("step " + std::to_string(resumeStep) + ", t = " + shortestDecimal(resumeTime) +
                                " s, at " + isoNow() + ", by: " + command);
  } else {
    record_.started = isoNow();
    record_.startTime = startTime;
  }
  record_.particles = n;
  record_.fluidParticles = fluid;
  record_.wallParticles = n - fluid;
}

void RunReport::save(Real time, long step, long wallGuardActions, const ThreadTuner& tuner) {
  RunRecord& record = record_;
  const RunRecord& previous = previous_;
  record.simulatedTime = time;
  record.step = step;
  record.wallGuardActions = previous.wallGuardActions + wallGuardActions;
  // Threads over the whole run: a resume adds to what the run used before.
  record.threadsUsed = previous.threadsUsed;
  record.threadSeconds = previous.threadSeconds;
  for (int t : tuner.history())
    if (std::find(record.threadsUsed.begin(), record.threadsUsed.end(), t) == record.threadsUsed.end())
      record.threadsUsed.push_back(t);
  for (const auto& [t, seconds] : tuner.secondsWith()) record.threadSeconds[t] += seconds;
  // CPU time and peak memory of this process (a resume adds its own).
  // On several MPI ranks: every rank's CPU time and peak memory, summed
  // (collective: every rank saves at the same points; rank 0 writes).
  rusage usage{};
  double used[2] = {0, 0};
  if (::getrusage(RUSAGE_SELF, &usage) == 0) {
    auto seconds = [](const timeval& tv) { return static_cast<double>(tv.tv_sec) + 1e-6 * static_cast<double>(tv.tv_usec); };
    used[0] = seconds(usage.ru_utime) + seconds(usage.ru_stime);
    used[1] = 1024.0 * static_cast<double>(usage.ru_maxrss);
  }
  const mpi::Communicator& comm = mpi::world();
  used[0] = mpi::allSum(comm, used[0]);
  used[1] = mpi::allSum(comm, used[1]);
  record.ranks = comm.size;
  record.cpuSeconds = previous.cpuSeconds + used[0];
  record.peakMemoryBytes = std::max(previous.peakMemoryBytes, used[1]);
  record.addFile("run.json");
  record.addFile("run.case");
  if (comm.rank == 0) writeRunRecord(dir_, record);
}

template <int D>
void RunReport::finish(const Scene<D>& scene, const ResolvedCase& c, const RunTotals& totals,
                       const ThreadTuner& tuner, bool autoThreads, Real resumeTime, const RunOutput<D>& output,
                       std::ostream& out, std::ostream& err) {
  RunRecord& record = record_;
  const TimeStepStats& dtStats = totals.dtStats;
  const std::size_t n = record.particles;
  const double stepSeconds = totals.stepSeconds;
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - totals.wall0).count();
  const long done = scene.stepIndex() - totals.firstStep;
  record.ended = isoNow();
  record.wallSeconds += wall;
  record.steppingSeconds += stepSeconds;
  record.particleStepsPerSecond =
      stepSeconds > 0 ? static_cast<double>(n) * static_cast<double>(done) / stepSeconds : 0;
  record.neighboursPerParticle = scene.meanNeighbours();
  record.balances = scene.balances();
  record.workImbalance = scene.workImbalance();
  const mpi::Communicator& comm = scene.communicator();
  if (comm.size > 1) {
    // Means over the ranks: per step of this process, halo per owned.
    const mpi::CommunicationTime& spent = totals.communication;
    double sums[8] = {spent.halo,
                      spent.reductions,
                      spent.resort,
                      static_cast<double>(spent.reductionCalls),
                      static_cast<double>(scene.haloCount()),
                      static_cast<double>(scene.particles().size()),
                      static_cast<double>(spent.haloRefreshes),
                      spent.haloBytesSent};
    mpi::allSum(comm, sums, 8);
    const double perRankStep = done > 0 ? 1.0 / (static_cast<double>(comm.size) * static_cast<double>(done)) : 0;
    record.haloSecondsPerStep = sums[0] * perRankStep;
    record.reductionSecondsPerStep = sums[1] * perRankStep;
    record.resortSecondsPerStep = sums[2] * perRankStep;
    record.reductionsPerStep = sums[3] * perRankStep;
    record.haloFraction = sums[5] > 0 ? sums[4] / sums[5] : 0;
    record.haloRefreshesPerStep = sums[6] * perRankStep;
    record.haloBytesPerStep = sums[7] * perRankStep;
    // The rank that communicated least is the one the others waited for:
    // its time is about what the messages cost without waiting.
    record.leastCommunicationSecondsPerStep =
        mpi::allMin(comm, spent.total()) * (done > 0 ? 1.0 / static_cast<double>(done) : 0.0);
  }
  record.bytesPerParticle = static_cast<double>(scene.bytesAllocated()) / static_cast<double>(n);
  for (const auto& [name, count] : dtStats.criteria) record.dtCriteria[name] += count;
  if (dtStats.steps() > 0) {
    record.dtMin = resuming_ && previous_.dtMin > 0 ? std::min(previous_.dtMin, dtStats.dtMin) : dtStats.dtMin;
    record.dtMax = std::max(record.dtMax, dtStats.dtMax);
  }
  long most = -1;
  for (const auto& [name, count] : record.dtCriteria)
    if (count > most) record.dtLimitedBy = name, most = count;
  save(scene.time(), scene.stepIndex(), scene.wallGuardActions(), tuner);

  const bool adaptive = c.cfl > 0;
  const int status = totals.status;
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "sph: %s  (model %s, %dD)%s\n"
                "  particles        %zu%s\n"
                "  steps            %ld %s\n"
                "  simulated time   %s to %s s\n"
                "  wall time        %.3f s  (stepping %.3f s)\n"
                "  throughput       %.3g particle-steps/s\n"
                "  threads          %s\n"
                "  neighbours       %.1f per particle (mean at the end)\n"
                "  output           %s  (%ld snapshots)\n",
                c.name.c_str(), c.model.c_str(), D,
                status == kSuccess ? "" : ("  " + record.message.substr(0, 200)).c_str(), n,
                record.wallParticles ? (" (" + std::to_string(record.wallParticles) + " wall)").c_str() : "", done,
                timeStepText(dtStats, adaptive).c_str(), shortestDecimal(resumeTime).c_str(),
                shortestDecimal(scene.time()).c_str(), wall, stepSeconds, record.particleStepsPerSecond,
                threadsText(tuner, autoThreads, stepSeconds).c_str(), scene.meanNeighbours(),
                output.seriesPath().c_str(), output.count());
  out << buf;
  if (record.ranks > 1) {
    std::snprintf(buf, sizeof buf,
                  "  ranks            %d (the busiest's work %.3f x the mean at the end; the particles "
                  "shared out %ld time(s), rebalance_tolerance %s)\n",
                  record.ranks, record.workImbalance, record.balances, shortestDecimal(c.rebalanceTolerance).c_str());
    out << buf;
    const double perStep =
        record.haloSecondsPerStep + record.reductionSecondsPerStep + record.resortSecondsPerStep;
    const double stepMean = done > 0 ? stepSeconds / static_cast<double>(done) : 0;
    std::snprintf(buf, sizeof buf,
                  "  communication    %.3g ms a step, %.1f%% of the stepping (halo refresh %.3g, reductions %.3g, "
                  "re-sort %.3g ms; mean of the ranks, waiting for the others included; the least of the ranks "
                  "%.3g ms), %.1f reductions and %.1f halo refreshes of %.3g kB a step; %.3f halo particles per owned\n",
                  1e3 * perStep, stepMean > 0 ? 100 * perStep / stepMean : 0.0, 1e3 * record.haloSecondsPerStep,
                  1e3 * record.reductionSecondsPerStep, 1e3 * record.resortSecondsPerStep,
                  1e3 * record.leastCommunicationSecondsPerStep, record.reductionsPerStep, record.haloRefreshesPerStep,
                  1e-3 * record.haloBytesPerStep / std::max(record.haloRefreshesPerStep, 1e-300),
                  record.haloFraction);
    out << buf;
  }
  // The kernel corrections: what they did in this process (a resumed
  // run counts from its resume).
  const CorrectionCounts& cc = scene.model().correctionCounts();
  if (methodRow(gradientCorrectionMethods(), "gradient_correction", c.gradientCorrection).make(c))
    out << "  cspm             " << cc.cspmFallbacks << " of " << cc.cspmParticles
        << " particle-evaluations fell back to the uncorrected gradient ("
        << shortestDecimal(cc.cspmParticles ? 100.0 * static_cast<double>(cc.cspmFallbacks) / static_cast<double>(cc.cspmParticles) : 0.0)
        << "%)\n";
  if (wallGuardOn(c)) {
    // This process's actions and steps (run.json keeps the total over resumes).
    const long actions = scene.wallGuardActions();
    out << "  wall guard       ";
    if (actions == 0) {
      out << "0 times needed (the wall particles held every fluid particle)\n";
    } else {
      char rate[32];
      std::snprintf(rate, sizeof rate, "%.3g", done > 0 ? static_cast<double>(actions) / static_cast<double>(done) : 0.0);
      out << actions << " times it put a fluid particle back inside the walls (" << rate << " per step, of "
          << record.fluidParticles << " fluid particles)\n";
    }
  }
  const DensityReinit reinit = methodRow(densityReinitMethods(), "density_reinit", c.densityReinit).make(c);
  if (reinit != DensityReinit::kNone) {
    out << "  density reinit   " << c.densityReinit << " every " << c.densityReinitEvery << " steps: " << cc.reinitSteps
        << " times, " << cc.reinitParticles << " particle re-initialisations";
    if (reinit == DensityReinit::kMls) out << ", " << cc.mlsFallbacks << " left to Shepard (singular moment matrix)";
    out << "\n";
  }
  if (totals.signal != 0 && record.status == "interrupted")
    err << "sph: stopped at step " << scene.stepIndex() << ", t = " << shortestDecimal(scene.time()) << " s ("
        << (totals.signal == SIGINT ? "SIGINT" : "SIGTERM") << "); continue with: sph run --resume " << c.output
        << "\n";
}

template void RunReport::finish<2>(const Scene<2>&, const ResolvedCase&, const RunTotals&, const ThreadTuner&, bool,
                                   Real, const RunOutput<2>&, std::ostream&, std::ostream&);
template void RunReport::finish<3>(const Scene<3>&, const ResolvedCase&, const RunTotals&, const ThreadTuner&, bool,
                                   Real, const RunOutput<3>&, std::ostream&, std::ostream&);

}  // namespace sph
