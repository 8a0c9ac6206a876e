// One whole run: check everything, prepare the output folder, step, write
// snapshots, the .pvd series, energy.csv, timestep.csv and run.json, and
// print a summary. See run_case.hpp for the exit codes.
#include "sph/run_case.hpp"

#include "sph/case_file.hpp"
#include "sph/case_keys.hpp"
#include "sph/io/catalyst.hpp"
#include "sph/io/atomic_file.hpp"
#include "sph/io/number_format.hpp"
#include "sph/io/probe_files.hpp"
#include "sph/io/pvd_series.hpp"
#include "sph/io/run_folder.hpp"
#include "sph/io/vtp_io.hpp"
#include "sph/model_registry.hpp"
#include "sph/particle_sources.hpp"
#include "sph/regime_check.hpp"
#include "sph/run_signals.hpp"
#include "sph/scene.hpp"
#include "sph/thread_tuner.hpp"
#include "sph/toy_star.hpp"
#include "sph/version.hpp"

#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <new>
#include <optional>
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

// Lines of a CSV file whose first column (a number) passes keep(), header
// kept; "" if the file cannot be read.
template <class Keep>
std::string csvLinesWhere(const std::filesystem::path& path, Keep keep) {
  std::ifstream in(path);
  std::string out, line;
  bool header = true;
  while (std::getline(in, line)) {
    if (header) {
      out += line + "\n";
      header = false;
      continue;
    }
    try {
      if (keep(std::stod(line.substr(0, line.find(','))))) out += line + "\n";
    } catch (const std::exception&) {
    }
  }
  return out;
}

// Snapshots, the .pvd series, energy.csv and timestep.csv of one run; files
// are replaced atomically, and every file written is recorded in run.json.
template <int D>
class RunOutput {
 public:
  RunOutput(const std::filesystem::path& dir, const std::string& name, SnapshotInfo info, RunRecord& record,
            bool adaptive, ProbeFiles<D> probes)
      : dir_(dir), name_(name), info_(info), series_((dir / (name + ".pvd")).string()), record_(record),
        adaptive_(adaptive), probes_(std::move(probes)) {
    energy_ = "time,kinetic,potential,total\n";
    if (adaptive_) dtLog_ = "step,time,dt,criterion\n";
  }

  // Continue a run's series after its snapshot at step `step`, time `time`.
  void resumeAfter(long step, Real time) {
    series_ = PvdSeries::load(series_.path());
    count_ = static_cast<long>(series_.entries().size());
    lastStep_ = step;
    lastTime_ = time;
    energy_ = csvLinesWhere(dir_ / "energy.csv", [&](double t) { return t <= time; });
    if (energy_.empty()) energy_ = "time,kinetic,potential,total\n";
    if (adaptive_) {
      dtLog_ = csvLinesWhere(dir_ / "timestep.csv", [&](double s) { return s <= static_cast<double>(step); });
      if (dtLog_.empty()) dtLog_ = "step,time,dt,criterion\n";
    }
    probes_.resume(time, [&](const char* file) {
      return csvLinesWhere(dir_ / file, [&](double t) { return t <= time * (1 + 1e-12); });
    });
  }

  void write(const Scene<D>& scene) {
    char file[64];
    std::snprintf(file, sizeof file, "_%05ld.vtp", count_);
    const std::string vtp = name_ + file;
    info_.time = scene.time();
    info_.step = scene.stepIndex();
    writeVtp<D>((dir_ / vtp).string(), scene.particles(), info_);
    record_.addFile(vtp);
    series_.add(scene.time(), scene.stepIndex(), vtp);
    record_.addFile(name_ + ".pvd");
    const Energy e = scene.energy();
    char line[160];
    std::snprintf(line, sizeof line, "%s,%.10g,%.10g,%.10g\n", shortestDecimal(scene.time()).c_str(), e.kinetic,
                  e.potential, e.total());
    energy_ += line;
    writeFileAtomically((dir_ / "energy.csv").string(), energy_);
    record_.addFile("energy.csv");
    if (count_ == 0 && lastStep_ < 0) sampleProbes(scene);
    for (const auto& f : probes_.files()) {
      writeFileAtomically((dir_ / f.name).string(), *f.text);
      record_.addFile(f.name);
    }
    flushTimeSteps();
    ++count_;
    lastStep_ = scene.stepIndex();
    lastTime_ = scene.time();
    record_.snapshots = count_;
    record_.lastSnapshot = vtp;
  }

  // Probes after a step (when one is due).
  void sampleProbes(const Scene<D>& scene) {
    if (probes_.any()) probes_.sample(scene.particles(), scene.time(), shortestDecimal(scene.time()));
  }

  void addTimeStep(const Scene<D>& scene) {
    if (!adaptive_) return;
    char line[128];
    std::snprintf(line, sizeof line, "%ld,%s,%.6g,%s\n", scene.stepIndex(), shortestDecimal(scene.time()).c_str(),
                  scene.lastTimeStep().dt, scene.lastTimeStep().criterion);
    dtLog_ += line;
  }

  // timestep.csv, replaced atomically like the other files.
  void flushTimeSteps() {
    if (!adaptive_) return;
    writeFileAtomically((dir_ / "timestep.csv").string(), dtLog_);
    record_.addFile("timestep.csv");
  }

  Real lastTime() const { return lastTime_; }
  long count() const { return count_; }
  long lastStep() const { return lastStep_; }
  const std::string& seriesPath() const { return series_.path(); }

 private:
  std::filesystem::path dir_;
  std::string name_;
  SnapshotInfo info_;
  PvdSeries series_;
  RunRecord& record_;
  bool adaptive_;
  ProbeFiles<D> probes_;
  std::string energy_, dtLog_;
  long count_ = 0;
  long lastStep_ = -1;
  Real lastTime_ = 0;
};

// After a toy-star run: the radial density profile next to the analytic
// equilibrium of mass star_mass, as star_profile.csv, and the relative L2
// error inside 0.9 R printed. With several stars (a collision) the profile
// is that of all particles about their centre of mass: the merged star.
template <int D>
void writeStarProfiles(const Scene<D>& scene, const CaseConfig& c, const std::filesystem::path& dir,
                       std::ostream& out, RunRecord& record) {
  const Real lambda = starLambda(c);
  const auto& P = scene.particles();
  Vec<D> centre = Vec<D>::Zero();
  Real mass = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    centre += P.m[i] * P.x[i];
    mass += P.m[i];
  }
  centre /= mass;
  const StarProfile prof = toyStarProfile(P, centre, lambda, c.starRadius, c.k, c.polytropicIndex);
  std::string csv = "r,rho_sph,rho_analytic,particles\n";
  char line[160];
  for (std::size_t b = 0; b < prof.r.size(); ++b) {
    std::snprintf(line, sizeof line, "%.6g,%.8g,%.8g,%zu\n", prof.r[b], prof.rhoSph[b], prof.rhoExact[b],
                  prof.count[b]);
    csv += line;
  }
  writeFileAtomically((dir / "star_profile.csv").string(), csv);
  record.addFile("star_profile.csv");
  std::snprintf(line, sizeof line,
                "  toy star         relative L2 density error inside 0.9 R: %.4f (%zu particles "
                "inside; lambda = %.6g)\n",
                prof.l2Error, prof.inside, lambda);
  out << line;
}

std::string failureMessage(const StateFailure& f, long step, Real time) {
  std::ostringstream s;
  s << "the run blew up at step " << step << ", t = " << time << " s: particle id " << f.id << ": " << f.detail;
  return s.str();
}

// dt actually used: range and how often each criterion set it.
struct TimeStepStats {
  Real dtMin = std::numeric_limits<Real>::infinity(), dtMax = 0;
  std::map<std::string, long> criteria;
  void add(const TimeStepChoice& c) {
    dtMin = std::min(dtMin, c.dt);
    dtMax = std::max(dtMax, c.dt);
    ++criteria[c.criterion];
  }
  std::string mostOften() const {
    std::string best;
    long n = -1;
    for (const auto& [name, count] : criteria)
      if (count > n) best = name, n = count;
    return best;
  }
  long steps() const {
    long n = 0;
    for (const auto& [name, count] : criteria) n += count;
    return n;
  }
};

// What the run record says about the case: every key's value and the keys
// set. A resume changes only the keys it may (case_keys.hpp) and keeps the
// command line that started the run (its own goes to resumed_at).
void describeCase(RunRecord& r, const CaseConfig& c, bool resuming) {
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

}  // namespace

template <int D>
int runCase(const CaseConfig& given, std::ostream& out, std::ostream& err) {
  InitialState<D> init;
  CaseConfig c;
  const bool resuming = !given.resume.empty();
  RunRecord previous;
  std::string resumeSnapshot;
  try {
    validateCase(given);
    c = withDefaults(given);
    if (resuming) {
      previous = readRunRecord(c.output);
      if (previous.dimension != D || previous.name != c.name)
        throw CaseError("resume: run.json of " + c.output + " does not match its run.case");
      const PvdSeries series = PvdSeries::load((std::filesystem::path(c.output) / (c.name + ".pvd")).string());
      if (series.entries().empty()) throw CaseError("resume: the series of " + c.output + " has no snapshot");
      resumeSnapshot = (std::filesystem::path(c.output) / series.entries().back().file).string();
      init = resumeState<D>(resumeSnapshot);
    } else {
      init = buildInitialState<D>(c);
    }
    const Real t0 = init.startTime;
    if (!(c.endTime > t0 * (1 + 1e-12)))
      throw CaseError("end_time = " + shortestDecimal(c.endTime) + " s is not after the start, t = " +
                      shortestDecimal(t0) + " s " +
                      (resuming ? "(the run reached it: give --end_time T, later, to run further)"
                                : "(of particle_file; end_time is absolute)"));
    if ((c.endTime - t0) / c.dt > kMaxSteps)
      throw CaseError("(end_time - start) / dt is more than " + shortestDecimal(kMaxSteps) + " steps");
    checkOutputFolder(c.output, c.overwrite, resuming);
  } catch (const CaseError& e) {
    err << "sph: error: " << escapeControl(e.what()) << "\n";  // values are echoed: no raw control bytes
    return kBadInput;
  } catch (const std::bad_alloc&) {
    err << "sph: error: not enough memory for the particles of this case (reduce spacing, "
           "star_particles or the block/disc size)\n";
    return kBadInput;
  } catch (const std::runtime_error& e) {
    err << "sph: error: " << escapeControl(e.what()) << "\n";
    return kBadInput;
  }
  for (const std::string& note : unusedKeyNotes(c)) err << "sph: warning: " << escapeControl(note) << "\n";

  const std::size_t n = init.particles.size();
  Vec<D> lo = toVec<D>(c.domainMin), hi = toVec<D>(c.domainMax);
  for (int d = 0; d < D; ++d)  // periodic faces have no wall
    if ((periodicAxes(c) >> d) & 1u) lo[d] = -std::numeric_limits<Real>::infinity(), hi[d] = -lo[d];
  std::size_t nearWall = 0;
  if (c.walls && c.boundary == "reflecting" && !resuming)
    for (const auto& x : init.particles.x)
      nearWall += ((x.array() - lo.array()).minCoeff() < c.h || (hi.array() - x.array()).minCoeff() < c.h);

  // Threads: an explicit count (or OMP_NUM_THREADS) is obeyed; auto is tuned.
  const int asked = requestedThreads(c);
  const bool auto_threads = asked == 0 && std::getenv("OMP_NUM_THREADS") == nullptr;
  if (asked > 0) omp_set_num_threads(asked);
  ThreadTuner tuner = auto_threads ? ThreadTuner(n) : ThreadTuner::fixed(omp_get_max_threads());

  // The run's clock: a new run starts at the time of its particles (0, or a
  // particle_file's); a resumed one at the original run's start.
  const Real startTime = resuming ? previous.startTime : init.startTime;
  const Real resumeTime = init.startTime;
  const long resumeStep = init.startStep;
  const bool massesGiven = init.massesGiven;
  Scene<D> scene = makeScene<D>(c, std::move(init), startTime);
  try {
    const auto failure = resuming ? scene.resume(resumeStep, resumeTime) : scene.initialise(!massesGiven);
    if (failure) {
      err << "sph: error: the initial state is not valid: particle id " << failure->id << ": " << failure->detail
          << "\n";
      return kBadInput;
    }
  } catch (const std::runtime_error& e) {
    err << "sph: error: resume: " << resumeSnapshot << ": " << e.what() << "\n";
    return kBadInput;
  }

  // The Catalyst script, when given: loaded (ParaView's start-up) after the
  // case's own checks and before anything is written, so that a missing or
  // broken script is refused with no folder made.
  std::unique_ptr<Catalyst> catalyst;
  if (!c.catalyst.empty()) {
    try {
      catalyst = std::make_unique<Catalyst>(c.catalyst, c.output, c.name);
    } catch (const CaseError& e) {
      err << "sph: error: " << escapeControl(e.what()) << "\n";
      return kBadInput;
    }
  }

  // Everything that can be checked has been: now, and only now, write.
  const std::filesystem::path dir(c.output);
  std::error_code ec;
  // The first folder on the path that does not exist yet: removed again if
  // the rest of the path cannot be created, so a failure writes nothing.
  std::filesystem::path firstNew;
  for (std::filesystem::path p = std::filesystem::absolute(dir, ec); !p.empty() && !std::filesystem::exists(p, ec);
       p = p.parent_path()) {
    firstNew = p;
    if (p == p.parent_path()) break;
  }
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    err << "sph: error: output folder " << escapeControl(c.output) << " cannot be created"
        << (ec ? ": " + ec.message() : std::string()) << "\n";
    std::error_code ignored;
    if (!firstNew.empty()) std::filesystem::remove_all(firstNew, ignored);
    return kBadInput;
  }
  if (c.overwrite && inspectFolder(dir) == FolderContents::kRun) {
    const std::size_t removed = removeRunFiles(dir);
    err << "sph: note: --overwrite removed " << removed << " file(s) of the earlier run in " << c.output << "\n";
  }
  removeStaleTemporaries(dir);
  if (!c.particleFile.empty() && !resuming && (!c.blockMin.empty() || !c.discCenter.empty() || !c.points.empty()))
    err << "sph: note: particles come from particle_file " << c.particleFile
        << "; the case's block, disc and points generators are not used\n";
  if (nearWall > 0)
    err << "sph: note: " << nearWall << " particle(s) start closer than h = " << c.h
        << " to a wall; the walls move them to distance h on the first step\n";

  RunRecord record = resuming ? previous : RunRecord{};
  describeCase(record, c, resuming);
  record.name = c.name;
  record.status = "running";
  record.message.clear();
  if (resuming) {
    std::string command;
    for (const std::string& a : c.commandLine) command += (command.empty() ? "" : " ") + a;
    record.resumedAt.push_back("step " + std::to_string(resumeStep) + ", t = " + shortestDecimal(resumeTime) +
                               " s, at " + isoNow() + ", by: " + command);
  } else {
    record.started = isoNow();
    record.startTime = startTime;
  }
  record.particles = n;
  record.fluidParticles = scene.particles().fluidCount();
  record.wallParticles = n - scene.particles().fluidCount();

  SnapshotInfo info{0, 0, c.h, c.spacing, {}, {}};
  if (c.starMass > 0) {
    // Random star particles have no lattice spacing: give the mean one, so
    // that renders size the particles sensibly.
    const Real ball = D == 2 ? M_PI * c.starRadius * c.starRadius : 4 * M_PI / 3 * std::pow(c.starRadius, 3);
    info.particleSpacing =
        std::pow(ball * static_cast<Real>(c.starParticles.size()) / static_cast<Real>(n), 1.0 / D);
  }
  if (c.walls) info.domainMin = c.domainMin, info.domainMax = c.domainMax;
  const bool adaptive = c.cfl > 0;
  // Probes interpolate with the case's kernel; the seed model's kernels are
  // its own, so there a Wendland C2 with the seed's support h stands in.
  CaseConfig probeKernel = c;
  if (probeKernel.kernel.empty()) probeKernel.kernel = "wendland_c2", probeKernel.h = c.h / 2;
  RunOutput<D> output(dir, c.name, info, record, adaptive, ProbeFiles<D>(c, makeKernel<D>(probeKernel)));
  // Hands the particles to Catalyst; a script that fails during the run is
  // reported once and left out for the rest of it (the run and its files
  // go on: they are what the run is for).
  auto offerToCatalyst = [&](bool last) {
    if (!catalyst) return;
    SnapshotInfo now = info;
    now.time = scene.time();
    now.step = scene.stepIndex();
    const std::string failure = catalyst->offer<D>(scene.particles(), now, last);
    if (failure.empty()) return;
    err << "sph: warning: catalyst: script " << escapeControl(catalyst->script()) << " failed at step "
        << scene.stepIndex() << ": " << escapeControl(failure) << "; Catalyst is off for the rest of the run\n";
    catalyst.reset();
  };
  if (resuming) output.resumeAfter(resumeStep, resumeTime);

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

  // The regime check's sound speed: the EOS's at rho0 (the seed's p =
  // k (rho - rho0): sqrt(k)); none for the polytropic toy stars.
  Real soundSpeed = 0;
  if (c.model == "seed_wcsph") soundSpeed = std::sqrt(c.k);
  else if (c.eos != "polytropic")
    soundSpeed = std::visit([&](const auto& e) { return e.soundSpeed(c.rho0); }, makeEos(c));
  // ... and, for the Tait EOS of the water cases, its rest density for the
  // density window (a linear EOS and the seed's set a stiffness k and are
  // compressible by design: the seed dam break reaches 1.2 rho0).
  const Real densityRef = c.model != "seed_wcsph" && c.eos == "tait" ? c.rho0 : 0;
  RegimeCheck regime(soundSpeed, c.spacing, scene.particles().fluidCount());
  const bool regimeOn = c.regimeCheck != "off";
  if (regimeOn) regime.start(measureRegime(scene.particles(), scene.neighbours(), soundSpeed, c.spacing, densityRef));

  const bool terminal = isatty(STDERR_FILENO);
  const bool showLiveLine = c.progress && terminal;
  const double progressEvery = terminal ? 0.25 : 10.0;
  installStopHandlers();
  const auto wall0 = Clock::now();
  double stepSeconds = 0;
  auto lastProgress = wall0;
  TimeStepStats dtStats;
  const long firstStep = scene.stepIndex();
  int status = kSuccess;
  bool regimeWarned = false;
  auto saveRecord = [&] {
    record.simulatedTime = scene.time();
    record.step = scene.stepIndex();
    record.wallGuardActions = previous.wallGuardActions + scene.wallGuardActions();
    // Threads over the whole run: a resume adds to what the run used before.
    record.threadsUsed = previous.threadsUsed;
    record.threadSeconds = previous.threadSeconds;
    for (int t : tuner.history())
      if (std::find(record.threadsUsed.begin(), record.threadsUsed.end(), t) == record.threadsUsed.end())
        record.threadsUsed.push_back(t);
    for (const auto& [t, seconds] : tuner.secondsWith()) record.threadSeconds[t] += seconds;
    // CPU time and peak memory of this process (a resume adds its own).
    rusage usage{};
    if (::getrusage(RUSAGE_SELF, &usage) == 0) {
      auto seconds = [](const timeval& tv) { return static_cast<double>(tv.tv_sec) + 1e-6 * static_cast<double>(tv.tv_usec); };
      record.cpuSeconds = previous.cpuSeconds + seconds(usage.ru_utime) + seconds(usage.ru_stime);
      record.peakMemoryBytes = std::max(previous.peakMemoryBytes, 1024.0 * static_cast<double>(usage.ru_maxrss));
    }
    record.addFile("run.json");
    record.addFile("run.case");
    writeRunRecord(dir, record);
  };
  try {
    // run.json first: a folder holding any file of this run holds its record,
    // so that a run killed at any moment can be resumed or overwritten.
    writeFileAtomically((dir / "run.case").string(), resolvedCaseText(c));
    saveRecord();
    if (!resuming) output.write(scene);
    saveRecord();
    offerToCatalyst(finished());
    while (!finished()) {
      if (stopSignal() != 0) break;
      const auto t0 = Clock::now();
      const auto failure = scene.step(nextOutput);
      const double dtWall = secondsSince(t0);
      stepSeconds += dtWall;
      tuner.record(dtWall);
      dtStats.add(scene.lastTimeStep());
      output.addTimeStep(scene);
      if (!failure) output.sampleProbes(scene);
      if (failure) {
        if (showLiveLine) err << "\n";
        const std::string message = failureMessage(*failure, scene.stepIndex(), scene.time());
        err << "sph: error: " << message << "\nsph: the outputs up to step " << output.lastStep()
            << " (t = " << output.lastTime() << " s) are intact in " << output.seriesPath() << "\n";
        output.flushTimeSteps();  // the dt history up to the failure is what explains it
        record.status = "blew_up";
        record.message = message;
        status = kBlewUp;
        break;
      }
      // An adaptive dt that no longer lets the run end stops it (below).
      const bool collapsed =
          adaptive && !finished() && (c.endTime - scene.time()) / scene.lastTimeStep().dt > kMaxSteps;
      const bool outputDue = (byInterval ? scene.time() >= nextOutput * (1 - 1e-12) - 1e-12 * c.outputInterval
                                         : scene.stepIndex() % c.outputEvery == 0) ||
                             finished() || stopSignal() != 0;
      // Still physics? Every 10 steps, and before anything is written: a
      // snapshot, the last step, a stop signal, a collapsed dt (regime_check.hpp).
      // So however few its steps, no run writes a snapshot of nonsense.
      if (regimeOn && (scene.stepIndex() % 10 == 0 || outputDue || collapsed)) {
        const auto verdict = regime.judge(measureRegime(scene.particles(), scene.neighbours(), soundSpeed, c.spacing, densityRef),
                                          scene.lastTimeStep().dt, c.h);
        if (!verdict.warning.empty()) {
          if (showLiveLine) err << "\n";
          err << "sph: warning: at step " << scene.stepIndex() << ", t = " << shortestDecimal(scene.time()) << " s: " << verdict.warning << "\n";
        }
        if (!verdict.stop.empty()) {
          if (showLiveLine) err << "\n";
          const std::string message = "the run left its regime at step " + std::to_string(scene.stepIndex()) +
                                      ", t = " + shortestDecimal(scene.time()) + " s: " + verdict.stop;
          if (c.regimeCheck == "stop") {
            err << "sph: error: " << message << "\nsph: the outputs up to step " << output.lastStep()
                << " (t = " << output.lastTime() << " s) are intact in " << output.seriesPath()
                << " (regime_check = \"warn\" lets such a run go on)\n";
            output.flushTimeSteps();
            record.status = "blew_up";
            record.message = message;
            status = kBlewUp;
            break;
          }
          if (!regimeWarned) err << "sph: warning: " << message << "\n";
          regimeWarned = true;
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
        record.status = "blew_up";
        record.message = message;
        status = kBlewUp;
        break;
      }
      if (outputDue) {
        output.write(scene);
        saveRecord();
        if (byInterval) nextOutput = outputTime(outputIndex(scene.time()) + 1);
      }
      if (catalyst && (scene.stepIndex() % c.catalystEvery == 0 || finished() || stopSignal() != 0))
        offerToCatalyst(finished() || stopSignal() != 0);
      if (c.progress && secondsSince(lastProgress) > progressEvery) {
        lastProgress = Clock::now();
        const double elapsed = secondsSince(wall0);
        const double rate = stepSeconds > 0 ? static_cast<double>(n) * static_cast<double>(scene.stepIndex() - firstStep) / stepSeconds : 0;
        char line[200];
        std::snprintf(line, sizeof line, "t = %.4g / %.4g s   step %ld   %.3g M particle-steps/s   %d thread(s)   ETA %s",
                      scene.time(), c.endTime, scene.stepIndex(), rate / 1e6, omp_get_max_threads(),
                      formatDuration(elapsed / (scene.time() - resumeTime) * (c.endTime - scene.time())).c_str());
        if (showLiveLine) err << "\r  " << line << "   " << std::flush;
        else err << "sph: " << line << "\n" << std::flush;
      }
    }
  } catch (const std::runtime_error& e) {
    if (showLiveLine) err << "\n";
    err << "sph: error: " << e.what() << "\n";
    record.status = "write_failed";
    record.message = e.what();
    try {
      saveRecord();
    } catch (const std::runtime_error&) {
    }
    return kWriteFailed;
  }
  if (showLiveLine) err << "\r" << std::string(100, ' ') << "\r" << std::flush;
  const int signal = stopSignal();
  if (signal != 0 && status == kSuccess) {
    status = 128 + signal;
    record.status = "interrupted";
    record.message = std::string("stopped by ") + (signal == SIGINT ? "SIGINT" : "SIGTERM") + " at step " +
                     std::to_string(scene.stepIndex()) + ", t = " + shortestDecimal(scene.time()) + " s";
  }
  try {
    if (status == kSuccess) {
      record.status = "finished";
      if (c.starMass > 0) writeStarProfiles(scene, c, dir, out, record);
    }
    const double wall = secondsSince(wall0);
    const long done = scene.stepIndex() - firstStep;
    record.ended = isoNow();
    record.wallSeconds += wall;
    record.steppingSeconds += stepSeconds;
    record.particleStepsPerSecond =
        stepSeconds > 0 ? static_cast<double>(n) * static_cast<double>(done) / stepSeconds : 0;
    record.neighboursPerParticle = scene.meanNeighbours();
    record.bytesPerParticle = static_cast<double>(scene.bytesAllocated()) / static_cast<double>(n);
    for (const auto& [name, count] : dtStats.criteria) record.dtCriteria[name] += count;
    if (dtStats.steps() > 0) {
      record.dtMin = resuming && previous.dtMin > 0 ? std::min(previous.dtMin, dtStats.dtMin) : dtStats.dtMin;
      record.dtMax = std::max(record.dtMax, dtStats.dtMax);
    }
    long most = -1;
    for (const auto& [name, count] : record.dtCriteria)
      if (count > most) record.dtLimitedBy = name, most = count;
    saveRecord();

    char dtLine[200];
    if (dtStats.steps() == 0) std::snprintf(dtLine, sizeof dtLine, "(no step taken)");
    else if (!adaptive) std::snprintf(dtLine, sizeof dtLine, "(dt = %g s, fixed)", dtStats.dtMax);
    else
      std::snprintf(dtLine, sizeof dtLine, "(dt %.3g to %.3g s; set by %s in %.0f%% of the steps)", dtStats.dtMin,
                    dtStats.dtMax, dtStats.mostOften().c_str(),
                    100.0 * static_cast<double>(dtStats.criteria.at(dtStats.mostOften())) /
                        static_cast<double>(dtStats.steps()));
    // "2", or with auto the count it ended with and the share of the
    // stepping time of each count it timed: "2 (auto: 2 threads 96%, 1 4%)".
    std::string threads = std::to_string(tuner.threads());
    if (auto_threads && stepSeconds > 0) {
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
    } else if (auto_threads) {
      threads += " (auto)";
    }
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
                  dtLine, shortestDecimal(resumeTime).c_str(), shortestDecimal(scene.time()).c_str(), wall,
                  stepSeconds, record.particleStepsPerSecond, threads.c_str(), scene.meanNeighbours(),
                  output.seriesPath().c_str(), output.count());
    out << buf;
    // The kernel corrections: what they did in this process (a resumed
    // run counts from its resume).
    const CorrectionCounts& cc = scene.model().correctionCounts();
    if (c.gradientCorrection != "none")
      out << "  cspm             " << cc.cspmFallbacks << " of " << cc.cspmParticles
          << " particle-evaluations fell back to the uncorrected gradient ("
          << shortestDecimal(cc.cspmParticles ? 100.0 * static_cast<double>(cc.cspmFallbacks) / static_cast<double>(cc.cspmParticles) : 0.0)
          << "%)\n";
    if (c.walls && c.boundary != "reflecting" && c.wallGuard) {
      // This process's actions and steps (run.json keeps the total over resumes).
      const long taken = scene.stepIndex() - firstStep, actions = scene.wallGuardActions();
      out << "  wall guard       ";
      if (actions == 0) {
        out << "0 times needed (the wall particles held every fluid particle)\n";
      } else {
        char rate[32];
        std::snprintf(rate, sizeof rate, "%.3g", taken > 0 ? static_cast<double>(actions) / static_cast<double>(taken) : 0.0);
        out << actions << " times it put a fluid particle back inside the walls (" << rate << " per step, of "
            << scene.particles().fluidCount() << " fluid particles)\n";
      }
    }
    if (c.densityReinit != "none") {
      out << "  density reinit   " << c.densityReinit << " every " << c.densityReinitEvery << " steps: " << cc.reinitSteps
          << " times, " << cc.reinitParticles << " particle re-initialisations";
      if (c.densityReinit == "mls") out << ", " << cc.mlsFallbacks << " left to Shepard (singular moment matrix)";
      out << "\n";
    }
    if (signal != 0 && record.status == "interrupted")
      err << "sph: stopped at step " << scene.stepIndex() << ", t = " << shortestDecimal(scene.time())
          << " s (" << (signal == SIGINT ? "SIGINT" : "SIGTERM") << "); continue with: sph run --resume " << c.output
          << "\n";
  } catch (const std::runtime_error& e) {
    err << "sph: error: " << e.what() << "\n";
    return kWriteFailed;
  }
  return status;
}

template int runCase<2>(const CaseConfig&, std::ostream&, std::ostream&);
template int runCase<3>(const CaseConfig&, std::ostream&, std::ostream&);

}  // namespace sph
