// sph study: a matrix of runs, reference cases x methods x resolutions, each
// run a child `sph run` with key overrides, its errors measured against the
// case's reference by validation/study.py, which writes study.csv, a chart
// per case (error against wall time, the Pareto front, the tolerance) and
// report.md (the cheapest setting that meets each tolerance).
//
// A study file is read by the case-file reader (sph/case_file.hpp), so its
// syntax is that of a case file; its keys (see studies/README.md):
//
//   case_NAME       = ["CASE_FILE", "OBSERVABLE"]   a reference case; CASE_FILE is relative
//                                                   to the study file; OBSERVABLE: dam_break
//                                                   or hydrostatic (study.py measures them);
//                                                   a third element names the error metric
//   method_NAME     = ["key = value", ...]          a method: overrides on every case
//   resolution_NAME = ["key = value", ...]          a resolution: overrides too
//   overrides       = ["key = value", ...]          for every run (e.g. a shorter end_time)
//   overrides_NAME  = ["key = value", ...]          for the runs of case NAME
//   tolerance       = 0.05  or  [0.05, 0.1]         the errors the report asks for
//   cost            = "wall"  or  "cpu"             what the charts and the report count (default wall)
//
// Each run is case x method x resolution; overrides apply in the order
// common, case, method, resolution (a later one wins), in the folder OUTPUT/runs/CASE__METHOD__RESOLUTION.
// Runs get --threads 1 unless an override sets threads, so that --jobs N
// runs N of them at once without competing.
//
// Resuming: a run whose run.json says finished or blew_up (a blow-up is a
// result: the method fails there), with the values the study asks for, is
// not run again; one that was interrupted or killed is resumed (sph run
// --resume); one whose record differs from what the study asks for, or that
// failed to write, is run anew (--overwrite).
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sph {

// "key = value" of an override, the value as case-file text ("0.01", "[0, 1]").
using KeyOverride = std::pair<std::string, std::string>;

struct StudyCase {
  std::string name;
  std::filesystem::path caseFile;  // as given, resolved against the study file's folder
  std::string observable;
  std::string metric;                  // "" -> the observable's first (study.py checks the name)
  std::vector<KeyOverride> overrides;  // overrides_NAME: for this case's runs
};

struct StudyVariant {  // a method or a resolution
  std::string name;
  std::vector<KeyOverride> overrides;
};

struct Study {
  std::string name;  // the study file's name without extension
  std::filesystem::path file;
  std::vector<StudyCase> cases;
  std::vector<StudyVariant> methods, resolutions;
  std::vector<KeyOverride> common;
  std::vector<double> tolerances;
  std::string cost = "wall";  // "wall" or "cpu" seconds: the cost axis and what "cheapest" means
};

// The observables study.py can measure.
const std::vector<std::string>& studyObservables();

// Reads and checks a study file: throws CaseError with one line naming the
// file, line and key (unknown key, an override of a key sph does not have or
// of a run-only key, a missing case file, an unknown observable, no case).
Study readStudyFile(const std::filesystem::path& file);
// The same from text; `dir` resolves the case files.
Study parseStudy(const std::string& text, const std::string& name, const std::filesystem::path& dir);

struct StudyRun {
  std::string name;  // CASE__METHOD__RESOLUTION
  std::size_t caseIndex = 0, methodIndex = 0, resolutionIndex = 0;
  std::vector<KeyOverride> overrides;  // common, case, method, resolution; a key once, the last value
  std::filesystem::path folder;
};

// Every run of the study, cases outermost, resolutions innermost.
std::vector<StudyRun> studyRuns(const Study& s, const std::filesystem::path& output);

// The arguments of `sph run` for a run (without the program name).
std::vector<std::string> runArguments(const Study& s, const StudyRun& r);

// What to do with a run folder: kSkip (finished or blew up with these
// values), kResume (interrupted or killed), kFresh (no run yet), kOverwrite
// (another run, different values, or a failed write).
enum class RunAction { kSkip, kResume, kFresh, kOverwrite };
RunAction runAction(const StudyRun& r);

struct StudyOptions {
  std::filesystem::path output;        // "" -> runs/study_<name>
  int jobs = 1;
  std::optional<double> tolerance;     // replaces the study file's
  std::string self = "/proc/self/exe"; // the sph executable the runs use
  std::string python;                  // "" -> $SPH_PYTHON or the configured python3
  std::string script;                  // "" -> $SPH_STUDY_SCRIPT or validation/study.py of the source tree
};

// Runs the study: the runs (up to jobs at once, each logged to
// OUTPUT/logs/RUN.log), OUTPUT/study.json, then study.py. Returns the exit
// status: 0, 2 (a run refused its input), 4 (a run or the analysis could
// not write), or 130/143 when stopped by a signal.
int runStudy(const Study& s, const StudyOptions& o, std::ostream& out, std::ostream& err);

}  // namespace sph
