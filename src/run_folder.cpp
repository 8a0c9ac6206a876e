// run.json with nlohmann::json (Debian's nlohmann-json3-dev), and the rules
// for output folders, checked and then made. The only translation unit that
// includes the JSON library.
#include "sph/io/run_folder.hpp"

#include "sph/case_file.hpp"
#include "sph/io/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <ostream>
#include <vector>

namespace sph {
namespace {

using json = nlohmann::ordered_json;

constexpr const char* kRecordFile = "run.json";
constexpr const char* kCaseFile = "run.case";

// Files only sph writes: a folder holding one of these holds sph output.
bool looksLikeSphOutput(const std::filesystem::path& p) {
  const std::string name = p.filename().string(), ext = p.extension().string();
  return ext == ".pvd" || ext == ".vtp" || ext == ".pvtp" || name == "energy.csv" || name == "timestep.csv" ||
         name == kCaseFile;
}

}  // namespace

void RunRecord::addFile(const std::string& f) {
  if (std::find(files.begin(), files.end(), f) == files.end()) files.push_back(f);
}

void writeRunRecord(const std::filesystem::path& dir, const RunRecord& r) {
  json j;
  j["sph_version"] = r.version;
  j["git_commit"] = r.gitCommit;
  j["name"] = r.name;
  j["status"] = r.status;
  j["message"] = r.message;
  j["command_line"] = r.commandLine;
  j["case_file"] = r.caseFile;
  j["dimension"] = r.dimension;
  j["model"] = r.model;
  j["case"] = json::object();
  // The case-file text of a value is JSON too (numbers, "strings", [lists],
  // true/false); nothing given is null.
  for (const auto& [k, v] : r.caseValues) {
    if (v.empty()) j["case"][k] = nullptr;
    else j["case"][k] = json::parse(v, nullptr, false).is_discarded() ? json(v) : json::parse(v);
  }
  j["given_keys"] = r.given;
  json seconds = json::object();
  for (const auto& [count, s] : r.threadSeconds) seconds[std::to_string(count)] = s;
  j["ranks"] = r.ranks;
  if (r.ranks > 1) {
    j["balances"] = r.balances;
    j["work_imbalance"] = r.workImbalance;
    j["communication_per_step"] = {{"halo_seconds", r.haloSecondsPerStep},
                                   {"reduction_seconds", r.reductionSecondsPerStep},
                                   {"resort_seconds", r.resortSecondsPerStep},
                                   {"reductions", r.reductionsPerStep},
                                   {"least_of_the_ranks_seconds", r.leastCommunicationSecondsPerStep},
                                   {"halo_refreshes", r.haloRefreshesPerStep},
                                   {"halo_bytes_sent", r.haloBytesPerStep}};
    j["halo_fraction"] = r.haloFraction;
  }
  j["threads"] = {{"asked", r.threadMode}, {"used", r.threadsUsed}, {"stepping_seconds", seconds}};
  j["started"] = r.started;
  j["ended"] = r.ended;
  j["resumed_at"] = r.resumedAt;
  j["summary"] = {{"particles", r.particles},
                  {"fluid_particles", r.fluidParticles},
                  {"wall_particles", r.wallParticles},
                  {"wall_guard_actions", r.wallGuardActions},
                  {"start_time_s", r.startTime},
                  {"simulated_time_s", r.simulatedTime},
                  {"steps", r.step},
                  {"wall_seconds", r.wallSeconds},
                  {"stepping_seconds", r.steppingSeconds},
                  {"particle_steps_per_second", r.particleStepsPerSecond},
                  {"neighbours_per_particle", r.neighboursPerParticle},
                  {"bytes_per_particle", r.bytesPerParticle},
                  {"cpu_seconds", r.cpuSeconds},
                  {"peak_memory_bytes", r.peakMemoryBytes},
                  {"dt_min_s", r.dtMin},
                  {"dt_max_s", r.dtMax},
                  {"dt_limited_by", r.dtLimitedBy},
                  {"dt_criteria_steps", r.dtCriteria},
                  {"snapshots", r.snapshots},
                  {"last_snapshot", r.lastSnapshot}};
  j["files"] = r.files;
  writeFileAtomically((dir / kRecordFile).string(), j.dump(2) + "\n");
}

RunRecord readRunRecord(const std::filesystem::path& dir) {
  const std::string path = (dir / kRecordFile).string();
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  RunRecord r;
  try {
    const json j = json::parse(in);
    r.version = j.at("sph_version").get<std::string>();
    r.gitCommit = j.at("git_commit").get<std::string>();
    r.name = j.at("name").get<std::string>();
    r.status = j.at("status").get<std::string>();
    r.message = j.at("message").get<std::string>();
    r.commandLine = j.at("command_line").get<std::vector<std::string>>();
    r.caseFile = j.at("case_file").get<std::string>();
    r.dimension = j.at("dimension").get<int>();
    r.model = j.at("model").get<std::string>();
    for (const auto& [k, v] : j.at("case").items()) r.caseValues[k] = v.is_null() ? "" : v.dump();
    r.given = j.at("given_keys").get<std::vector<std::string>>();
    r.ranks = j.value("ranks", 1);  // (absent in runs written before MPI)
    r.balances = j.value("balances", 0L);
    r.workImbalance = j.value("work_imbalance", 0.0);
    if (j.contains("communication_per_step") && j["communication_per_step"].is_object()) {
      const auto& c = j["communication_per_step"];
      r.haloSecondsPerStep = c.value("halo_seconds", 0.0);
      r.reductionSecondsPerStep = c.value("reduction_seconds", 0.0);
      r.resortSecondsPerStep = c.value("resort_seconds", 0.0);
      r.reductionsPerStep = c.value("reductions", 0.0);
      r.leastCommunicationSecondsPerStep = c.value("least_of_the_ranks_seconds", 0.0);
      r.haloRefreshesPerStep = c.value("halo_refreshes", 0.0);
      r.haloBytesPerStep = c.value("halo_bytes_sent", 0.0);
    }
    r.haloFraction = j.value("halo_fraction", 0.0);
    r.threadMode = j.at("threads").at("asked").get<std::string>();
    r.threadsUsed = j.at("threads").at("used").get<std::vector<int>>();
    for (const auto& [count, s] : j.at("threads").at("stepping_seconds").items())
      r.threadSeconds[std::stoi(count)] = s.get<double>();
    r.started = j.at("started").get<std::string>();
    r.ended = j.at("ended").get<std::string>();
    r.resumedAt = j.at("resumed_at").get<std::vector<std::string>>();
    const json& s = j.at("summary");
    r.particles = s.at("particles").get<std::size_t>();
    r.fluidParticles = s.at("fluid_particles").get<std::size_t>();
    r.wallParticles = s.at("wall_particles").get<std::size_t>();
    r.wallGuardActions = s.value("wall_guard_actions", 0L);  // (absent in runs written before the guard)
    r.startTime = s.at("start_time_s").get<double>();
    r.simulatedTime = s.at("simulated_time_s").get<double>();
    r.step = s.at("steps").get<long>();
    r.wallSeconds = s.at("wall_seconds").get<double>();
    r.steppingSeconds = s.at("stepping_seconds").get<double>();
    r.particleStepsPerSecond = s.at("particle_steps_per_second").get<double>();
    r.neighboursPerParticle = s.at("neighbours_per_particle").get<double>();
    r.bytesPerParticle = s.at("bytes_per_particle").get<double>();
    r.cpuSeconds = s.value("cpu_seconds", 0.0);  // absent in records of older sph
    r.peakMemoryBytes = s.value("peak_memory_bytes", 0.0);
    r.dtMin = s.at("dt_min_s").get<double>();
    r.dtMax = s.at("dt_max_s").get<double>();
    r.dtLimitedBy = s.at("dt_limited_by").get<std::string>();
    r.dtCriteria = s.at("dt_criteria_steps").get<std::map<std::string, long>>();
    r.snapshots = s.at("snapshots").get<long>();
    r.lastSnapshot = s.at("last_snapshot").get<std::string>();
    r.files = j.at("files").get<std::vector<std::string>>();
  } catch (const json::exception& e) {
    throw std::runtime_error(path + " is not a run record sph can read: " + e.what());
  }
  return r;
}

FolderContents inspectFolder(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return FolderContents::kNothing;
  if (std::filesystem::exists(dir / kRecordFile, ec)) return FolderContents::kRun;
  bool any = false;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    if (looksLikeSphOutput(e.path())) return FolderContents::kOtherSphOutput;
    any = true;
  }
  return any ? FolderContents::kOtherFiles : FolderContents::kNothing;
}

void checkOutputFolder(const std::filesystem::path& dir, bool overwrite, bool resuming) {
  const std::string where = "output folder " + dir.string();
  if (overwrite && resuming) throw CaseError("overwrite and resume go against each other: give one");
  switch (inspectFolder(dir)) {
    case FolderContents::kNothing:
      if (resuming) throw CaseError("resume: " + where + " holds no run to resume (no run.json)");
      return;
    case FolderContents::kRun:
      if (overwrite || resuming) return;
      {
        std::string what = "another run";
        try {
          const RunRecord r = readRunRecord(dir);
          what = "the run '" + r.name + "' (" + r.status + ", started " + r.started + ")";
        } catch (const std::exception&) {
        }
        throw CaseError(where + " holds " + what + ": give --overwrite to replace it, --resume " + dir.string() +
                        " to continue it, or another --output");
      }
    case FolderContents::kOtherSphOutput:
      throw CaseError(where + " holds sph output without a run.json (from an older sph?): remove it or give "
                      "another --output" + std::string(overwrite ? " (--overwrite removes only what a run.json lists)" : ""));
    case FolderContents::kOtherFiles:
      if (resuming) throw CaseError("resume: " + where + " holds no run to resume (no run.json)");
      if (overwrite)
        throw CaseError("overwrite: " + where + " holds files but no run: sph removes only what a run recorded");
      return;
  }
}

std::size_t removeRunFiles(const std::filesystem::path& dir) {
  const RunRecord r = readRunRecord(dir);
  std::size_t removed = 0;
  std::error_code ec;
  for (const std::string& f : r.files) {
    const std::filesystem::path p = dir / f;
    // Only plain names inside the folder: a record never reaches outside it.
    if (std::filesystem::path(f).has_parent_path() || f == "." || f == "..") continue;
    if (std::filesystem::is_regular_file(p, ec)) removed += std::filesystem::remove(p, ec);
  }
  // Snapshots named like this run's whose write the record did not see yet
  // (a run killed between writing a snapshot and its record).
  std::vector<std::filesystem::path> unrecorded;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string f = e.path().filename().string(), prefix = r.name + "_";
    const bool snapshot = f.size() > prefix.size() + 4 && f.rfind(prefix, 0) == 0 &&
                          f.compare(f.size() - 4, 4, ".vtp") == 0 &&
                          std::all_of(f.begin() + static_cast<long>(prefix.size()), f.end() - 4,
                                      [](char ch) { return ch >= '0' && ch <= '9'; });
    if (snapshot && e.is_regular_file(ec)) unrecorded.push_back(e.path());
  }
  for (const auto& p : unrecorded) removed += std::filesystem::remove(p, ec);
  for (const char* f : {kCaseFile, kRecordFile})
    if (std::filesystem::is_regular_file(dir / f, ec)) removed += std::filesystem::remove(dir / f, ec);
  return removed + removeStaleTemporaries(dir);
}

bool makeRunFolder(const std::string& output, bool overwrite, std::ostream& err) {
  const std::filesystem::path dir(output);
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
    err << "sph: error: output folder " << escapeControl(output) << " cannot be created"
        << (ec ? ": " + ec.message() : std::string()) << "\n";
    std::error_code ignored;
    if (!firstNew.empty()) std::filesystem::remove_all(firstNew, ignored);
    return false;
  }
  if (overwrite && inspectFolder(dir) == FolderContents::kRun) {
    const std::size_t removed = removeRunFiles(dir);
    err << "sph: note: --overwrite removed " << removed << " file(s) of the earlier run in " << output << "\n";
  }
  removeStaleTemporaries(dir);
  return true;
}

std::string isoNow() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace sph
