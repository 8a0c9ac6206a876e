// sph: the command line. Every case-file key is declared here once, with its
// unit, default and allowed range; CLI11 reads the case file (TOML-style
// `key = value`) and lets any flag override it. This is the only translation
// unit that includes CLI11, and the only place that picks the dimension D.
// Case files are read by sph's own strict reader (sph/case_file.hpp), which
// CLI11 calls through the config-formatter hook (CaseFileFormat below).
#include "sph/case_config.hpp"
#include "sph/case_file.hpp"
#include "sph/run_case.hpp"

#include <CLI/CLI.hpp>

#include <cctype>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

namespace {

const char* kTopHelp =
    "sph: Smoothed-Particle Hydrodynamics for ParaView workflows.\n"
    "Usage: sph run CASE_FILE [--output DIR] [--KEY VALUE ...]\n"
    "Every key of a case file is also a flag that overrides it.";

void declareKeys(CLI::App& run, sph::CaseConfig& c) {
  // One line per key: group, flag, field, "meaning [unit; allowed range]".
  auto key = [&](const char* group, const char* flag, auto& field, const char* help) {
    run.add_option(flag, field, help)->capture_default_str()->group(group);
  };
  auto flag = [&](const char* group, const char* names, bool& field, const char* help) {
    run.add_flag(names, field, help)->capture_default_str()->group(group);
  };
  const char* runGroup = "Run";
  key(runGroup, "--output", c.output, "Output folder [default: runs/<name>]");
  key(runGroup, "--name", c.name, "Run name: <name>.pvd, <name>_NNNNN.vtp [letters, digits, _ - .; default: case file name]");
  key(runGroup, "--model", c.model, "Physics model [seed_wcsph | wcsph]");
  key(runGroup, "--dimension", c.dimension, "Spatial dimension [2 or 3]");
  key(runGroup, "--threads", c.threads, "OpenMP threads [0 to 1024; 0: all cores]");
  flag(runGroup, "--progress,!--no-progress", c.progress, "Progress line on a terminal");

  const char* physics = "Physics and numerics";
  key(physics, "--h", c.h, "Smoothing length h [m; > 0]: the seed scheme's support radius; kernel support "
                           "is 2h (cubic, Wendland), 3h (Gaussian), h (Mueller)");
  key(physics, "--k", c.k, "EOS stiffness k: p = k (rho - rho0), or k rho^(1+1/n) polytropic [> 0]");
  key(physics, "--rho0", c.rho0, "Rest density rho0 [kg/m^D; > 0]");
  key(physics, "--mu", c.mu, "Dynamic viscosity mu [>= 0; 0 switches viscosity off]");
  key(physics, "--g", c.g, "Gravity g along -y (2D) or -z (3D) [m/s^2; 0 switches gravity off]");
  key(physics, "--restitution", c.restitution, "Wall restitution e: normal velocity -> -e times itself [0 to 1]");
  flag(physics, "--walls,!--no-walls", c.walls, "Damped reflecting walls on the domain box");
  key(physics, "--integrator", c.integrator, "Time integrator [leap_frog (default) | symplectic_euler | rk4 | euler]");
  key(physics, "--cfl", c.cfl, "Adaptive dt with this CFL factor (dt is then the largest step) [0 to 2; 0: fixed dt]");
  key(physics, "--dt", c.dt, "Time step [s; > 0]");
  key(physics, "--end_time", c.endTime, "Simulated time [s; > 0]");
  key(physics, "--output_every", c.outputEvery, "Write a snapshot every N steps (and the last) [>= 1]");

  const char* wcsph = "wcsph model";
  key(wcsph, "--kernel", c.kernel, "Kernel [cubic_spline (default) | wendland_c2 | gaussian | muller]");
  key(wcsph, "--eos", c.eos, "Equation of state [linear (default) | linear_clamped | tait | polytropic]");
  key(wcsph, "--viscosity", c.viscosity, "Viscosity [laplacian (default, uses mu) | monaghan | none]");
  key(wcsph, "--gamma", c.gamma, "Tait exponent [> 0]");
  key(wcsph, "--c0", c.c0, "Tait sound speed [m/s; > 0 with eos = tait]");
  key(wcsph, "--polytropic_index", c.polytropicIndex, "n in p = k rho^(1 + 1/n) [> 0]");
  key(wcsph, "--alpha", c.alpha, "Monaghan viscosity alpha [>= 0]");
  key(wcsph, "--beta", c.beta, "Monaghan viscosity beta [>= 0]");
  key(wcsph, "--xsph", c.xsph, "XSPH epsilon [0 to 1; 0: off]");
  key(wcsph, "--damping", c.damping, "Linear damping nu in a = -nu v [1/s; >= 0; 0: off]");
  key(wcsph, "--star_mass", c.starMass, "Toy star mass M [> 0; 0: no star]");
  key(wcsph, "--star_radius", c.starRadius, "Toy star radius R [m; > 0]");
  key(wcsph, "--star_particles", c.starParticles, "Particles per star [>= 1 each]");
  key(wcsph, "--star_center", c.starCenter, "Star centres [m; D values per star] (the attraction -lambda x always pulls to the origin)");
  key(wcsph, "--star_velocity", c.starVelocity, "Star velocities [m/s; D values per star]");
  key(wcsph, "--seed", c.seed, "Random seed of the star particles");

  const char* particles = "Domain and particles";
  key(particles, "--domain_min", c.domainMin, "Lower domain corner, walls [m; D values]");
  key(particles, "--domain_max", c.domainMax, "Upper domain corner, walls [m; D values; > domain_min + 2h]");
  key(particles, "--block_min", c.blockMin, "Lattice block lower corner [m; D values]");
  key(particles, "--block_max", c.blockMax, "Lattice block upper corner [m; D values]");
  key(particles, "--disc_center", c.discCenter, "Lattice disc (2D) or ball (3D) centre [m; D values]");
  key(particles, "--disc_radius", c.discRadius, "Disc/ball radius [m; > 0]");
  key(particles, "--spacing", c.spacing, "Lattice spacing dx of block and disc [m; > 0]");
  key(particles, "--velocity", c.velocity, "Initial velocity of generated particles [m/s; D values; default 0]");
  key(particles, "--points", c.points, "Explicit particles: x y [z] per point [m]");
  key(particles, "--particle_file", c.particleFile,
      "Particles from a CSV (header x,y[,z][,vx,vy[,vz]]) or a .vtp written by sph");
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

// `sph run ...` is parsed by an App of its own: CLI11 reads config files for
// the top-level App only, and the case file is that App's config file.
int runCommand(int argc, char** argv) {
  sph::CaseConfig c;
  CLI::App run("Run a case file. Every key of the case file is also a flag that overrides it.",
               "sph run");
  run.set_config("case_file", "", "Case file to run (see cases/)", true);
  run.allow_config_extras(CLI::config_extras_mode::error);
  const auto format = std::make_shared<CaseFileFormat>();
  run.config_formatter(format);
  declareKeys(run, c);
  try {
    run.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return run.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(explain(e, run, *format));
  } catch (const sph::CaseFileError& e) {
    const std::string line = e.line() ? " line " + std::to_string(e.line()) : "";
    return fail("case file " + run.get_config_ptr()->as<std::string>() + line + ": " + e.what());
  }
  c.caseFile = run.get_config_ptr()->as<std::string>();
  if (run.count("--name") == 0) c.name = sph::defaultRunName(c.caseFile);
  if (c.output.empty()) c.output = (std::filesystem::path("runs") / c.name).string();
  if (c.dimension == 3) return sph::runCase<3>(c, std::cout, std::cerr);
  if (c.dimension == 2) return sph::runCase<2>(c, std::cout, std::cerr);
  return fail("dimension = " + std::to_string(c.dimension) + " is out of range: it must be 2 or 3");
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
  return fail("unknown subcommand '" + first + "': the subcommand is 'run': " +
              "sph run CASE_FILE [--output DIR] [--KEY VALUE ...] ('sph --help' lists the keys)");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == "run") return runCommand(argc - 1, argv + 1);
  if (argc >= 2 && argv[1][0] != '-') return missingSubcommand(argc, argv);
  CLI::App app(kTopHelp, "sph");
  app.set_version_flag("--version", std::string("sph ") + SPH_VERSION);
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
