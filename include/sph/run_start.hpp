// The start of a run, before anything is written: the case checked and its
// defaults filled in, its particles built (or, for --resume, read back from
// the run's last snapshot, with its run.json), the end time and the output
// folder's rules checked. Bad input: one "sph: error:" line, nothing back.
#pragma once

#include "sph/case_config.hpp"
#include "sph/io/run_folder.hpp"
#include "sph/particle_sources.hpp"

#include <iosfwd>
#include <optional>
#include <string>

namespace sph {

template <int D>
struct RunStart {
  ResolvedCase c;            // validated, defaults filled in
  InitialState<D> init;      // the particles to start from
  bool resuming = false;
  RunRecord previous;        // the resumed run's record (resuming only)
  std::string resumeSnapshot;  // the snapshot it continues from (resuming only)
};

// The checked start of `given`, or nothing after printing why to err (the
// run then exits with kBadInput); unused keys are warned about.
template <int D>
std::optional<RunStart<D>> startRun(const CaseConfig& given, std::ostream& err);

}  // namespace sph
