#include "sph/run_case.hpp"

#include "sph/case_file.hpp"
#include "sph/io/atomic_file.hpp"
#include "sph/io/pvd_series.hpp"
#include "sph/io/vtp_io.hpp"
#include "sph/particle_sources.hpp"
#include "sph/model_registry.hpp"
#include "sph/scene.hpp"
#include "sph/toy_star.hpp"

#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <new>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <ostream>
#include <sstream>

namespace sph {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string formatDuration(double s) {
  char buf[32];
  if (s < 120) std::snprintf(buf, sizeof buf, "%.0f s", s);
  else std::snprintf(buf, sizeof buf, "%.0f min", s / 60);
  return buf;
}

// Snapshots, the .pvd series and energy.csv of one run.
template <int D>
class RunOutput {
 public:
  RunOutput(const std::filesystem::path& dir, const std::string& name, SnapshotInfo info)
      : dir_(dir), name_(name), info_(info), series_((dir / (name + ".pvd")).string()) {
    energy_ = "time,kinetic,potential,total\n";
  }

  void write(const Scene<D>& scene) {
    char file[64];
    std::snprintf(file, sizeof file, "_%05ld.vtp", count_);
    const std::string vtp = name_ + file;
    info_.time = scene.time();
    info_.step = scene.stepIndex();
    writeVtp<D>((dir_ / vtp).string(), scene.particles(), info_);
    series_.add(scene.time(), scene.stepIndex(), vtp);
    const Energy e = scene.energy();
    char line[160];
    std::snprintf(line, sizeof line, "%.10g,%.10g,%.10g,%.10g\n", scene.time(), e.kinetic,
                  e.potential, e.total());
    energy_ += line;
    writeFileAtomically((dir_ / "energy.csv").string(), energy_);
    ++count_;
    lastStep_ = scene.stepIndex();
    lastTime_ = scene.time();
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
  std::string energy_;
  long count_ = 0;
  long lastStep_ = -1;
  Real lastTime_ = 0;
};

// timestep.csv of an adaptive run: step, time, dt and the criterion that set
// it, for every step; lines are buffered and appended at each snapshot.
class TimeStepLog {
 public:
  TimeStepLog(std::string path, bool enabled) : path_(std::move(path)), enabled_(enabled) {
    if (enabled_) buffer_ = "step,time,dt,criterion\n";
  }

  template <class Scene>
  void add(const Scene& scene) {
    if (!enabled_) return;
    char line[128];
    std::snprintf(line, sizeof line, "%ld,%.10g,%.6g,%s\n", scene.stepIndex(), scene.time(),
                  scene.lastTimeStep().dt, scene.lastTimeStep().criterion);
    buffer_ += line;
  }

  void flush() {
    if (!enabled_ || buffer_.empty()) return;
    std::ofstream f(path_, started_ ? std::ios::app : std::ios::trunc);
    started_ = true;
    f << buffer_;
    if (!f) throw std::runtime_error("cannot write " + path_);
    buffer_.clear();
  }

 private:
  std::string path_;
  bool enabled_;
  bool started_ = false;
  std::string buffer_;
};

// After a toy-star run: the radial density profile next to the analytic
// equilibrium of mass star_mass, as star_profile.csv, and the relative L2
// error inside 0.9 R printed. With several stars (a collision) the profile
// is that of all particles about their centre of mass: the merged star.
template <int D>
void writeStarProfiles(const Scene<D>& scene, const CaseConfig& c, const std::filesystem::path& dir,
                       std::ostream& out) {
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
  std::snprintf(line, sizeof line,
                "  toy star         relative L2 density error inside 0.9 R: %.4f (%zu particles "
                "inside; lambda = %.6g)\n",
                prof.l2Error, prof.inside, lambda);
  out << line;
}

std::string failureMessage(const StateFailure& f, long step, Real time) {
  std::ostringstream s;
  s << "the run blew up at step " << step << ", t = " << time << " s: particle id " << f.id
    << ": " << f.detail;
  return s.str();
}

}  // namespace

template <int D>
int runCase(const CaseConfig& given, std::ostream& out, std::ostream& err) {
  InitialState<D> init;
  CaseConfig c;
  try {
    validateCase(given);
    c = withDefaults(given);
    init = buildInitialState<D>(c);
  } catch (const CaseError& e) {
    err << "sph: error: " << escapeControl(e.what()) << "\n";  // values are echoed: no raw control bytes
    return kBadInput;
  } catch (const std::bad_alloc&) {
    err << "sph: error: not enough memory for the particles of this case (reduce spacing, "
           "star_particles or the block/disc size)\n";
    return kBadInput;
  }
  if (c.threads > 0) omp_set_num_threads(c.threads);
  const std::size_t n = init.particles.size();
  const Vec<D> lo = toVec<D>(c.domainMin), hi = toVec<D>(c.domainMax);

  std::size_t nearWall = 0;
  if (c.walls)
    for (const auto& x : init.particles.x)
      nearWall += ((x.array() - lo.array()).minCoeff() < c.h || (hi.array() - x.array()).minCoeff() < c.h);

  const Real startTime = init.startTime, endTime = startTime + c.endTime;
  const bool massesGiven = init.massesGiven;
  Scene<D> scene = makeScene<D>(c, std::move(init));
  if (auto failure = scene.initialise(!massesGiven)) {
    err << "sph: error: the initial state is not valid: particle id " << failure->id << ": "
        << failure->detail << "\n";
    return kBadInput;
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
  if (!c.particleFile.empty() && (!c.blockMin.empty() || !c.discCenter.empty() || !c.points.empty()))
    err << "sph: note: particles come from particle_file " << c.particleFile
        << "; the case's block, disc and points generators are not used\n";
  if (nearWall > 0)
    err << "sph: note: " << nearWall << " particle(s) start closer than h = " << c.h
        << " to a wall; the walls move them to distance h on the first step\n";

  SnapshotInfo info{0, 0, c.h, c.spacing, {}, {}};
  if (c.starMass > 0) {
    // Random star particles have no lattice spacing: give the mean one, so
    // that renders size the particles sensibly.
    const Real ball = D == 2 ? M_PI * c.starRadius * c.starRadius
                             : 4 * M_PI / 3 * std::pow(c.starRadius, 3);
    info.particleSpacing = std::pow(ball * static_cast<Real>(c.starParticles.size()) / static_cast<Real>(n), 1.0 / D);
  }
  if (c.walls) info.domainMin = c.domainMin, info.domainMax = c.domainMax;
  RunOutput<D> output(dir, c.name, info);
  TimeStepLog dtLog((dir / "timestep.csv").string(), c.cfl > 0);
  const long steps = c.cfl > 0 ? 0 : stepsFor(c);  // adaptive: until end_time
  const bool showProgress = c.progress && isatty(STDERR_FILENO);
  const auto wall0 = Clock::now();
  double stepSeconds = 0;
  auto lastProgress = wall0;
  int status = kSuccess;
  try {
    output.write(scene);
    auto finished = [&](long s) {
      return steps > 0 ? s >= steps : scene.time() >= endTime * (1 - 1e-12);
    };
    for (long s = 1; !finished(s - 1); ++s) {
      const auto t0 = Clock::now();
      const auto failure = scene.step();
      stepSeconds += secondsSince(t0);
      dtLog.add(scene);
      if (failure) {
        if (showProgress) err << "\n";
        err << "sph: error: " << failureMessage(*failure, scene.stepIndex(), scene.time())
            << "\nsph: the outputs up to step " << output.lastStep() << " (t = "
            << output.lastTime() << " s) are intact in " << output.seriesPath() << "\n";
        dtLog.flush();  // the dt history up to the failure is what explains it
        status = kBlewUp;
        break;
      }
      if (s % c.outputEvery == 0 || finished(s)) {
        output.write(scene);
        dtLog.flush();
      }
      if (showProgress && secondsSince(lastProgress) > 0.25) {
        lastProgress = Clock::now();
        const double elapsed = secondsSince(wall0);
        char line[160];
        std::snprintf(line, sizeof line, "\r  t = %.4g / %.4g s   step %ld / %ld   ETA %s   ",
                      scene.time(), endTime, s, steps,
                      formatDuration(elapsed / (scene.time() - startTime) *
                                     (endTime - scene.time())).c_str());
        err << line << std::flush;
      }
    }
  } catch (const std::runtime_error& e) {
    if (showProgress) err << "\n";
    err << "sph: error: " << e.what() << "\n";
    return kWriteFailed;
  }
  if (showProgress) err << "\r" << std::string(70, ' ') << "\r" << std::flush;
  if (status == kSuccess && c.starMass > 0) {
    try {
      writeStarProfiles(scene, c, dir, out);
    } catch (const std::runtime_error& e) {
      err << "sph: error: " << e.what() << "\n";
      return kWriteFailed;
    }
  }

  const double wall = secondsSince(wall0);
  const long done = scene.stepIndex();
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "sph: %s  (model %s, %dD)\n"
                "  particles        %zu\n"
                "  steps            %ld  (dt = %g s)\n"
                "  simulated time   %g s\n"
                "  wall time        %.3f s  (stepping %.3f s)\n"
                "  throughput       %.3g particle-steps/s\n"
                "  threads          %d\n"
                "  neighbours       %.1f per particle (mean at the end)\n"
                "  output           %s  (%ld snapshots)\n",
                c.name.c_str(), c.model.c_str(), D, n, done, c.dt, scene.time() - startTime,
                wall, stepSeconds,
                stepSeconds > 0 ? static_cast<double>(n) * static_cast<double>(done) / stepSeconds : 0.0,
                omp_get_max_threads(), scene.meanNeighbours(), output.seriesPath().c_str(),
                output.count());
  out << buf;
  return status;
}

template int runCase<2>(const CaseConfig&, std::ostream&, std::ostream&);
template int runCase<3>(const CaseConfig&, std::ostream&, std::ostream&);

}  // namespace sph
