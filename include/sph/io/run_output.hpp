// The files a run writes as it goes: snapshots (.vtp), the .pvd series,
// energy.csv, timestep.csv (adaptive dt) and the probe files (logs that grow
// by appended rows; the rest replaced atomically), recorded in run.json; and, after a toy-star run, the star's
// density profile. A resumed run continues the files of the run it resumes.
#pragma once

#include "sph/mpi/session.hpp"

#include "sph/case_config.hpp"
#include "sph/io/probe_files.hpp"
#include "sph/io/pvd_series.hpp"
#include "sph/io/run_folder.hpp"
#include "sph/io/vtp_io.hpp"

#include <filesystem>
#include <iosfwd>
#include <set>
#include <string>

namespace sph {

template <int D>
class Scene;

// What every snapshot states besides time and step: h, the particle
// spacing (for random toy-star particles the mean one, so that renders size
// them sensibly) and, with walls, the domain box. n: the particle count.
template <int D>
SnapshotInfo snapshotInfo(const CaseConfig& c, std::size_t n);

template <int D>
class RunOutput {
 public:
  RunOutput(const std::filesystem::path& dir, const std::string& name, SnapshotInfo info, RunRecord& record,
            bool adaptive, ProbeFiles<D> probes);

  // Continue a run's series after its snapshot at step `step`, time `time`.
  void resumeAfter(long step, Real time);
  // A snapshot, with energy.csv, the probe files and timestep.csv brought up to date.
  void write(const Scene<D>& scene);
  // Probes after a step (when one is due).
  void sampleProbes(const Scene<D>& scene);
  // The step's dt, for timestep.csv (adaptive dt only).
  void addTimeStep(const Scene<D>& scene);
  // timestep.csv brought up to date.
  void flushTimeSteps();

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
  // The rows of each growing log not yet on disk.
  std::string energy_, dtLog_;
  // The logs (energy.csv, timestep.csv, probe files) this object has written.
  std::set<std::string> onDisk_;
  // Several MPI ranks: a .pvtp and a piece per rank per snapshot; only rank
  // 0 writes the series, the logs and the record.
  mpi::Communicator comm_;

  // The first time: the log written atomically from `text` (a new run's
  // header, or a resumed run's rows up to its snapshot); afterwards `text`
  // (the rows added since) appended. `text` is emptied, so a run holds only
  // the rows since its last snapshot, not the whole log.
  void writeLog(const std::string& file, std::string& text);
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
                       std::ostream& out, RunRecord& record);

}  // namespace sph
