// sph: the command line. Every case-file key is declared here once, with its
// unit, default and allowed range; CLI11 reads the case file (TOML-style
// `key = value`) and lets any flag override it. This is the only translation
// unit that includes CLI11, and the only place that picks the dimension D.
// Case files are read by sph's own strict reader (sph/case_file.hpp), which
// CLI11 calls through the config-formatter hook (CaseFileFormat below).
#include "sph/case_config.hpp"
#include "sph/case_file.hpp"
#include "sph/case_keys.hpp"
#include "sph/io/run_folder.hpp"
#include "sph/mpi/session.hpp"
#include "sph/run_case.hpp"
#include "sph/case_check.hpp"
#include "sph/study.hpp"

#include <CLI/CLI.hpp>

#include <cctype>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <variant>

namespace {

const char* kTopHelp =
    "sph: Smoothed-Particle Hydrodynamics for ParaView workflows.\n"
    "Usage: sph run CASE_FILE [--output DIR] [--KEY VALUE ...]\n"
    "       sph check CASE_FILE [--KEY VALUE ...]   (what the case implies; nothing is run or written)\n"
    "       sph study STUDY_FILE [--output DIR] [--jobs N] [--tolerance X]\n"
    "       sph keys                                 (every key as Markdown: docs/keys.md)\n"
    "Every key of a case file is also a flag that overrides it.";

// One CLI11 option per row of the key table (case_keys.hpp), in its topic
// group; a bool key is a flag with a --no- form.
void declareKeys(CLI::App& run, sph::CaseConfig& c) {
  for (const sph::KeySpec& k : sph::caseKeys()) {
    const std::string flag = std::string("--") + k.name;
    const std::string help = sph::keyHelp(k);
    const std::string group = sph::groupName(k.group);
    std::visit(
        [&](auto member) {
          auto& field = sph::keyRef(c, member);
          using T = std::decay_t<decltype(field)>;
          CLI::Option* o;
          if constexpr (std::is_same_v<T, bool>)
            o = run.add_flag(flag + ",!--no-" + k.name, field, help);
          else
            o = run.add_option(flag, field, help);
          if (k.defaultText == nullptr) o->capture_default_str();
          o->group(group);
        },
        k.field);
  }
}

// The keys the case file or the command line set.
std::set<std::string> givenKeys(const CLI::App& run) {
  std::set<std::string> given;
  for (const sph::KeySpec& k : sph::caseKeys())
    if (run.count(std::string("--") + k.name) > 0) given.insert(k.name);
  return given;
}

// CLI11 reads the case file through this: sph's strict reader instead of
// CLI11's own (see sph/case_file.hpp for why). It remembers the line of each
// key for explain(); it cannot write case files.
class CaseFileFormat : public CLI::Config {
 public:
  std::string to_config(const CLI::App*, bool, bool, std::string) const override { return ""; }
  std::vector<CLI::ConfigItem> from_config(std::istream& in) const override {
    std::vector<CLI::ConfigItem> out;
    for (sph::CaseEntry& e : sph::readCaseFile(in)) {
      if (sph::isCommandLineOnlyKey(e.key))
        throw sph::CaseFileError(e.line, e.key + " is a command-line key (how one run is watched, not part of the "
                                         "case): give it as --" + e.key + " to sph run");
      lines_[e.key] = e.line;
      out.push_back(CLI::ConfigItem{{}, std::move(e.key), std::move(e.values)});
    }
    return out;
  }
  std::size_t lineOf(const std::string& key) const {
    const auto it = lines_.find(key);
    return it == lines_.end() ? 0 : it->second;
  }

 private:
  mutable std::map<std::string, std::size_t> lines_;
};

// The keys `run` declares (long flag names without dashes), for suggestions.
std::vector<std::string> knownKeys(const CLI::App& run) {
  std::vector<std::string> keys;
  for (const CLI::Option* o : run.get_options())
    if (o != run.get_config_ptr()) keys.insert(keys.end(), o->get_lnames().begin(), o->get_lnames().end());
  return keys;
}

// One line on stderr, control characters escaped; the bad-input exit status.
int fail(const std::string& message) {
  std::cerr << "sph: error: " << sph::escapeControl(message) << "\n";
  return sph::kBadInput;
}

// CLI11's messages, reworded where they would not name the key or file.
std::string explain(const CLI::ParseError& e, const CLI::App& run, const CaseFileFormat& format) {
  const std::string what = e.what();
  const std::string extra = "INI was not able to parse ";
  const std::string caseFile = run.get_config_ptr()->count() ? run.get_config_ptr()->as<std::string>() : "";
  if (what.rfind(extra, 0) == 0) {
    const std::string key = what.substr(extra.size());
    return sph::unknownKeyMessage(key, "case file " + caseFile + " line " + std::to_string(format.lineOf(key)),
                                  knownKeys(run));
  }
  // Arguments CLI11 did not take: the first unknown flag, else the first one.
  const std::vector<std::string> extras = run.remaining();
  for (const std::string& arg : extras) {
    if (arg == "--") break;  // the rest are positional
    if (arg.size() < 2 || arg[0] != '-' || std::isdigit(static_cast<unsigned char>(arg[1]))) continue;
    const std::string key = arg.substr(arg[1] == '-' ? 2 : 1);  // --key, --key=value, -k
    if (!key.empty() && key[0] != '=')
      return sph::unknownKeyMessage(key.substr(0, key.find('=')), "on the command line", knownKeys(run));
  }
  if (dynamic_cast<const CLI::ExtrasError*>(&e) && !extras.empty())
    return "unexpected argument '" + extras.front() + "': sph run takes one case file, then --KEY VALUE pairs";
  if (what.find("no specified config file") != std::string::npos)
    return "sph run needs a case file: sph run CASE_FILE [--output DIR] [--KEY VALUE ...]";
  if (dynamic_cast<const CLI::ConversionError*>(&e))
    return what + " is not a valid value ('sph run --help' gives each key's type and range)";
  if (dynamic_cast<const CLI::FileError*>(&e)) {
    std::error_code ec;
    if (std::filesystem::is_directory(caseFile, ec)) return "case file " + caseFile + " is a directory, not a case file";
    return "case file " + caseFile + " cannot be read (missing or not a file)";
  }
  return what;
}

// The keys given on the command line itself (--key, --key=value, --no-key).
std::set<std::string> commandLineKeys(int argc, char** argv) {
  std::set<std::string> keys;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--", 0) != 0) continue;
    a = a.substr(2, a.find('=') == std::string::npos ? std::string::npos : a.find('=') - 2);
    if (a.rfind("no-", 0) == 0 && sph::findKey(a.substr(3))) a = a.substr(3);
    if (sph::findKey(a)) keys.insert(a);
  }
  return keys;
}

// A flag overrides the case file, also across the two output keys: an
// output key on the command line replaces the other one of the file (or of
// the run a resume continues). Both on the command line stay an error.
void preferCommandLineOutputKey(sph::CaseConfig& c, const std::set<std::string>& flags) {
  const bool every = flags.count("output_every") > 0, interval = flags.count("output_interval") > 0;
  if (interval && !every) c.given.erase("output_every");
  if (every && !interval) {
    c.given.erase("output_interval");
    c.outputInterval = 0;
  }
}

// A resumed run continues the one in its folder: a flag that would change
// that run (its physics, dt, name, folder, ...) is refused, naming it.
std::string resumeRefusal(const std::set<std::string>& flags, const std::string& folder) {
  for (const std::string& key : flags) {
    if (key == "output")
      return "resume: --output does not go with --resume: the run continues in its own folder " + folder;
    if (key == "overwrite") return "overwrite and resume go against each other: give one";
    const sph::KeySpec* k = sph::findKey(key);
    if (sph::isResumeKey(key) || (k && sph::isRunOnlyKey(*k))) continue;
    return "resume: --" + key + " cannot change when a run is resumed (only " + sph::resumeKeysText() +
           " can); to change it, start a new run from a snapshot with --particle_file";
  }
  return "";
}

// The folder of --resume DIR (or --resume=DIR), "" without one.
std::string resumeFolder(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--resume" && i + 1 < argc) return argv[i + 1];
    if (a.rfind("--resume=", 0) == 0) return a.substr(9);
  }
  return "";
}

// Parses `sph SUB CASE_FILE [--KEY VALUE ...]` (args without "sph") into
// c: the case file is the App's config file, every key a flag. Returns -1
// when c is ready, else the exit code (help printed, or an error).
int parseCaseCommand(const std::string& title, const std::string& name, std::vector<std::string> args,
                     sph::CaseConfig& c) {
  std::vector<char*> argp;
  for (auto& a : args) argp.push_back(a.data());
  CLI::App app(title, name);
  app.set_config("case_file", "", "Case file to run (see cases/)", true);
  app.allow_config_extras(CLI::config_extras_mode::error);
  const auto format = std::make_shared<CaseFileFormat>();
  app.config_formatter(format);
  declareKeys(app, c);
  try {
    app.parse(static_cast<int>(argp.size()), argp.data());
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(explain(e, app, *format));
  } catch (const sph::CaseFileError& e) {
    const std::string line = e.line() ? " line " + std::to_string(e.line()) : "";
    return fail("case file " + app.get_config_ptr()->as<std::string>() + line + ": " + e.what());
  }
  c.caseFile = app.get_config_ptr()->as<std::string>();
  c.given = givenKeys(app);
  return -1;
}

// `sph run ...` is parsed by an App of its own: CLI11 reads config files for
// the top-level App only, and the case file is that App's config file.
// `sph run --resume DIR` takes DIR/run.case, the resolved case of that run,
// as its case file.
int runCommand(int argc, char** argv) {
  sph::CaseConfig c;
  const std::string resume = resumeFolder(argc, argv);
  std::vector<std::string> args(argv, argv + argc);
  if (!resume.empty()) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(std::filesystem::path(resume) / "run.json", ec))
      return fail("resume: " + resume + " holds no run to resume (no run.json)");
    args.insert(args.begin() + 1, (std::filesystem::path(resume) / "run.case").string());
  }
  const int parsed = parseCaseCommand("Run a case file. Every key of the case file is also a flag that overrides it.",
                                      "sph run", args, c);
  if (parsed >= 0) return parsed;
  if (resume.empty() && c.given.count("name") == 0) c.name = sph::defaultRunName(c.caseFile);
  const std::set<std::string> flags = commandLineKeys(argc, argv);
  if (!resume.empty()) {
    const std::string refusal = resumeRefusal(flags, resume);
    if (!refusal.empty()) return fail(refusal);
  }
  c.commandLine.assign(argv, argv + argc);
  c.commandLine.insert(c.commandLine.begin(), "sph");
  if (!resume.empty()) {
    // The run's own record says which keys its case set; flags add to them.
    try {
      const sph::RunRecord record = sph::readRunRecord(resume);
      c.given = std::set<std::string>(record.given.begin(), record.given.end());
      c.caseFile = record.caseFile;
    } catch (const std::exception& e) {
      return fail(std::string("resume: ") + e.what());
    }
    c.given.insert(flags.begin(), flags.end());
    c.given.erase("resume");
    c.output = resume;
    c.resume = resume;
  }
  preferCommandLineOutputKey(c, flags);
  if (c.output.empty()) c.output = (std::filesystem::path("runs") / c.name).string();
  if (c.dimension == 3) return sph::runCase<3>(c, std::cout, std::cerr);
  if (c.dimension == 2) return sph::runCase<2>(c, std::cout, std::cerr);
  return fail("dimension = " + std::to_string(c.dimension) + " is out of range: it must be 2 or 3");
}

// `sph check CASE_FILE [--KEY VALUE ...]`: what the case implies, without
// running it (sph/case_check.hpp).
int checkCommand(int argc, char** argv) {
  sph::CaseConfig c;
  const int parsed = parseCaseCommand("Check a case file: what it implies (particles, h/dx, neighbours, Mach number, dt "
                                      "against its limits, wall layers, memory, a time estimate) and where it lies "
                                      "outside a method's measured stable range. Nothing is written.",
                                      "sph check", std::vector<std::string>(argv, argv + argc), c);
  if (parsed >= 0) return parsed;
  if (c.given.count("name") == 0) c.name = sph::defaultRunName(c.caseFile);
  if (c.dimension == 3) return sph::checkCase<3>(c, std::cout, std::cerr);
  if (c.dimension == 2) return sph::checkCase<2>(c, std::cout, std::cerr);
  return fail("dimension = " + std::to_string(c.dimension) + " is out of range: it must be 2 or 3");
}

// `sph study STUDY_FILE [--output DIR] [--jobs N] [--tolerance X]`: a
// matrix of child `sph run`s (sph/study.hpp).
int studyCommand(int argc, char** argv) {
  CLI::App app("Run a study: reference cases x methods x resolutions, each a child 'sph run', then measure "
               "every run's error and cost (study.csv, a chart per case, report.md).",
               "sph study");
  std::string file, output;
  int jobs = 1;
  double tolerance = 0;
  app.add_option("study_file", file, "Study file (see studies/)")->required();
  app.add_option("--output", output, "Study folder [default runs/study_<name>]");
  app.add_option("--jobs", jobs, "Runs at once [1 to 64; default 1]")->check(CLI::Range(1, 64));
  app.add_option("--tolerance", tolerance, "Error the report asks for, replacing the study file's [> 0]")
      ->check(CLI::PositiveNumber);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    if (what.find("study_file is required") != std::string::npos)
      what = "sph study needs a study file: sph study STUDY_FILE [--output DIR] [--jobs N] [--tolerance X]";
    return fail(what);
  }
  try {
    const sph::Study s = sph::readStudyFile(file);
    sph::StudyOptions o;
    o.output = output;
    o.jobs = jobs;
    if (app.count("--tolerance")) o.tolerance = tolerance;
    return sph::runStudy(s, o, std::cout, std::cerr);
  } catch (const sph::CaseError& e) {
    return fail(e.what());
  }
}

std::string runHelp() {
  sph::CaseConfig c;
  CLI::App run("Run a case file. Every key of the case file is also a flag that overrides it.",
               "sph run");
  run.set_config("case_file", "", "Case file to run (see cases/)", true);
  declareKeys(run, c);
  return run.help();
}

// `sph X ...` where X is not a subcommand: most often a case file without `run`.
int missingSubcommand(int argc, char** argv) {
  const std::string first = argv[1];
  std::error_code ec;
  if (std::filesystem::path(first).extension() == ".case" || std::filesystem::is_regular_file(first, ec)) {
    std::string command = "sph run";
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      command += a.find(' ') == std::string::npos ? " " + a : " \"" + a + "\"";
    }
    return fail("missing subcommand: did you mean '" + command + "'?");
  }
  return fail("unknown subcommand '" + first + "': the subcommands are 'run', 'check', 'study' and 'keys': " +
              "sph run CASE_FILE [--output DIR] [--KEY VALUE ...] ('sph --help' lists the keys)");
}

// A stream buffer that drops what it is given (the output of ranks > 0).
class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return traits_type::not_eof(c); }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

}  // namespace

int main(int argc, char** argv) {
  // MPI only when a launcher started sph (mpi/session.hpp). `sph run` runs on
  // every rank (docs/developer/mpi.md); the other subcommands run on one.
  // Ranks other than 0 print nothing through std::cout and std::cerr (every
  // rank reaches the same messages); a failure of one rank alone is printed
  // with fprintf(stderr) by the code that finds it.
  sph::mpi::Session mpi(argc, argv);
  NullBuffer silent;
  std::streambuf* const coutBuffer = std::cout.rdbuf();
  std::streambuf* const cerrBuffer = std::cerr.rdbuf();
  if (mpi.rank() > 0) {
    std::cout.rdbuf(&silent);
    std::cerr.rdbuf(&silent);
  }
  struct Restore {  // before the buffer goes
    std::streambuf *out, *err;
    ~Restore() {
      std::cout.rdbuf(out);
      std::cerr.rdbuf(err);
    }
  } restore{coutBuffer, cerrBuffer};
  if (mpi.size() > 1 && !(argc >= 2 && std::string(argv[1]) == "run"))
    return fail(std::string("started on ") + std::to_string(mpi.size()) + " MPI ranks: only 'sph run' runs on " +
                "several; start 'sph " + (argc >= 2 ? argv[1] : "") + "' without mpirun (or with mpirun -n 1)");
  if (argc >= 2 && std::string(argv[1]) == "run") return runCommand(argc - 1, argv + 1);
  if (argc >= 2 && std::string(argv[1]) == "study") return studyCommand(argc - 1, argv + 1);
  if (argc >= 2 && std::string(argv[1]) == "check") return checkCommand(argc - 1, argv + 1);
  if (argc == 2 && std::string(argv[1]) == "keys") {
    std::cout << sph::keyReferenceMarkdown();
    return 0;
  }
  if (argc >= 2 && argv[1][0] != '-') return missingSubcommand(argc, argv);
  CLI::App app(kTopHelp, "sph");
  app.set_version_flag("--version", std::string("sph ") + SPH_VERSION + " (precision " + sph::kBuildPrecision + ")");
  app.set_help_flag();
  bool help = false;
  app.add_flag("-h,--help", help, "Print this help, with every case key, and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (dynamic_cast<const CLI::ExtrasError*>(&e) && !app.remaining().empty())
      return fail("unknown option '" + app.remaining().front() + "': sph --help, sph --version or " +
                  "sph run CASE_FILE [--output DIR] [--KEY VALUE ...]");
    return fail(e.what());
  }
  std::cout << kTopHelp << "\n\n" << runHelp();
  return help ? 0 : sph::kBadInput;
}
