// The output folder of a run and run.json, the record of what produced it.
//
// A folder holds at most one run. A new run refuses a folder that holds
// another run's files unless it is told to --overwrite them (which removes
// the files that run listed or named as its snapshots, and nothing else) or
// to --resume that run; a
// folder with sph output but no run.json, or --overwrite of a folder that
// holds no run, is refused too, so nothing is ever removed by surprise.
//
// run.json (rewritten atomically at the start, at every snapshot and at the
// end): the fully resolved case (every key with the value used), the keys
// the case set, the command line, sph's version and git commit, threads,
// start and end wall-clock times, the summary figures, the files the run
// wrote, and how it ended: "running" (so far, or killed), "finished",
// "interrupted", "blew_up" or "write_failed", with the message.
// run.case beside it is the same resolved case as a case file; a resume
// reads it.
#pragma once

#include "sph/case_config.hpp"

#include <filesystem>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sph {

struct RunRecord {
  // what
  std::string name;                    // run name (<name>.pvd)
  std::map<std::string, std::string> caseValues;  // key -> case-file text of its value
  std::vector<std::string> given;      // keys the case file or command line set
  std::vector<std::string> commandLine;
  std::string caseFile;
  std::string version, gitCommit;
  int dimension = 2;
  int ranks = 1;  // MPI ranks of the run (the last process's)
  long balances = 0;         // several ranks: times the particles were shared out (the last process's)
  double workImbalance = 0;  // several ranks: the busiest rank's work over the mean at the end
  // several ranks, the last process's steps, mean over the ranks: wall-clock
  // seconds a step spent communicating (waiting included; mpi/
  // communication_time.hpp), by kind, and halo particles per owned one at the end
  double haloSecondsPerStep = 0, reductionSecondsPerStep = 0, resortSecondsPerStep = 0;
  double reductionsPerStep = 0, haloFraction = 0;
  double leastCommunicationSecondsPerStep = 0;  // the rank that communicated least (the one waited for)
  double haloRefreshesPerStep = 0, haloBytesPerStep = 0;  // bytes sent by a rank a step
  std::string model;
  // how it ran
  std::string threadMode;              // "auto" or the count asked for
  std::vector<int> threadsUsed;        // every thread count it ran with, in the order first used
  std::map<int, double> threadSeconds; // stepping time with each count
  std::string started, ended;          // ISO 8601 UTC
  std::string status = "running";      // running | finished | interrupted | blew_up | write_failed
  std::string message;
  std::vector<std::string> resumedAt;  // one line per resume: "step N, t = T"
  // figures
  double startTime = 0;                // simulated time the run started at [s]
  double simulatedTime = 0;            // where it is now [s]
  long step = 0;
  std::size_t particles = 0, fluidParticles = 0, wallParticles = 0;
  double wallSeconds = 0, steppingSeconds = 0, particleStepsPerSecond = 0;
  double neighboursPerParticle = 0, bytesPerParticle = 0;
  double cpuSeconds = 0;               // user + system CPU time of the process(es) that ran it (getrusage)
  double peakMemoryBytes = 0;          // peak resident set size of the process that ran it (getrusage ru_maxrss)
  double dtMin = 0, dtMax = 0;
  std::string dtLimitedBy;             // the criterion that set dt most often
  std::map<std::string, long> dtCriteria;  // criterion -> number of steps it set
  long snapshots = 0;
  long wallGuardActions = 0;           // fluid particles the wall guard put back (boundaries/wall_guard.hpp)
  std::string lastSnapshot;
  std::vector<std::string> files;      // the files the run wrote (relative to its folder)

  void addFile(const std::string& f);
};

// Writes run.json into `dir` atomically; throws std::runtime_error.
void writeRunRecord(const std::filesystem::path& dir, const RunRecord& r);
// Reads run.json of `dir`; throws std::runtime_error naming the file.
RunRecord readRunRecord(const std::filesystem::path& dir);

// What a folder holds, for the output-folder rules above.
enum class FolderContents { kNothing, kRun, kOtherSphOutput, kOtherFiles };
FolderContents inspectFolder(const std::filesystem::path& dir);

// Checks a run may write into `dir` (before anything is written): throws
// CaseError naming the folder and what to do. `resuming`: the run continues
// the one in dir.
void checkOutputFolder(const std::filesystem::path& dir, bool overwrite, bool resuming);

// --overwrite: removes the files the run recorded in dir's run.json lists,
// snapshots named like its own (<name>_NNNNN.vtp: one written just before
// it was killed), run.json, run.case and stale temporaries. Returns how many.
std::size_t removeRunFiles(const std::filesystem::path& dir);

// Once everything that can be checked has been: creates the output folder
// `output` (removing again the folders it made if the rest of the path cannot
// be created, so a failure writes nothing), removes an earlier run's files
// for --overwrite (one note to err) and stale temporaries. False after one
// "sph: error:" line to err.
bool makeRunFolder(const std::string& output, bool overwrite, std::ostream& err);

// Now as ISO 8601 UTC ("2026-12-01T16:38:00Z").
std::string isoNow();

}  // namespace sph
