// sph: the command line. Every case-file key is declared here once, with its
// unit, default and allowed range; CLI11 reads the case file (TOML-style
// `key = value`) and lets any flag override it. This is the only translation
// unit that includes CLI11, and the only place that picks the dimension D.
#include "sph/case_config.hpp"
#include "sph/run_case.hpp"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>

namespace {

const char* kTopHelp =
    "sph: Smoothed-Particle Hydrodynamics for ParaView workflows.\n"
    "Usage: sph run CASE_FILE [--output DIR] [--KEY VALUE ...]\n"
    "Every key of a case file is also a flag that overrides it.";

void declareKeys(CLI::App& run, sph::CaseConfig& c) {
  auto real = [&](const char* flag, sph::Real& v, const char* help) {
    run.add_option(flag, v, help)->capture_default_str()->group("Physics and numerics");
  };
  run.add_option("--output", c.output, "Output folder [default: runs/<name>]")->group("Run");
  run.add_option("--name", c.name, "Run name: <name>.pvd, <name>_NNNNN.vtp "
                 "[letters, digits, _ - .; default: case file name]")->group("Run");
  run.add_option("--model", c.model, "Physics model [seed_wcsph | wcsph]")->capture_default_str()->group("Run");
  run.add_option("--dimension", c.dimension, "Spatial dimension [2 or 3]")->capture_default_str()->group("Run");
  run.add_option("--threads", c.threads, "OpenMP threads [>= 0; 0: all cores]")->capture_default_str()->group("Run");
  run.add_flag("--progress,!--no-progress", c.progress, "Progress line on a terminal")->capture_default_str()->group("Run");

  real("--h", c.h, "Support radius h [m; > 0]");
  real("--k", c.k, "EOS stiffness k in p = k (rho - rho0) [> 0]");
  real("--rho0", c.rho0, "Rest density rho0 [kg/m^D; > 0]");
  real("--mu", c.mu, "Dynamic viscosity mu [>= 0; 0 switches viscosity off]");
  real("--g", c.g, "Gravity g along -y (2D) or -z (3D) [m/s^2; 0 switches gravity off]");
  real("--restitution", c.restitution, "Wall restitution e: normal velocity -> -e times itself [0 to 1]");
  run.add_flag("--walls,!--no-walls", c.walls, "Damped reflecting walls on the domain box")
      ->capture_default_str()->group("Physics and numerics");
  auto choice = [&](const char* flag, std::string& v, const char* help) {
    run.add_option(flag, v, help)->group("wcsph model");
  };
  choice("--kernel", c.kernel, "Kernel [cubic_spline (default) | wendland_c2 | gaussian | muller]");
  choice("--eos", c.eos, "Equation of state [linear (default) | linear_clamped | tait | polytropic]");
  choice("--viscosity", c.viscosity, "Viscosity [laplacian (default, uses mu) | monaghan | none]");
  auto wreal = [&](const char* flag, sph::Real& v, const char* help) {
    run.add_option(flag, v, help)->capture_default_str()->group("wcsph model");
  };
  wreal("--gamma", c.gamma, "Tait exponent [> 0]");
  wreal("--c0", c.c0, "Tait sound speed [m/s; > 0 with eos = tait]");
  wreal("--polytropic_index", c.polytropicIndex, "n in p = k rho^(1 + 1/n) [> 0]");
  wreal("--alpha", c.alpha, "Monaghan viscosity alpha [>= 0]");
  wreal("--beta", c.beta, "Monaghan viscosity beta [>= 0]");
  wreal("--xsph", c.xsph, "XSPH epsilon [0 to 1; 0: off]");
  wreal("--damping", c.damping, "Linear damping nu in a = -nu v [1/s; >= 0; 0: off]");
  wreal("--star_mass", c.starMass, "Toy star mass M [> 0; 0: no star]");
  wreal("--star_radius", c.starRadius, "Toy star radius R [m; > 0]");
  run.add_option("--star_particles", c.starParticles, "Particles per star [>= 1 each]")->group("wcsph model");
  run.add_option("--star_center", c.starCenter, "Star centres [m; D values per star] (the attraction -lambda x always pulls to the origin)")->group("wcsph model");
  run.add_option("--star_velocity", c.starVelocity, "Star velocities [m/s; D values per star]")->group("wcsph model");
  run.add_option("--seed", c.seed, "Random seed of the star particles")->capture_default_str()->group("wcsph model");
  run.add_option("--integrator", c.integrator, "Time integrator [leap_frog (default) | symplectic_euler | rk4 | euler]")
      ->group("Physics and numerics");
  real("--cfl", c.cfl, "Adaptive dt with this CFL factor (dt is then the largest step) [0 to 2; 0: fixed dt]");
  real("--dt", c.dt, "Time step [s; > 0]");
  real("--end_time", c.endTime, "Simulated time [s; > 0]");
  run.add_option("--output_every", c.outputEvery, "Write a snapshot every N steps (and the last) [>= 1]")
      ->capture_default_str()->group("Physics and numerics");

  auto vec = [&](const char* flag, std::vector<sph::Real>& v, const char* help) {
    run.add_option(flag, v, help)->group("Domain and particles");
  };
  vec("--domain_min", c.domainMin, "Lower domain corner, walls [m; D values; default 0 0]");
  vec("--domain_max", c.domainMax, "Upper domain corner, walls [m; D values; > domain_min + 2h; default 1 1]");
  vec("--block_min", c.blockMin, "Lattice block lower corner [m; D values]");
  vec("--block_max", c.blockMax, "Lattice block upper corner [m; D values]");
  vec("--disc_center", c.discCenter, "Lattice disc (2D) or ball (3D) centre [m; D values]");
  vec("--velocity", c.velocity, "Initial velocity of generated particles [m/s; D values; default 0]");
  run.add_option("--disc_radius", c.discRadius, "Disc/ball radius [m; > 0]")->group("Domain and particles");
  run.add_option("--spacing", c.spacing, "Lattice spacing dx of block and disc [m; > 0]")
      ->group("Domain and particles");
  run.add_option("--points", c.points, "Explicit particles: x y [z] per point [m]")->group("Domain and particles");
  run.add_option("--particle_file", c.particleFile,
                 "Particles from a CSV (header x,y[,z][,vx,vy[,vz]]) or a .vtp written by sph")
      ->group("Domain and particles");
}

// CLI11's messages, reworded where they would not name the key or file.
std::string explain(const CLI::ParseError& e, const CLI::App& run) {
  const std::string what = e.what();
  const std::string extra = "INI was not able to parse ";
  const std::string caseFile = run.get_config_ptr()->count() ? run.get_config_ptr()->as<std::string>() : "";
  if (what.rfind(extra, 0) == 0)
    return "case file " + caseFile + ": unknown key '" + what.substr(extra.size()) +
           "' ('sph run --help' lists the keys)";
  if (what.find("no specified config file") != std::string::npos)
    return "sph run needs a case file: sph run CASE_FILE [--output DIR] [--KEY VALUE ...]";
  if (dynamic_cast<const CLI::ConversionError*>(&e))
    return what + " is not a valid value ('sph run --help' gives each key's type and range)";
  if (dynamic_cast<const CLI::FileError*>(&e))
    return "case file " + caseFile + " cannot be read (missing or not a file)";
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
  declareKeys(run, c);
  try {
    run.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return run.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "sph: error: " << explain(e, run) << "\n";
    return sph::kBadInput;
  }
  c.caseFile = run.get_config_ptr()->as<std::string>();
  if (run.count("--name") == 0) c.name = std::filesystem::path(c.caseFile).stem().string();
  if (c.output.empty()) c.output = (std::filesystem::path("runs") / c.name).string();
  if (c.dimension == 3) return sph::runCase<3>(c, std::cout, std::cerr);
  if (c.dimension == 2) return sph::runCase<2>(c, std::cout, std::cerr);
  std::cerr << "sph: error: dimension = " << c.dimension << " is out of range: it must be 2 or 3\n";
  return sph::kBadInput;
}

std::string runHelp() {
  sph::CaseConfig c;
  CLI::App run("Run a case file. Every key of the case file is also a flag that overrides it.",
               "sph run");
  run.set_config("case_file", "", "Case file to run (see cases/)", true);
  declareKeys(run, c);
  return run.help();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == "run") return runCommand(argc - 1, argv + 1);
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
    std::cerr << "sph: error: " << e.what() << "\n";
    return sph::kBadInput;
  }
  std::cout << kTopHelp << "\n\n" << runHelp();
  return help ? 0 : sph::kBadInput;
}
