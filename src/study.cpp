// sph study (see include/sph/study.hpp): the study file, the matrix of runs,
// the child `sph run` processes (fork/exec, up to --jobs at once, each in a
// process group of its own so that a Ctrl-C reaches it once, forwarded) and
// the hand-over to validation/study.py.
#include "sph/study.hpp"

#include "sph/case_config.hpp"
#include "sph/case_file.hpp"
#include "sph/case_keys.hpp"
#include "sph/io/atomic_file.hpp"
#include "sph/io/run_folder.hpp"
#include "sph/run_case.hpp"
#include "sph/run_signals.hpp"

#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>
#include <thread>

#ifndef SPH_STUDY_PYTHON
#define SPH_STUDY_PYTHON "/usr/bin/python3"
#endif
#ifndef SPH_STUDY_SCRIPT
#define SPH_STUDY_SCRIPT "validation/study.py"
#endif

namespace sph {
namespace {

using json = nlohmann::ordered_json;
namespace fs = std::filesystem;

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// Keys a study may not set: the study places and names the runs itself.
bool studyOwnsKey(const std::string& key) {
  return key == "output" || key == "name" || key == "resume" || key == "overwrite" || key == "progress";
}

// "key = value" -> (key, value), checked against the key table.
KeyOverride parseOverride(const std::string& text, const std::string& where) {
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    throw CaseError(where + ": '" + text + "' is not 'key = value'");
  KeyOverride o{trim(text.substr(0, eq)), trim(text.substr(eq + 1))};
  const KeySpec* k = findKey(o.first);
  if (k == nullptr) {
    std::vector<std::string> known;
    for (const KeySpec& s : caseKeys()) known.push_back(s.name);
    throw CaseError(unknownKeyMessage(o.first, where, known));
  }
  if (studyOwnsKey(o.first) || isRunOnlyKey(*k))
    throw CaseError(where + ": key '" + o.first + "' cannot be set by a study (the study places and names its runs)");
  if (o.second.empty()) throw CaseError(where + ": key '" + o.first + "' has no value");
  return o;
}

std::vector<KeyOverride> parseOverrides(const CaseEntry& e, const std::string& where) {
  std::vector<KeyOverride> out;
  for (const std::string& v : e.values) out.push_back(parseOverride(v, where));
  return out;
}

// The value of an override as the tokens of its list ("[0, 1]" -> 0, 1),
// strings unquoted.
std::vector<std::string> valueTokens(const std::string& text) {
  std::string t = trim(text);
  if (!t.empty() && t.front() == '[' && t.back() == ']') t = t.substr(1, t.size() - 2);
  std::vector<std::string> out;
  std::stringstream ss(t);
  std::string item;
  while (std::getline(ss, item, ',')) {
    item = trim(item);
    if (item.size() >= 2 && (item.front() == '"' || item.front() == '\'') && item.back() == item.front())
      item = item.substr(1, item.size() - 2);
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

bool sameValue(const std::string& a, const std::string& b) {
  const auto ta = valueTokens(a), tb = valueTokens(b);
  if (ta.size() != tb.size()) return false;
  for (std::size_t i = 0; i < ta.size(); ++i) {
    char *ea = nullptr, *eb = nullptr;
    const double da = std::strtod(ta[i].c_str(), &ea), db = std::strtod(tb[i].c_str(), &eb);
    if (*ea == '\0' && *eb == '\0' && ea != ta[i].c_str() && eb != tb[i].c_str()) {
      if (std::abs(da - db) > 1e-12 * std::max(std::abs(da), std::abs(db))) return false;
    } else if (ta[i] != tb[i]) {
      return false;
    }
  }
  return true;
}

bool isBoolKey(const std::string& key) {
  const KeySpec* k = findKey(key);
  return k && std::holds_alternative<bool CaseConfig::*>(k->field);
}

// fork + exec argv; stdout and stderr to `log` when not empty. In a process
// group of its own: terminal signals reach the study, which forwards them.
pid_t spawn(const std::vector<std::string>& argv, const fs::path& log) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  if (!log.empty()) {
    ::setpgid(0, 0);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd >= 0) {
      ::dup2(fd, STDOUT_FILENO);
      ::dup2(fd, STDERR_FILENO);
      ::close(fd);
    }
  }
  ::execv(args[0], args.data());
  const std::string msg = "sph study: cannot run " + argv[0] + ": " + std::strerror(errno) + "\n";
  if (::write(STDERR_FILENO, msg.data(), msg.size()) < 0) {
  }
  ::_exit(127);
}

int exitStatus(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

std::string seconds(double s) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f s", s);
  return b;
}

std::string actionText(RunAction a) {
  switch (a) {
    case RunAction::kSkip: return "done";
    case RunAction::kResume: return "resumed";
    case RunAction::kFresh: return "started";
    case RunAction::kOverwrite: return "started anew";
  }
  return "";
}

}  // namespace

const std::vector<std::string>& studyObservables() {
  static const std::vector<std::string> o = {"dam_break", "hydrostatic", "toy_star"};
  return o;
}

Study parseStudy(const std::string& text, const std::string& name, const fs::path& dir) {
  Study s;
  s.name = name;
  std::vector<CaseEntry> entries;
  struct CaseOverrides {
    std::string name;
    std::vector<KeyOverride> overrides;
    std::size_t line;
  };
  std::vector<CaseOverrides> caseOverrides;
  try {
    entries = parseCaseText(text);
  } catch (const CaseFileError& e) {
    throw CaseError("study file " + name + (e.line() ? " line " + std::to_string(e.line()) : "") + ": " + e.what());
  }
  for (const CaseEntry& e : entries) {
    const std::string where = "study file " + name + " line " + std::to_string(e.line);
    auto suffix = [&](const std::string& prefix) {
      const std::string n = e.key.substr(prefix.size());
      if (n.empty()) throw CaseError(where + ": '" + e.key + "' needs a name after '" + prefix + "'");
      return n;
    };
    if (startsWith(e.key, "case_")) {
      if (!e.array || e.values.size() < 2 || e.values.size() > 3)
        throw CaseError(where + ": " + e.key + " must be [\"CASE_FILE\", \"OBSERVABLE\"] or [\"CASE_FILE\", "
                        "\"OBSERVABLE\", \"METRIC\"]");
      StudyCase c{suffix("case_"), fs::path(e.values[0]), e.values[1], e.values.size() == 3 ? e.values[2] : "", {}};
      if (c.caseFile.is_relative()) c.caseFile = dir / c.caseFile;
      std::error_code ec;
      if (!fs::is_regular_file(c.caseFile, ec))
        throw CaseError(where + ": case file " + c.caseFile.string() + " of " + e.key + " cannot be read");
      const auto& obs = studyObservables();
      if (std::find(obs.begin(), obs.end(), c.observable) == obs.end()) {
        std::string list;
        for (const auto& o : obs) list += (list.empty() ? "" : ", ") + o;
        throw CaseError(where + ": observable '" + c.observable + "' of " + e.key + " is unknown: it must be one of " + list);
      }
      s.cases.push_back(std::move(c));
    } else if (startsWith(e.key, "method_")) {
      s.methods.push_back({suffix("method_"), parseOverrides(e, where)});
    } else if (startsWith(e.key, "resolution_")) {
      s.resolutions.push_back({suffix("resolution_"), parseOverrides(e, where)});
    } else if (e.key == "overrides") {
      s.common = parseOverrides(e, where);
    } else if (startsWith(e.key, "overrides_")) {
      caseOverrides.push_back({suffix("overrides_"), parseOverrides(e, where), e.line});
    } else if (e.key == "cost") {
      if (e.array || e.values.size() != 1 || (e.values[0] != "wall" && e.values[0] != "cpu"))
        throw CaseError(where + ": cost must be \"wall\" (wall-clock seconds) or \"cpu\" (CPU seconds)");
      s.cost = e.values[0];
    } else if (e.key == "tolerance") {
      for (const std::string& v : e.values) {
        char* end = nullptr;
        const double t = std::strtod(v.c_str(), &end);
        if (end == v.c_str() || *end != '\0' || !(t > 0))
          throw CaseError(where + ": tolerance '" + v + "' must be a number > 0");
        s.tolerances.push_back(t);
      }
    } else {
      throw CaseError(where + ": unknown key '" + e.key +
                      "' (a study file has case_NAME, overrides_NAME, method_NAME, resolution_NAME, overrides, tolerance and cost)");
    }
  }
  if (s.cases.empty()) throw CaseError("study file " + name + " has no case_NAME = [\"CASE_FILE\", \"OBSERVABLE\"]");
  for (CaseOverrides& o : caseOverrides) {
    auto it = std::find_if(s.cases.begin(), s.cases.end(), [&](const StudyCase& c) { return c.name == o.name; });
    if (it == s.cases.end())
      throw CaseError("study file " + name + " line " + std::to_string(o.line) + ": overrides_" + o.name +
                      " names no case (there is no case_" + o.name + ")");
    it->overrides = std::move(o.overrides);
  }
  if (s.methods.empty()) s.methods.push_back({"case", {}});          // the case file as it is
  if (s.resolutions.empty()) s.resolutions.push_back({"case", {}});
  if (s.tolerances.empty()) s.tolerances.push_back(0.05);
  return s;
}

Study readStudyFile(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw CaseError("study file " + file.string() + " cannot be read (missing or not a file)");
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw CaseError("study file " + file.string() + " cannot be read");
  Study s = parseStudy(text.str(), file.string(), file.parent_path());
  s.name = defaultRunName(file.string());
  s.file = file;
  return s;
}

std::vector<StudyRun> studyRuns(const Study& s, const fs::path& output) {
  std::vector<StudyRun> runs;
  for (std::size_t c = 0; c < s.cases.size(); ++c)
    for (std::size_t m = 0; m < s.methods.size(); ++m)
      for (std::size_t r = 0; r < s.resolutions.size(); ++r) {
        StudyRun run;
        run.name = s.cases[c].name + "__" + s.methods[m].name + "__" + s.resolutions[r].name;
        run.caseIndex = c, run.methodIndex = m, run.resolutionIndex = r;
        for (const auto* list : {&s.common, &s.cases[c].overrides, &s.methods[m].overrides, &s.resolutions[r].overrides})
          for (const KeyOverride& o : *list) {
            auto it = std::find_if(run.overrides.begin(), run.overrides.end(),
                                   [&](const KeyOverride& p) { return p.first == o.first; });
            if (it != run.overrides.end()) it->second = o.second;
            else run.overrides.push_back(o);
          }
        run.folder = output / "runs" / run.name;
        runs.push_back(std::move(run));
      }
  return runs;
}

std::vector<std::string> runArguments(const Study& s, const StudyRun& r) {
  std::vector<std::string> a = {"run", s.cases[r.caseIndex].caseFile.string(), "--output", r.folder.string(),
                                "--no-progress"};
  bool threads = false;
  for (const auto& [key, value] : r.overrides) {
    threads |= key == "threads";
    if (isBoolKey(key)) {
      a.push_back(sameValue(value, "true") ? "--" + key : "--no-" + key);
      continue;
    }
    a.push_back("--" + key);
    for (const std::string& t : valueTokens(value)) a.push_back(t);
  }
  if (!threads) a.insert(a.end(), {"--threads", "1"});
  return a;
}

RunAction runAction(const StudyRun& r) {
  std::error_code ec;
  if (!fs::is_regular_file(r.folder / "run.json", ec)) return RunAction::kFresh;
  RunRecord rec;
  try {
    rec = readRunRecord(r.folder);
  } catch (const std::exception&) {
    return RunAction::kOverwrite;
  }
  for (const auto& [key, value] : r.overrides) {
    if (key == "threads" || key == "end_time" || isResumeKey(key)) continue;  // may differ after a resume
    const auto it = rec.caseValues.find(key);
    if (it == rec.caseValues.end() || !sameValue(it->second, value)) return RunAction::kOverwrite;
  }
  if (rec.status == "finished" || rec.status == "blew_up") {
    const auto it = std::find_if(r.overrides.begin(), r.overrides.end(), [](const KeyOverride& o) { return o.first == "end_time"; });
    const auto end = rec.caseValues.find("end_time");
    if (it != r.overrides.end() && end != rec.caseValues.end() && !sameValue(end->second, it->second))
      return RunAction::kOverwrite;
    return RunAction::kSkip;
  }
  if (rec.status == "running" || rec.status == "interrupted") return RunAction::kResume;
  return RunAction::kOverwrite;
}

int runStudy(const Study& s, const StudyOptions& o, std::ostream& out, std::ostream& err) {
  const fs::path output = o.output.empty() ? fs::path("runs") / ("study_" + s.name) : o.output;
  const std::vector<double> tolerances = o.tolerance ? std::vector<double>{*o.tolerance} : s.tolerances;
  std::error_code ec;
  fs::create_directories(output / "logs", ec);
  fs::create_directories(output / "runs", ec);
  if (ec) {
    err << "sph: error: cannot create the study folder " << output.string() << ": " << ec.message() << "\n";
    return kWriteFailed;
  }
  const std::vector<StudyRun> runs = studyRuns(s, output);
  out << "sph study " << s.name << ": " << s.cases.size() << " case(s) x " << s.methods.size() << " method(s) x "
      << s.resolutions.size() << " resolution(s) = " << runs.size() << " runs, " << o.jobs << " at once, in "
      << output.string() << "\n"
      << std::flush;

  installStopHandlers();
  using Clock = std::chrono::steady_clock;
  struct Running {
    std::size_t run;
    RunAction action;
    Clock::time_point start;
  };
  std::map<pid_t, Running> running;
  std::vector<int> exitCodes(runs.size(), -1);
  std::size_t next = 0, done = 0;
  int worst = kSuccess;
  int forwarded = 0;
  auto launch = [&](std::size_t i, RunAction a) {
    std::vector<std::string> argv = {o.self};
    if (a == RunAction::kResume) {
      argv.insert(argv.end(), {"run", "--resume", runs[i].folder.string(), "--no-progress"});
    } else {
      const auto args = runArguments(s, runs[i]);
      argv.insert(argv.end(), args.begin(), args.end());
      if (a == RunAction::kOverwrite) argv.push_back("--overwrite");
    }
    {
      std::ofstream log(output / "logs" / (runs[i].name + ".log"), std::ios::app);
      log << "$ sph";
      for (std::size_t k = 1; k < argv.size(); ++k) log << " " << argv[k];
      log << "\n";
    }
    const pid_t pid = spawn(argv, output / "logs" / (runs[i].name + ".log"));
    if (pid < 0) {
      err << "sph: error: cannot start a run: " << std::strerror(errno) << "\n";
      worst = std::max(worst, static_cast<int>(kWriteFailed));
      return;
    }
    running[pid] = {i, a, Clock::now()};
  };
  while (done < runs.size()) {
    const int sig = stopSignal();
    if (sig != 0 && forwarded == 0) {
      forwarded = sig;
      for (const auto& [pid, r] : running) ::kill(pid, sig);
    }
    while (sig == 0 && worst != kBadInput && next < runs.size() && static_cast<int>(running.size()) < o.jobs) {
      const std::size_t i = next++;
      const RunAction a = runAction(runs[i]);
      if (a == RunAction::kSkip) {
        ++done;
        out << "[" << done << "/" << runs.size() << "] " << runs[i].name << ": done before, kept\n" << std::flush;
        continue;
      }
      launch(i, a);
    }
    if (running.empty()) break;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid <= 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const Running r = it->second;
    running.erase(it);
    const int code = exitStatus(status);
    const double wall = std::chrono::duration<double>(Clock::now() - r.start).count();
    // A resume refused (no snapshot to resume from): run it anew.
    if (r.action == RunAction::kResume && code == kBadInput && stopSignal() == 0) {
      out << "  " << runs[r.run].name << ": cannot be resumed, run anew\n";
      launch(r.run, RunAction::kOverwrite);
      continue;
    }
    ++done;
    exitCodes[r.run] = code;
    std::string how = code == kSuccess ? "finished" : code == kBlewUp ? "blew up (a result: recorded)"
                      : code == kBadInput ? "refused its input"
                      : code >= 128 ? "stopped by a signal" : "failed (exit " + std::to_string(code) + ")";
    out << "[" << done << "/" << runs.size() << "] " << runs[r.run].name << ": " << actionText(r.action) << ", " << how
        << " in " << seconds(wall) << "\n"
        << std::flush;
    if (code == kBadInput || (code != kSuccess && code != kBlewUp && code < 128)) {
      std::ifstream log(output / "logs" / (runs[r.run].name + ".log"));
      std::string line, last;
      while (std::getline(log, line))
        if (line.find("error") != std::string::npos) last = line;
      if (!last.empty()) err << "sph: " << runs[r.run].name << ": " << last << "\n";
      worst = std::max(worst, code == kBadInput ? static_cast<int>(kBadInput) : static_cast<int>(kWriteFailed));
    }
  }
  if (forwarded != 0 || stopSignal() != 0) {
    const int sig = forwarded ? forwarded : stopSignal();
    err << "sph: study stopped by a signal; run the same command again to resume it\n";
    return 128 + sig;
  }

  // study.json: what study.py needs to measure the runs.
  json j;
  j["study"] = s.name;
  j["study_file"] = s.file.string();
  j["tolerances"] = tolerances;
  j["cost"] = s.cost;
  j["command"] = "sph study " + s.file.string() + " --output " + output.string() + " --jobs " + std::to_string(o.jobs) +
                 (o.tolerance ? " --tolerance " + std::to_string(*o.tolerance) : "");
  auto overridesJson = [](const std::vector<KeyOverride>& list) {
    json m = json::object();
    for (const auto& [k, v] : list) m[k] = v;
    return m;
  };
  j["cases"] = json::array();
  for (const StudyCase& c : s.cases)
    j["cases"].push_back({{"name", c.name}, {"case_file", c.caseFile.string()}, {"observable", c.observable},
                          {"metric", c.metric}, {"overrides", overridesJson(c.overrides)}});
  j["methods"] = json::array();
  for (const StudyVariant& m : s.methods) j["methods"].push_back({{"name", m.name}, {"overrides", overridesJson(m.overrides)}});
  j["resolutions"] = json::array();
  for (const StudyVariant& r : s.resolutions)
    j["resolutions"].push_back({{"name", r.name}, {"overrides", overridesJson(r.overrides)}});
  j["overrides"] = overridesJson(s.common);
  j["runs"] = json::array();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const StudyRun& r = runs[i];
    j["runs"].push_back({{"name", r.name},
                         {"case", s.cases[r.caseIndex].name},
                         {"method", s.methods[r.methodIndex].name},
                         {"resolution", s.resolutions[r.resolutionIndex].name},
                         {"folder", fs::relative(r.folder, output, ec).string()},
                         {"overrides", overridesJson(r.overrides)}});
  }
  try {
    writeFileAtomically((output / "study.json").string(), j.dump(2) + "\n");
  } catch (const std::runtime_error& e) {
    err << "sph: error: " << e.what() << "\n";
    return kWriteFailed;
  }
  if (worst != kSuccess) {
    err << "sph: error: not every run could run; the analysis is not made\n";
    return worst;
  }

  // The analysis: errors, study.csv, charts, report.md.
  const char* envPython = std::getenv("SPH_PYTHON");
  const char* envScript = std::getenv("SPH_STUDY_SCRIPT");
  const std::string python = !o.python.empty() ? o.python : envPython ? envPython : SPH_STUDY_PYTHON;
  const std::string script = !o.script.empty() ? o.script : envScript ? envScript : SPH_STUDY_SCRIPT;
  out << "sph study: measuring the runs: " << python << " " << script << " " << output.string() << "\n" << std::flush;
  const pid_t pid = spawn({python, script, output.string()}, "");
  int status = 0;
  if (pid < 0 || ::waitpid(pid, &status, 0) != pid || exitStatus(status) != 0) {
    err << "sph: error: the analysis (" << script << ") failed"
        << (pid > 0 ? " with exit status " + std::to_string(exitStatus(status)) : "") << "\n";
    return kWriteFailed;
  }
  return kSuccess;
}

}  // namespace sph
