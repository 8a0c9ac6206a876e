// Run management, tested on the real executable: SIGINT/SIGTERM stop a run
// cleanly (summary line, exit 130/143, a valid series) and a second SIGINT
// stops it at once; output folders are refused when they hold another run
// unless --overwrite (which removes only that run's files) or --resume;
// run.json records the run; --resume continues bit for bit for every
// integrator and thread count; output_interval snapshots land on exact,
// shortly written multiples of the interval; the summary's dt range; unused
// keys are named; and the bad-input catalogue of these features (exit 2, one
// line naming the key, nothing written or removed).
#include "pvd_reader.hpp"
#include "cli_support.hpp"

#include "sph/case_file.hpp"
#include "sph/case_keys.hpp"
#include "sph/io/number_format.hpp"

#include <nlohmann/json.hpp>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

using namespace sph;
namespace fs = std::filesystem;
namespace tt = boost::test_tools;

namespace {

std::string readText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::json readJson(const fs::path& p) { return nlohmann::json::parse(readText(p)); }

// Every file of a folder with its content: "untouched" means equal.
std::map<std::string, std::string> folderState(const fs::path& dir) {
  std::map<std::string, std::string> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) files[e.path().filename().string()] = readText(e.path());
  return files;
}

// The timestep attributes of a .pvd, as written, and its file attributes.
std::vector<std::string> pvdAttribute(const fs::path& pvd, const std::string& name) {
  const std::string text = readText(pvd);
  const std::regex re(" " + name + "=\"([^\"]*)\"");
  std::vector<std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back((*it)[1]);
  return out;
}

// The .vtp files a series lists, in order.
std::vector<fs::path> seriesFiles(const fs::path& pvd) {
  std::vector<fs::path> out;
  for (const std::string& f : pvdAttribute(pvd, "file")) out.push_back(pvd.parent_path() / f);
  return out;
}

// The state of a snapshot, field by field, in file order.
struct Snapshot {
  std::vector<double> x, v, rho;
  double time = -1, step = -1;
};

Snapshot readSnapshot(const fs::path& vtp) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(vtp.string().c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  Snapshot s;
  BOOST_TEST_REQUIRE(poly->GetNumberOfPoints() > 0, "cannot read " << vtp);
  vtkPointData* pd = poly->GetPointData();
  BOOST_TEST_REQUIRE(pd->GetArray("velocity") != nullptr);
  BOOST_TEST_REQUIRE(pd->GetArray("density") != nullptr);
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
    double x[3];
    poly->GetPoint(i, x);
    s.x.insert(s.x.end(), x, x + 3);
    for (int c = 0; c < 3; ++c) s.v.push_back(pd->GetArray("velocity")->GetComponent(i, c));
    s.rho.push_back(pd->GetArray("density")->GetTuple1(i));
  }
  s.time = poly->GetFieldData()->GetArray("TimeValue")->GetTuple1(0);
  s.step = poly->GetFieldData()->GetArray("step")->GetTuple1(0);
  return s;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// Positions, velocities and densities equal bit for bit, and the same time.
void requireSameState(const fs::path& a, const fs::path& b) {
  const Snapshot sa = readSnapshot(a), sb = readSnapshot(b);
  BOOST_TEST(sameBits(sa.x, sb.x), "positions differ: " << a << " and " << b);
  BOOST_TEST(sameBits(sa.v, sb.v), "velocities differ: " << a << " and " << b);
  BOOST_TEST(sameBits(sa.rho, sb.rho), "densities differ: " << a << " and " << b);
  BOOST_TEST(sa.time == sb.time);
  BOOST_TEST(sa.step == sb.step);
}

// A run of sph in the background, output (stdout and stderr) to a file.
class BackgroundRun {
 public:
  BackgroundRun(const std::vector<std::string>& args, const fs::path& log) : log_(log) {
    pid_ = ::fork();
    BOOST_TEST_REQUIRE(pid_ >= 0);
    if (pid_ == 0) {
      sigset_t none;
      sigemptyset(&none);
      sigprocmask(SIG_SETMASK, &none, nullptr);  // the test framework's mask is not sph's
      ::signal(SIGINT, SIG_DFL);
      ::signal(SIGTERM, SIG_DFL);
      const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      std::vector<std::string> all{SPH_EXECUTABLE};
      all.insert(all.end(), args.begin(), args.end());
      std::vector<char*> argv;
      for (auto& a : all) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
  }
  ~BackgroundRun() {
    if (pid_ > 0 && !done_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }

  bool running() {
    if (done_) return false;
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      done_ = true;
      status_ = status;
    }
    return !done_;
  }

  // Waits (at most `seconds`) until `ready()` holds; false if the run ended first.
  template <class Ready>
  bool waitUntil(Ready ready, double seconds = 60) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      if (ready()) return true;
      if (!running()) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
  }

  void signal(int sig) const { ::kill(pid_, sig); }

  // Whether signal `sig` is pending (sent, not yet delivered) for the
  // process or any of its threads (/proc/PID/status ShdPnd, task SigPnd).
  bool pending(int sig) const {
    const std::uint64_t bit = std::uint64_t{1} << (sig - 1);
    auto has = [&](const fs::path& status, const std::string& field) {
      std::ifstream in(status);
      std::string line;
      while (std::getline(in, line))
        if (line.rfind(field + ":", 0) == 0) return (std::stoull(line.substr(field.size() + 1), nullptr, 16) & bit) != 0;
      return false;
    };
    const fs::path proc = "/proc/" + std::to_string(pid_);
    if (has(proc / "status", "ShdPnd")) return true;
    std::error_code ec;
    for (const auto& task : fs::directory_iterator(proc / "task", ec))
      if (has(task.path() / "status", "SigPnd")) return true;
    return false;
  }

  // The wait status once it ended (killed after `seconds`).
  int wait(double seconds = 60) {
    waitUntil([] { return false; }, seconds);
    if (running()) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, &status_, 0);
      done_ = true;
      BOOST_FAIL("sph did not end within " << seconds << " s");
    }
    return status_;
  }

  std::string output() const { return readText(log_); }

 private:
  fs::path log_;
  pid_t pid_ = -1;
  bool done_ = false;
  int status_ = 0;
};

std::size_t snapshotsListed(const fs::path& pvd) { return pvdAttribute(pvd, "timestep").size(); }

// The checks every refusal shares: exit 2, one line "sph: error: ..." that
// contains `expected`.
void expectOneLineError(const test::Result& r, const std::string& expected) {
  BOOST_TEST(r.exitCode == 2, r.output);
  BOOST_TEST(r.output.rfind("sph: error: ", 0) == 0, r.output);
  BOOST_TEST(std::count(r.output.begin(), r.output.end(), '\n') == 1, r.output);
  BOOST_TEST(r.output.find(expected) != std::string::npos, "expected '" << expected << "' in: " << r.output);
}

// A small wcsph case whose forces depend on the velocity (Laplacian
// viscosity, XSPH) with a Tait EOS, gravity and walls: 600 particles, above
// the size at which the loops run in parallel.
std::string wcsphCase(const fs::path& dir) {
  const fs::path file = dir / "wcsph_box.case";
  std::ofstream(file) << "model = \"wcsph\"\n"
                         "kernel = \"cubic_spline\"\n"
                         "h = 0.013\n"
                         "eos = \"tait\"\n"
                         "c0 = 20\n"
                         "rho0 = 1000\n"
                         "viscosity = \"laplacian\"\n"
                         "mu = 0.5\n"
                         "xsph = 0.5\n"
                         // A free block with summation density: its surface reads 0.6 rho0;
                         // with tension allowed it pulls itself to 1.16 rho0 and the
                         // regime check stops it (compressed).
                         "negative_pressure = \"clamp\"\n"
                         "g = 9.81\n"
                         "dt = 1e-4\n"
                         "end_time = 0.01\n"
                         "domain_min = [0, 0]\n"
                         "domain_max = [1, 1]\n"
                         "block_min = [0.02, 0.02]\n"
                         "block_max = [0.22, 0.32]\n"
                         "spacing = 0.01\n";
  return file.string();
}

// The decimal k * interval as the shortest text of the double nearest it.
std::string decimalMultiple(long k, double interval) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.12g", static_cast<double>(k) * interval);
  return shortestDecimal(std::stod(buf));
}

const std::regex kStoppedLine(R"(sph: stopped at step (\d+), t = (\S+) s)");

}  // namespace

BOOST_AUTO_TEST_SUITE(run_folder)

// Starts the dam break (long enough never to end by itself) into
// dir/run, sends `sig` once it has written a few snapshots, and checks the
// clean stop: exit 128 + sig, the line "stopped at step N, t = T s (SIG)",
// run.json "interrupted" naming the signal, and a valid series that ends at
// step N with no temporary left. Returns N and T as written.
std::pair<long, std::string> stopRunWith(int sig, const char* sigName, const fs::path& dir) {
  const fs::path out = dir / "run", pvd = out / "dam_break_seed.pvd";
  BackgroundRun run({"run", test::caseFile("dam_break_seed"), "--output", out.string(), "--end_time", "5",
                     "--output_every", "20", "--threads", "1"},
                    dir / "log.txt");
  BOOST_TEST_REQUIRE(run.waitUntil([&] { return snapshotsListed(pvd) >= 3; }), run.output());
  run.signal(sig);
  const int status = run.wait();
  const std::string log = run.output();
  BOOST_TEST_REQUIRE(WIFEXITED(status), log);
  BOOST_TEST(WEXITSTATUS(status) == 128 + sig, log);
  std::smatch m;
  BOOST_TEST_REQUIRE(std::regex_search(log, m, kStoppedLine), log);
  const long step = std::stol(m[1]);
  const std::string time = m[2];
  BOOST_TEST(log.find(std::string("(") + sigName + "); continue with: sph run --resume " + out.string()) !=
                 std::string::npos,
             log);
  BOOST_TEST(log.find(std::string("stopped by ") + sigName + " at step " + std::to_string(step) + ", t = " + time +
                      " s") != std::string::npos,
             log);
  const auto record = readJson(out / "run.json");
  BOOST_TEST(record["status"] == "interrupted");
  BOOST_TEST(record["message"].get<std::string>().find(sigName) != std::string::npos);
  BOOST_TEST(record["summary"]["steps"] == step);
  BOOST_TEST(shortestDecimal(record["summary"]["simulated_time_s"].get<double>()) == time);
  test::readPvd(pvd);
  BOOST_TEST(pvdAttribute(pvd, "timestep").back() == time);
  BOOST_TEST(readSnapshot(seriesFiles(pvd).back()).step == static_cast<double>(step));
  for (const auto& e : fs::directory_iterator(out)) BOOST_TEST(e.path().extension() != ".tmp");
  return {step, time};
}

// SIGINT: the step in progress ends, a final snapshot, the .pvd, run.json and
// the summary are written, exit 130. --resume then finishes the run, and
// the result is bit for bit that of a run never interrupted.
BOOST_AUTO_TEST_CASE(sigint_stops_cleanly_and_resume_finishes) {
  const auto dir = test::scratchDir("sigint");
  const fs::path out = dir / "run", pvd = out / "dam_break_seed.pvd";
  const long step = stopRunWith(SIGINT, "SIGINT", dir).first;

  // Resume to 100 steps later; the series grows, step and file numbers go on.
  const std::string end = shortestDecimal(static_cast<double>(step + 100) / 1e4);
  const auto before = pvdAttribute(pvd, "file");
  const auto r = test::runSph({"run", "--resume", out.string(), "--end_time", end});
  BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
  const auto files = pvdAttribute(pvd, "file"), steps = pvdAttribute(pvd, "step");
  BOOST_TEST_REQUIRE(files.size() > before.size());
  BOOST_TEST(std::equal(before.begin(), before.end(), files.begin()));
  for (std::size_t k = 0; k < files.size(); ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "dam_break_seed_%05zu.vtp", k);
    BOOST_TEST(files[k] == name);
    if (k > 0) BOOST_TEST(std::stol(steps[k]) > std::stol(steps[k - 1]));
  }
  BOOST_TEST(std::stol(steps.back()) == step + 100);
  BOOST_TEST(readJson(out / "run.json")["status"] == "finished");
  test::readPvd(pvd);

  // The run never interrupted reaches the same state.
  const fs::path whole = dir / "whole";
  const auto w = test::runSph({"run", test::caseFile("dam_break_seed"), "--output", whole.string(), "--end_time", end,
                               "--output_every", "20", "--threads", "1"});
  BOOST_TEST_REQUIRE(w.exitCode == 0, w.output);
  requireSameState(seriesFiles(whole / "dam_break_seed.pvd").back(), seriesFiles(pvd).back());
}

BOOST_AUTO_TEST_CASE(sigterm_exits_143) { stopRunWith(SIGTERM, "SIGTERM", test::scratchDir("sigterm")); }

// A second SIGINT after the first ends the run at once (killed by the
// signal, no summary), and the series stays valid and resumable. The second
// is sent once the first has been delivered (two pending signals would merge
// into one), while the run still finishes its step: 20 000 particles, so
// that the step and the final snapshot take a while.
BOOST_AUTO_TEST_CASE(second_sigint_stops_at_once) {
  // On a loaded machine the first stop may complete (snapshot, summary,
  // exit 130) before the second signal arrives; that run is checked as a
  // clean stop and the race is tried again, up to five times.
  fs::path dir, out, pvd;
  int status = 0;
  std::string log;
  for (int attempt = 0; attempt < 5; ++attempt) {
    dir = test::scratchDir("sigint2_" + std::to_string(attempt));
    out = dir / "run", pvd = out / "dam_break_seed.pvd";
    BackgroundRun run({"run", test::caseFile("dam_break_seed"), "--output", out.string(), "--end_time", "5",
                       "--spacing", "0.0025", "--h", "0.0033", "--output_every", "100000", "--threads", "1"},
                      dir / "log.txt");
    BOOST_TEST_REQUIRE(run.waitUntil([&] { return snapshotsListed(pvd) >= 1; }), run.output());
    run.signal(SIGINT);
    BOOST_TEST(run.waitUntil([&] { return !run.pending(SIGINT); }, 10));
    run.signal(SIGINT);
    status = run.wait();
    log = run.output();
    if (WIFSIGNALED(status)) break;
    BOOST_TEST(WEXITSTATUS(status) == 130, log);  // the first stop won the race: a clean stop
    BOOST_TEST(log.find("stopped at step") != std::string::npos, log);
  }
  BOOST_TEST_REQUIRE(WIFSIGNALED(status), log);
  BOOST_TEST(WTERMSIG(status) == SIGINT);
  BOOST_TEST(log.find("stopped at step") == std::string::npos, log);
  const auto series = test::readPvd(pvd);
  BOOST_TEST(readJson(out / "run.json")["status"] == "running");
  const auto r = test::runSph({"run", "--resume", out.string(), "--end_time",
                               shortestDecimal(std::stod(pvdAttribute(pvd, "timestep").back()) + 0.0003)});
  BOOST_TEST(r.exitCode == 0, r.output);
  BOOST_TEST(snapshotsListed(pvd) == series.size() + 1);
  test::readPvd(pvd);
  for (const auto& e : fs::directory_iterator(out)) BOOST_TEST(e.path().extension() != ".tmp");
}

// A folder holding a run is refused; --overwrite removes exactly that run's
// files (not the user's) and runs; a folder of other files is refused with
// --overwrite, and sph output without run.json is refused in any case.
BOOST_AUTO_TEST_CASE(used_folder_refused_overwrite_removes_only_the_run) {
  const auto dir = test::scratchDir("folders");
  const fs::path out = dir / "run";
  const std::vector<std::string> base{"run", test::caseFile("dam_break_seed"), "--output", out.string(), "--output_every",
                                      "10"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = base;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  BOOST_TEST_REQUIRE(test::runSph(with({"--end_time", "0.005"})).exitCode == 0);
  std::ofstream(out / "notes.txt") << "the user's own file\n";
  std::ofstream(out / "dam_break_seed_notes.vtp") << "the user's too\n";
  // A snapshot written just before a kill, not in run.json yet.
  fs::copy_file(out / "dam_break_seed_00005.vtp", out / "dam_break_seed_00006.vtp");
  const auto first = folderState(out);
  const auto firstFiles = readJson(out / "run.json")["files"].get<std::vector<std::string>>();

  const auto again = test::runSph(with({"--end_time", "0.002"}));
  expectOneLineError(again, "output folder " + out.string() + " holds the run 'dam_break_seed'");
  BOOST_TEST(again.output.find("--overwrite") != std::string::npos);
  BOOST_TEST(again.output.find("--resume " + out.string()) != std::string::npos);
  BOOST_TEST((folderState(out) == first));

  const auto over = test::runSph(with({"--end_time", "0.002", "--overwrite"}));
  BOOST_TEST_REQUIRE(over.exitCode == 0, over.output);
  BOOST_TEST(over.output.find("--overwrite removed " + std::to_string(firstFiles.size() + 1) + " file(s)") !=
                 std::string::npos,
             over.output);
  const auto now = folderState(out);
  for (const char* mine : {"notes.txt", "dam_break_seed_notes.vtp"}) BOOST_TEST(now.at(mine) == first.at(mine));
  for (const char* old : {"dam_break_seed_00005.vtp", "dam_break_seed_00006.vtp"})
    BOOST_TEST(now.count(old) == 0u, "a snapshot of the old run survived: " << old);
  BOOST_TEST(snapshotsListed(out / "dam_break_seed.pvd") == 3u);
  // The new record lists every file of the folder but the user's.
  const auto files = readJson(out / "run.json")["files"].get<std::vector<std::string>>();
  const std::set<std::string> listed(files.begin(), files.end());
  std::set<std::string> present;
  for (const auto& [name, text] : now)
    if (name != "notes.txt" && name != "dam_break_seed_notes.vtp") present.insert(name);
  BOOST_TEST(listed == present, tt::per_element());

  // sph output without run.json: refused, even with --overwrite.
  const fs::path bare = dir / "bare";
  fs::create_directories(bare);
  fs::copy_file(out / "dam_break_seed_00000.vtp", bare / "dam_break_seed_00000.vtp");
  const auto bareState = folderState(bare);
  for (const bool overwrite : {false, true}) {
    const auto r = test::runSph({"run", test::caseFile("dam_break_seed"), "--output", bare.string(), "--end_time", "0.001",
                                 overwrite ? "--overwrite" : "--progress"});
    expectOneLineError(r, "holds sph output without a run.json");
    BOOST_TEST((folderState(bare) == bareState));
  }
  // A folder of other files is fine without --overwrite: nothing is removed.
  const fs::path other = dir / "other";
  fs::create_directories(other);
  std::ofstream(other / "data.txt") << "x\n";
  const auto r = test::runSph({"run", test::caseFile("one_particle"), "--output", other.string(), "--end_time", "0.001"});
  BOOST_TEST(r.exitCode == 0, r.output);
  BOOST_TEST(readText(other / "data.txt") == "x\n");
}

// run.json: the resolved case (every key, with the value used), the command
// line, version and commit, threads, times, summary figures, files, status.
BOOST_AUTO_TEST_CASE(run_json_records_the_run) {
  const auto dir = test::scratchDir("record");
  const fs::path out = dir / "run";
  const std::vector<std::string> args{"run",         test::caseFile("dam_break_seed"), "--output", out.string(),
                                      "--end_time",  "0.003",  "--output_every",     "10",
                                      "--mu",        "0.5",    "--threads",          "1"};
  const auto r = test::runSph(args);
  BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
  const auto j = readJson(out / "run.json");
  BOOST_TEST(j["sph_version"] == SPH_VERSION);
  BOOST_TEST(!j["git_commit"].get<std::string>().empty());
  BOOST_TEST(j["name"] == "dam_break_seed");
  BOOST_TEST(j["status"] == "finished");
  BOOST_TEST(j["message"] == "");
  std::vector<std::string> expectedLine{"sph"};
  expectedLine.insert(expectedLine.end(), args.begin(), args.end());
  BOOST_TEST((j["command_line"].get<std::vector<std::string>>() == expectedLine));
  BOOST_TEST(j["dimension"] == 2);
  BOOST_TEST(j["model"] == "seed_wcsph");

  // Every key of the table but the run-only ones, with the value used: the
  // case file's, the command line's, or the default.
  for (const KeySpec& k : caseKeys())
    BOOST_TEST(j["case"].contains(k.name) != isRunOnlyKey(k), "key " << k.name);
  std::ifstream caseIn(test::caseFile("dam_break_seed"));
  for (const CaseEntry& e : readCaseFile(caseIn)) {
    if (e.key == "mu" || e.key == "end_time" || e.key == "output_every") continue;
    std::string text = e.array ? "[" : "";
    for (std::size_t k = 0; k < e.values.size(); ++k) text += (k ? "," : "") + e.values[k];
    if (e.array) text += "]";
    nlohmann::json expected = nlohmann::json::parse(text, nullptr, false);
    if (expected.is_discarded()) expected = text;
    BOOST_TEST(j["case"][e.key] == expected, "key " << e.key << ": " << j["case"][e.key] << " vs " << text);
  }
  BOOST_TEST(j["case"]["mu"] == 0.5);
  BOOST_TEST(j["case"]["end_time"] == 0.003);
  BOOST_TEST(j["case"]["output_every"] == 10);
  BOOST_TEST(j["case"]["integrator"] == "leap_frog");  // a default, filled in
  BOOST_TEST(j["case"]["threads"] == "1");
  const auto given = j["given_keys"].get<std::vector<std::string>>();
  BOOST_TEST((std::find(given.begin(), given.end(), "mu") != given.end()));

  BOOST_TEST(j["threads"]["asked"] == "1");
  BOOST_TEST((j["threads"]["used"].get<std::vector<int>>() == std::vector<int>{1}));
  BOOST_TEST(j["threads"]["stepping_seconds"]["1"].get<double>() > 0);
  BOOST_TEST(j["threads"]["stepping_seconds"].size() == 1u);
  const std::regex iso(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)");
  BOOST_TEST(std::regex_match(j["started"].get<std::string>(), iso));
  BOOST_TEST(std::regex_match(j["ended"].get<std::string>(), iso));
  BOOST_TEST(j["ended"].get<std::string>() >= j["started"].get<std::string>());

  const auto& s = j["summary"];
  const fs::path pvd = out / "dam_break_seed.pvd";
  const auto files = seriesFiles(pvd);
  const Snapshot last = readSnapshot(files.back());
  BOOST_TEST(s["steps"] == std::lround(0.003 / 1e-4));
  BOOST_TEST(s["simulated_time_s"] == last.time);
  BOOST_TEST(s["particles"] == last.rho.size());
  BOOST_TEST(s["snapshots"] == files.size());
  BOOST_TEST(s["last_snapshot"] == files.back().filename().string());
  BOOST_TEST(s["dt_min_s"] == 1e-4);
  BOOST_TEST(s["dt_max_s"] == 1e-4);
  BOOST_TEST(s["dt_limited_by"] == "fixed");
  BOOST_TEST(s["particle_steps_per_second"].get<double>() > 0);
  BOOST_TEST(s["wall_seconds"].get<double>() > 0);
  BOOST_TEST(s["neighbours_per_particle"].get<double>() > 0);
  std::set<std::string> listed, present;
  for (const auto& f : j["files"]) listed.insert(f.get<std::string>());
  for (const auto& e : fs::directory_iterator(out)) present.insert(e.path().filename().string());
  BOOST_TEST(listed == present, tt::per_element());

  // run.case repeats the run: no warning, the same particles.
  const auto again = test::runSph({"run", (out / "run.case").string(), "--output", (dir / "again").string()});
  BOOST_TEST_REQUIRE(again.exitCode == 0, again.output);
  BOOST_TEST(again.output.find("warning") == std::string::npos, again.output);
  requireSameState(files.back(), seriesFiles(dir / "again" / "dam_break_seed.pvd").back());

  // A run that stops itself says how: an adaptive dt that collapses (the
  // star squeezed into 8e-9 m) names the criterion, exit 3.
  const fs::path collapse = dir / "collapse";
  const auto c = test::runSph({"run", test::caseFile("toy_star_2d"), "--output", collapse.string(), "--star_radius",
                               "8e-9"});
  BOOST_TEST(c.exitCode == 3, c.output);
  BOOST_TEST(c.output.find("the adaptive time step collapsed") != std::string::npos, c.output);
  const auto cj = readJson(collapse / "run.json");
  BOOST_TEST(cj["status"] == "blew_up");
  BOOST_TEST(cj["message"].get<std::string>().find("criterion") != std::string::npos);
  test::readPvd(collapse / "toy_star_2d.pvd");
}

// A run stopped early and resumed ends in the same state, bit for bit, as
// the run never stopped: every integrator, a wcsph case with velocity-
// dependent forces (viscosity, XSPH), the seed dam break, the water dam
// break (walls, continuity density), and adaptive steps
// stopped on an output time; stopped and resumed with 1 thread and with 2
// (results do not depend on the thread count). The series and record go on.
// Short runs: on a loaded machine 2 threads cost milliseconds per barrier.
BOOST_AUTO_TEST_CASE(resume_is_bit_identical) {
  const auto dir = test::scratchDir("resume");
  const std::string wcsph = wcsphCase(dir);
  struct Variant {
    std::string label, caseFile;
    std::vector<std::string> flags;
    std::string stop, end;
  };
  std::vector<Variant> variants;
  for (const char* integrator : {"leap_frog", "rk4", "symplectic_euler", "euler", "two_step_leap_frog"})
    variants.push_back({integrator, wcsph, {"--integrator", integrator, "--output_every", "10"}, "0.0017", "0.004"});
  variants.push_back({"seed", test::caseFile("dam_break_seed"), {"--output_every", "10"}, "0.0023", "0.004"});
  // Wall particles, continuity density with delta-SPH, hydrostatic start:
  // the density and its rate are state too.
  variants.push_back({"water", test::caseFile("dam_break_mm"), {"--output_every", "20"}, "0.0023", "0.004"});
  // The two-step leap-frog with continuity density and dynamic walls (whose
  // density it integrates): vbar and rhobar of the step before are state.
  variants.push_back({"water_two_step", test::caseFile("dam_break_mm"),
                      {"--output_every", "20", "--integrator", "two_step_leap_frog", "--boundary", "dynamic"},
                      "0.0023", "0.004"});
  // CSPM with Shepard re-initialisation on the snapshot steps: the density-
  // rate pass reads L_i, which the snapshot does not hold.
  variants.push_back({"water_cspm_shepard", test::caseFile("dam_break_mm"),
                      {"--output_every", "20", "--gradient_correction", "cspm", "--density_reinit", "shepard",
                       "--density_reinit_every", "20"},
                      "0.0023", "0.004"});
  // A Verlet skin (wcsph's default above rebuilds the list seldom in these
  // short runs) so thin that the list is rebuilt every few
  // steps, stopped between two rebuilds; leap-frog's half-step density rate
  // and RK4's four evaluations; a periodic box, whose particles are wrapped
  // only at a rebuild.
  variants.push_back({"water_skin", test::caseFile("dam_break_mm"),
                      {"--output_every", "20", "--neighbour_skin", "0.002"}, "0.0023", "0.004"});
  // The cell walk (no stored list) and the packed list with the same thin
  // skin.
  for (const char* walk : {"cells", "packed"})
    variants.push_back({std::string("water_") + walk + "_skin", test::caseFile("dam_break_mm"),
                        {"--output_every", "20", "--neighbour_skin", "0.002", "--neighbour_walk", walk}, "0.0023",
                        "0.004"});
  variants.push_back({"rk4_skin", wcsph, {"--integrator", "rk4", "--output_every", "10", "--neighbour_skin", "0.002"},
                      "0.0017", "0.004"});
  // Particle shifting: the shift after a resume takes its sums from a walk
  // of its own, the run never stopped from the force pass
  // (terms/shifting_sums.hpp); with walls, with a Shepard re-initialisation
  // on the snapshot step (after which the shift walks too), periodic.
  variants.push_back({"shifting_walls", test::caseFile("dam_break_mm"),
                      {"--output_every", "20", "--shifting", "fickian"}, "0.0023", "0.004"});
  variants.push_back({"shifting_shepard", test::caseFile("dam_break_mm"),
                      {"--output_every", "20", "--shifting", "fickian", "--density_reinit", "shepard",
                       "--density_reinit_every", "20"},
                      "0.0023", "0.004"});
  variants.push_back({"shifting_periodic", test::caseFile("taylor_green_2d"), {"--output_every", "10"}, "0.01",
                      "0.02"});
  variants.push_back({"periodic_skin", test::caseFile("poiseuille_2d"),
                      {"--output_every", "20", "--neighbour_skin", "0.01", "--gravity", "1e-2", "0"}, "0.0235", "0.04"});
  for (const char* integrator : {"leap_frog", "rk4"})
    variants.push_back({std::string("adaptive_") + integrator,
                        wcsph,
                        {"--integrator", integrator, "--cfl", "0.3", "--dt", "2e-4", "--output_interval", "0.001"},
                        "0.002",
                        "0.004"});
  for (const Variant& v : variants) {
    const std::string name = fs::path(v.caseFile).stem().string() + ".pvd";
    auto args = [&](const fs::path& out, const std::string& end, const char* threads) {
      std::vector<std::string> a{"run", v.caseFile, "--output", out.string(), "--end_time", end, "--threads", threads};
      a.insert(a.end(), v.flags.begin(), v.flags.end());
      return a;
    };
    const fs::path whole = dir / (v.label + "_whole");
    const auto w = test::runSph(args(whole, v.end, "1"));
    BOOST_TEST_REQUIRE(w.exitCode == 0, w.output);
    for (const char* threads : {"1", "2"}) {
      BOOST_TEST_CONTEXT(v.label << ", " << threads << " thread(s)") {
        const fs::path split = dir / (v.label + "_" + threads);
        const auto s = test::runSph(args(split, v.stop, threads));
        BOOST_TEST_REQUIRE(s.exitCode == 0, s.output);
        const auto r = test::runSph({"run", "--resume", split.string(), "--end_time", v.end, "--threads", threads});
        BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
        requireSameState(seriesFiles(whole / name).back(), seriesFiles(split / name).back());
        // Probe files (the water dam break has them) go on as if never stopped.
        for (const char* probe : {"probes.csv", "heights.csv", "front.csv"})
          if (fs::exists(whole / probe)) BOOST_TEST(readText(split / probe) == readText(whole / probe), probe);
        // The resumed series is the whole one, plus the stop's snapshot when
        // it fell between two outputs.
        auto wt = pvdAttribute(whole / name, "timestep");
        if (std::find(wt.begin(), wt.end(), v.stop) == wt.end()) wt.push_back(v.stop);
        std::sort(wt.begin(), wt.end(), [](const auto& a, const auto& b) { return std::stod(a) < std::stod(b); });
        BOOST_TEST(pvdAttribute(split / name, "timestep") == wt, tt::per_element());
        const auto j = readJson(split / "run.json");
        BOOST_TEST(j["status"] == "finished");
        BOOST_TEST(j["resumed_at"].size() == 1u);
        BOOST_TEST(j["resumed_at"][0].get<std::string>().find("sph run --resume " + split.string()) !=
                   std::string::npos);
        BOOST_TEST((j["command_line"].get<std::vector<std::string>>() == [&] {
          std::vector<std::string> line{"sph"};
          for (const auto& a : args(split, v.stop, threads)) line.push_back(a);
          return line;
        }()));  // the command that started the run
        BOOST_TEST(j["case"]["end_time"] == std::stod(v.end));
        BOOST_TEST(j["summary"]["steps"] == readJson(whole / "run.json")["summary"]["steps"]);
        BOOST_TEST(j["summary"]["start_time_s"] == 0.0);
      }
    }
  }
}

// The logs (energy.csv, timestep.csv) grow by appended rows. A run killed
// while appending leaves rows past its series' last snapshot, the last one
// possibly without its newline: a resume drops them, and the logs end as
// those of the run never stopped.
BOOST_AUTO_TEST_CASE(resume_drops_log_rows_past_the_last_snapshot) {
  const auto dir = test::scratchDir("resume_logs");
  const std::string box = wcsphCase(dir);
  auto run = [&](const fs::path& out, const char* end) {
    return test::runSph({"run", box, "--output", out.string(), "--end_time", end, "--cfl", "0.3", "--dt", "2e-4",
                         "--output_interval", "0.001"});
  };
  const fs::path whole = dir / "whole", split = dir / "split";
  BOOST_TEST_REQUIRE(run(whole, "0.004").exitCode == 0);
  BOOST_TEST_REQUIRE(run(split, "0.002").exitCode == 0);
  // Whole rows past the snapshot, then a row cut inside its first column,
  // which reads as an early time (0.00 s, step 1).
  std::ofstream(split / "energy.csv", std::ios::app) << "0.0025,1,2,3\n0.00";
  std::ofstream(split / "timestep.csv", std::ios::app) << "99999,0.1,0.0001,cfl\n1";
  const auto r = test::runSph({"run", "--resume", split.string(), "--end_time", "0.004"});
  BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
  for (const char* log : {"energy.csv", "timestep.csv"}) BOOST_TEST(readText(split / log) == readText(whole / log), log);
}

// A run whose snapshot lacks the state its integrator carries between steps
// (run.case edited from leap_frog to two_step_leap_frog, or a snapshot
// written by another integrator) is refused with one line naming the
// missing array, and the folder is left as it was: continuing with zeros
// for the previous velocity would be a different, wrong, run.
BOOST_AUTO_TEST_CASE(resume_refuses_a_snapshot_without_the_integrators_state) {
  const auto dir = test::scratchDir("resume_carried");
  const fs::path out = dir / "run";
  BOOST_TEST_REQUIRE(test::runSph({"run", wcsphCase(dir), "--output", out.string(), "--end_time", "0.002",
                                   "--output_every", "10", "--integrator", "leap_frog"})
                         .exitCode == 0);
  {
    std::ifstream in(out / "run.case");
    std::stringstream text;
    text << in.rdbuf();
    std::string s = text.str();
    const auto at = s.find("integrator = \"leap_frog\"");
    BOOST_TEST_REQUIRE(at != std::string::npos, s);
    s.replace(at, std::string("integrator = \"leap_frog\"").size(), "integrator = \"two_step_leap_frog\"");
    std::ofstream(out / "run.case") << s;
  }
  const auto before = folderState(out);
  expectOneLineError(test::runSph({"run", "--resume", out.string(), "--end_time", "0.004"}),
                     "has no velocity_previous array, which the integrator two_step_leap_frog carries");
  BOOST_TEST((folderState(out) == before));
}

// Snapshots every output_interval seconds of simulated time land exactly on
// the multiples of the interval (adaptive steps are cut to them), written
// as the shortest decimal of k * interval; the last one at end_time. The
// flag replaces the case file's output_every.
BOOST_AUTO_TEST_CASE(output_interval_times_are_exact_decimals) {
  const auto dir = test::scratchDir("interval");
  struct Variant {
    std::string caseName;
    double interval;
    std::string end;
  };
  for (const Variant& v : {Variant{"toy_star_2d", 0.1, "1"}, Variant{"toy_star_2d", 0.07, "0.5"},
                           Variant{"dam_break_seed", 0.002, "0.011"}}) {
    BOOST_TEST_CONTEXT(v.caseName << ", interval " << v.interval) {
      const fs::path out = dir / (v.caseName + shortestDecimal(v.interval));
      const auto r = test::runSph({"run", test::caseFile(v.caseName), "--output", out.string(), "--output_interval",
                                   shortestDecimal(v.interval), "--end_time", v.end});
      BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
      const fs::path pvd = out / (v.caseName + ".pvd");
      const auto times = pvdAttribute(pvd, "timestep");
      std::vector<std::string> expected;
      for (long k = 0; k * v.interval < std::stod(v.end) * (1 - 1e-9); ++k) expected.push_back(decimalMultiple(k, v.interval));
      expected.push_back(v.end);
      BOOST_TEST(times == expected);
      // The snapshots hold the same time as the series says.
      const auto files = seriesFiles(pvd);
      for (std::size_t k = 0; k < files.size() && k < times.size(); ++k)
        BOOST_TEST(shortestDecimal(readSnapshot(files[k]).time) == times[k]);
    }
  }
}

// The summary gives the dt range used and the criterion that set dt most,
// as timestep.csv and run.json record them.
BOOST_AUTO_TEST_CASE(summary_gives_dt_range_and_criterion) {
  const auto dir = test::scratchDir("dt_range");
  const fs::path out = dir / "star";
  const auto r = test::runSph({"run", test::caseFile("toy_star_2d"), "--output", out.string(), "--end_time", "2"});
  BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
  std::smatch m;
  BOOST_TEST_REQUIRE(
      std::regex_search(r.output, m, std::regex(R"(steps +(\d+) \(dt (\S+) to (\S+) s; set by (\w+) in (\d+)% of the steps\))")),
      r.output);
  std::ifstream csv(out / "timestep.csv");
  std::string line;
  std::getline(csv, line);
  double lo = 1e300, hi = 0;
  std::map<std::string, long> count;
  long steps = 0;
  while (std::getline(csv, line)) {
    std::stringstream s(line);
    std::string step, time, dt, criterion;
    std::getline(s, step, ',');
    std::getline(s, time, ',');
    std::getline(s, dt, ',');
    std::getline(s, criterion, ',');
    lo = std::min(lo, std::stod(dt));
    hi = std::max(hi, std::stod(dt));
    ++count[criterion];
    ++steps;
  }
  const auto most = std::max_element(count.begin(), count.end(),
                                     [](const auto& a, const auto& b) { return a.second < b.second; });
  BOOST_TEST(std::stol(m[1]) == steps);
  BOOST_TEST(std::stod(m[2]) == lo, tt::tolerance(1e-2));
  BOOST_TEST(std::stod(m[3]) == hi, tt::tolerance(1e-2));
  BOOST_TEST(m[4] == most->first);
  BOOST_TEST(std::stol(m[5]) == std::lround(100.0 * static_cast<double>(most->second) / static_cast<double>(steps)));
  const auto j = readJson(out / "run.json");
  BOOST_TEST(j["summary"]["dt_min_s"].get<double>() == lo, tt::tolerance(1e-5));
  BOOST_TEST(j["summary"]["dt_max_s"].get<double>() == hi, tt::tolerance(1e-5));
  BOOST_TEST(j["summary"]["dt_limited_by"] == most->first);
  // A fixed dt says so.
  const auto f = test::runSph({"run", test::caseFile("one_particle"), "--output", (dir / "fixed").string(),
                               "--end_time", "0.01"});
  BOOST_TEST(f.output.find("(dt = 0.0001 s, fixed)") != std::string::npos, f.output);
}

// A key that the chosen model or option does not use is named in a warning;
// a case that uses every key it sets gets none.
BOOST_AUTO_TEST_CASE(unused_keys_are_named) {
  const auto dir = test::scratchDir("unused");
  const std::string wcsph = wcsphCase(dir);
  struct Variant {
    std::string caseFile;
    std::vector<std::string> flags;
    std::string key;
  };
  const std::vector<Variant> variants{
      {test::caseFile("one_particle"), {"--alpha", "2"}, "alpha"},  // seed model
      {wcsph, {"--alpha", "2"}, "alpha"},                           // Laplacian viscosity
      {wcsph, {"--eos", "linear", "--gamma", "5"}, "gamma"},
      {test::caseFile("one_particle"), {"--no-walls", "--restitution", "0.2"}, "restitution"},
      {test::caseFile("one_particle"), {"--seed", "7"}, "seed"},  // no star (star_particles alone: star_mass missing)
  };
  int k = 0;
  for (const Variant& v : variants) {
    BOOST_TEST_CONTEXT(v.key << " " << v.flags.back()) {
      std::vector<std::string> a{"run", v.caseFile, "--output", (dir / std::to_string(k++)).string(), "--end_time",
                                 "0.002"};
      a.insert(a.end(), v.flags.begin(), v.flags.end());
      const auto r = test::runSph(a);
      BOOST_TEST(r.exitCode == 0, r.output);
      BOOST_TEST(r.output.find("sph: warning: key '" + v.key + "' is not used") != std::string::npos, r.output);
    }
  }
  const auto clean = test::runSph({"run", test::caseFile("dam_break_seed"), "--output", (dir / "clean").string(),
                                   "--end_time", "0.002"});
  BOOST_TEST(clean.exitCode == 0);
  BOOST_TEST(clean.output.find("warning") == std::string::npos, clean.output);
}

// The bad-input catalogue of these features: each refused with exit 2 and
// one line naming the key or folder; nothing written, nothing removed.
BOOST_AUTO_TEST_CASE(bad_input_catalogue) {
  const auto dir = test::scratchDir("catalogue");
  const fs::path fresh = dir / "fresh";  // must never be created
  const fs::path empty = dir / "empty", others = dir / "others", done = dir / "done";
  fs::create_directories(empty);
  fs::create_directories(others);
  std::ofstream(others / "notes.txt") << "keep me\n";
  BOOST_TEST_REQUIRE(test::runSph({"run", test::caseFile("one_particle"), "--output", done.string(), "--end_time",
                                   "0.002", "--output_every", "10"})
                         .exitCode == 0);
  const std::string dam = test::caseFile("dam_break_seed");
  const fs::path bothFile = dir / "both.case";
  std::ofstream(bothFile) << "points = [0.5, 0.5]\noutput_every = 10\noutput_interval = 0.01\n";
  struct Refusal {
    std::vector<std::string> args;
    std::string expected;
  };
  const std::vector<Refusal> refusals{
      {{"run", "--resume", empty.string()}, "resume: " + empty.string() + " holds no run"},
      {{"run", "--resume", fresh.string()}, "resume: " + fresh.string() + " holds no run"},
      {{"run", "--resume", others.string()}, "resume: " + others.string() + " holds no run"},
      {{"run", dam, "--output", others.string(), "--overwrite"}, "overwrite: output folder " + others.string()},
      {{"run", dam, "--output", fresh.string(), "--output_every", "10", "--output_interval", "0.01"},
       "output_every and output_interval"},
      {{"run", bothFile.string(), "--output", fresh.string()}, "output_every and output_interval"},
      {{"run", dam, "--output", fresh.string(), "--output_interval", "0"}, "output_interval = 0 is out of range: it must be > 0"},
      {{"run", dam, "--output", fresh.string(), "--output_interval", "-1"}, "output_interval = -1 is out of range: it must be > 0"},
      {{"run", dam, "--output", fresh.string(), "--name", ".."}, "name = \"..\" is not allowed"},
      {{"run", dam, "--output", fresh.string(), "--name", "a/b"}, "name = \"a/b\" is not allowed"},
      {{"run", dam, "--output", fresh.string(), "--h", "1e-300"}, "h = 1e-300 is out of range"},
      {{"run", dam, "--output", fresh.string(), "--threads", "0"}, "threads = 0 is out of range"},
      {{"run", dam, "--output", fresh.string(), "--threads", "2000"}, "threads = 2000 is out of range"},
      {{"run", dam, "--output", fresh.string(), "--threads", "abc"}, "threads = abc is out of range"},
      {{"run", "--resume", done.string(), "--overwrite"}, "overwrite and resume"},
      {{"run", "--resume", done.string()}, "end_time = 0.002 s is not after the start"},
      {{"run", "--resume", done.string(), "--end_time", "0.004", "--output", fresh.string()}, "--output"},
      {{"run", "--resume", done.string(), "--end_time", "0.004", "--dt", "5e-5"}, "dt"},
      {{"run", "--resume", done.string(), "--end_time", "0.004", "--name", "other"}, "name"},
  };
  const auto before = std::map<std::string, std::map<std::string, std::string>>{
      {"empty", folderState(empty)}, {"others", folderState(others)}, {"done", folderState(done)}};
  for (const Refusal& f : refusals) {
    std::string line;
    for (const auto& a : f.args) line += a + " ";
    BOOST_TEST_CONTEXT("sph " << line) {
      expectOneLineError(test::runSph(f.args), f.expected);
      BOOST_TEST(!fs::exists(fresh));
      BOOST_TEST((folderState(empty) == before.at("empty")));
      BOOST_TEST((folderState(others) == before.at("others")));
      BOOST_TEST((folderState(done) == before.at("done")));
    }
  }
}

// Misspelt keys of these features get a suggestion.
BOOST_AUTO_TEST_CASE(did_you_mean) {
  const auto dir = test::scratchDir("did_you_mean");
  const fs::path out = dir / "out";
  expectOneLineError(test::runSph({"run", test::caseFile("dam_break_seed"), "--output", out.string(), "--resme", "x"}),
                     "unknown key 'resme' (on the command line); did you mean 'resume'?");
  expectOneLineError(
      test::runSph({"run", test::caseFile("dam_break_seed"), "--output", out.string(), "--output_intervl", "0.1"}),
      "did you mean 'output_interval'?");
  expectOneLineError(test::runSph({"run", test::caseFile("dam_break_seed"), "--output", out.string(), "--overwite"}),
                     "did you mean 'overwrite'?");
  const fs::path file = dir / "typo.case";
  std::ofstream(file) << "points = [0.5, 0.5]\noutput_intervall = 0.1\n";
  expectOneLineError(test::runSph({"run", file.string(), "--output", out.string()}),
                     "unknown key 'output_intervall' (case file " + file.string() +
                         " line 2); did you mean 'output_interval'?");
  BOOST_TEST(!fs::exists(out));
}

BOOST_AUTO_TEST_SUITE_END()
