// The files a run writes as it goes: snapshots, the .pvd series, energy.csv,
// timestep.csv, the probe files and the toy star's profile (run_output.hpp).
#include "sph/io/run_output.hpp"

#include "sph/io/atomic_file.hpp"
#include "sph/io/number_format.hpp"
#include "sph/model_registry.hpp"
#include "sph/mpi/parallel_snapshot.hpp"
#include "sph/scene.hpp"
#include "sph/toy_star.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <ostream>

namespace sph {
namespace {

// Lines of a CSV file whose first column (a number) passes keep(), header
// kept; "" if the file cannot be read. A last line without its newline (a
// run killed while appending it) is dropped.
template <class Keep>
std::string csvLinesWhere(const std::filesystem::path& path, Keep keep) {
  std::ifstream in(path);
  std::string out, line;
  bool header = true;
  while (std::getline(in, line)) {
    if (in.eof()) break;  // no newline: an unfinished row
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

}  // namespace

template <int D>
SnapshotInfo snapshotInfo(const CaseConfig& c, std::size_t n) {
  SnapshotInfo info{0, 0, c.h, c.spacing, {}, {}};
  if (c.starMass > 0) {
    const Real ball = D == 2 ? M_PI * c.starRadius * c.starRadius : 4 * M_PI / 3 * std::pow(c.starRadius, 3);
    info.particleSpacing =
        std::pow(ball * static_cast<Real>(c.starParticles.size()) / static_cast<Real>(n), 1.0 / D);
  }
  if (c.walls) info.domainMin = c.domainMin, info.domainMax = c.domainMax;
  return info;
}

template <int D>
RunOutput<D>::RunOutput(const std::filesystem::path& dir, const std::string& name, SnapshotInfo info,
                        RunRecord& record, bool adaptive, ProbeFiles<D> probes)
    : dir_(dir), name_(name), info_(info), series_((dir / (name + ".pvd")).string()), record_(record),
      adaptive_(adaptive), probes_(std::move(probes)), comm_(mpi::world()) {
  energy_ = "time,kinetic,potential,total\n";
  if (adaptive_) dtLog_ = "step,time,dt,criterion\n";
}

template <int D>
void RunOutput<D>::resumeAfter(long step, Real time) {
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

template <int D>
void RunOutput<D>::write(const Scene<D>& scene) {
  char file[64];
  std::snprintf(file, sizeof file, comm_.size > 1 ? "_%05ld.pvtp" : "_%05ld.vtp", count_);
  const std::string vtp = name_ + file;
  info_.time = scene.time();
  info_.step = scene.stepIndex();
  if (comm_.size > 1) {
    mpi::writeParallelSnapshot<D>((dir_ / vtp).string(), scene.particles(), info_, comm_);
    for (int r = 0; r < comm_.size; ++r) record_.addFile(pvtpPieceName(vtp, r));
  } else {
    writeVtp<D>((dir_ / vtp).string(), scene.particles(), info_);
  }
  record_.addFile(vtp);
  // The logs first, the series last: a run killed in between leaves rows
  // past the series' last snapshot, which a resume drops (resumeAfter).
  const Energy e = scene.energy();
  char line[160];
  std::snprintf(line, sizeof line, "%s,%.10g,%.10g,%.10g\n", shortestDecimal(scene.time()).c_str(), e.kinetic,
                e.potential, e.total());
  energy_ += line;
  writeLog("energy.csv", energy_);
  if (count_ == 0 && lastStep_ < 0) sampleProbes(scene);
  for (const auto& f : probes_.files()) writeLog(f.name, *f.text);
  flushTimeSteps();
  series_.add(scene.time(), scene.stepIndex(), vtp, comm_.rank == 0);
  record_.addFile(name_ + ".pvd");
  ++count_;
  lastStep_ = scene.stepIndex();
  lastTime_ = scene.time();
  record_.snapshots = count_;
  record_.lastSnapshot = vtp;
}

template <int D>
void RunOutput<D>::sampleProbes(const Scene<D>& scene) {
  if (probes_.any()) probes_.sample(scene.particles(), scene.time(), shortestDecimal(scene.time()));
}

template <int D>
void RunOutput<D>::addTimeStep(const Scene<D>& scene) {
  if (!adaptive_) return;
  char line[128];
  std::snprintf(line, sizeof line, "%ld,%s,%.6g,%s\n", scene.stepIndex(), shortestDecimal(scene.time()).c_str(),
                scene.lastTimeStep().dt, scene.lastTimeStep().criterion);
  dtLog_ += line;
}

template <int D>
void RunOutput<D>::flushTimeSteps() {
  if (!adaptive_) return;
  writeLog("timestep.csv", dtLog_);
}

template <int D>
void RunOutput<D>::writeLog(const std::string& file, std::string& text) {
  record_.addFile(file);
  if (comm_.rank != 0) {  // rank 0 writes the logs
    text.clear();
    return;
  }
  const std::string path = (dir_ / file).string();
  if (!onDisk_.count(file)) {
    writeFileAtomically(path, text);
    onDisk_.insert(file);
    std::string().swap(text);  // a resumed run's rows up to its snapshot: release them
  } else if (!text.empty()) {
    appendToFile(path, text);
    text.clear();
  }
}

namespace {

// Every rank's particles (x, m, rho) in one Particles on every rank, in the
// order of their ids: the profile's sums are then the same on any number of
// ranks > 1. Once, at the end of a run.
template <int D>
Particles<D> gatherInIdOrder(const Particles<D>& P, const mpi::Communicator& comm) {
  struct Record {
    Vec<D> x;
    Real m, rho;
  };
  std::vector<mpi::ById<Record>> mine(P.size());
  for (std::size_t i = 0; i < P.size(); ++i) mine[i] = {P.id[i], {P.x[i], P.m[i], P.rho[i]}};
  const auto all = mpi::allGatherById(comm, mine);
  Particles<D> gathered;
  for (const auto& r : all) {
    gathered.x.push_back(r.value.x);
    gathered.m.push_back(r.value.m);
    gathered.id.push_back(r.id);
  }
  gathered.resize(all.size());
  for (std::size_t k = 0; k < all.size(); ++k) gathered.rho[k] = all[k].value.rho;
  return gathered;
}

}  // namespace

template <int D>
void writeStarProfiles(const Scene<D>& scene, const CaseConfig& c, const std::filesystem::path& dir,
                       std::ostream& out, RunRecord& record) {
  const Real lambda = starLambda(c);
  const mpi::Communicator& comm = scene.communicator();
  const Particles<D> gathered = comm.size > 1 ? gatherInIdOrder(scene.particles(), comm) : Particles<D>();
  const auto& P = comm.size > 1 ? gathered : scene.particles();
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
  if (comm.rank == 0) writeFileAtomically((dir / "star_profile.csv").string(), csv);
  record.addFile("star_profile.csv");
  std::snprintf(line, sizeof line,
                "  toy star         relative L2 density error inside 0.9 R: %.4f (%zu particles "
                "inside; lambda = %.6g)\n",
                prof.l2Error, prof.inside, lambda);
  out << line;
}

template SnapshotInfo snapshotInfo<2>(const CaseConfig&, std::size_t);
template SnapshotInfo snapshotInfo<3>(const CaseConfig&, std::size_t);
template class RunOutput<2>;
template class RunOutput<3>;
template void writeStarProfiles<2>(const Scene<2>&, const CaseConfig&, const std::filesystem::path&, std::ostream&,
                                   RunRecord&);
template void writeStarProfiles<3>(const Scene<3>&, const CaseConfig&, const std::filesystem::path&, std::ostream&,
                                   RunRecord&);

}  // namespace sph
