// The time loop of a run: run.case and run.json first, the first snapshot,
// then step by step to end_time: dt history and probes, the regime check
// (every 10 steps and before anything is written), snapshots on schedule,
// Catalyst, progress, and the ways a run stops early (a blow-up, the
// regime left, a collapsed adaptive dt, SIGINT/SIGTERM).
#pragma once

#include "sph/case_config.hpp"
#include "sph/io/vtp_io.hpp"
#include "sph/run_report.hpp"

#include <iosfwd>
#include <memory>

namespace sph {

class Catalyst;
template <int D>
class Scene;
template <int D>
class RunOutput;

// Runs `scene` from its current state to c.endTime. startTime: where the
// run's clock started (output_interval counts from it); resumeTime: where
// this process took over (progress); resuming: the first snapshot exists.
// `catalyst` (may be empty) gets `info` with every offer and is switched off
// after a failing script. The status is kWriteFailed when a file could not
// be written (the record says so, if it can); the record is otherwise left
// for RunReport::finish.
template <int D>
RunTotals driveRun(const ResolvedCase& c, Scene<D>& scene, RunOutput<D>& output, RunReport& report,
                   ThreadTuner& tuner, std::unique_ptr<Catalyst>& catalyst, const SnapshotInfo& info,
                   Real startTime, Real resumeTime, bool resuming, std::ostream& err);

}  // namespace sph
