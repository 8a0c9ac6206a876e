// sph-bench: throughput of the shipped models, printed, never asserted.
//
// For each scenario: particle-steps per second (median of several repeats,
// with min..max), neighbours per particle, bytes per particle (capacities of
// every particle, grid and neighbour-list array), for 1 and 2 threads, and
// the machine's load average before and after.
//
//   sph-bench [--suite seed|water|kernels|3d|star|all] [--n 10000,100000]
//             [--hdx 1.35,2.5] [--steps 200] [--repeats 5] [--threads 1,2]
//             [--integrator leap_frog]
//
// Suites: seed    the seed scheme's dam break (2D) at the given N and h/dx;
//         water   the wall-particle dam break (2D; dummy and dynamic walls,
//                 continuity density, delta-SPH, Wendland at h/dx 1.3: ~20
//                 neighbours) at the given N of fluid particles, with
//                 --integrator (leap_frog; two_step_leap_frog: one
//                 neighbour walk per step);
//         kernels the wcsph dam break (2D, Tait, Laplacian viscosity) with
//                 each kernel at its usual support (~20 neighbours);
//         3d      the wcsph dam break in 3D (cubic spline);
//         star    the toy star in 2D and 3D (polytropic, cubic spline).
#include "sph/model_registry.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using sph::CaseConfig;
using sph::Real;

std::vector<double> parseList(const char* s) {
  std::vector<double> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::stod(item));
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double loadAverage() {
  std::ifstream in("/proc/loadavg");
  double l = 0;
  in >> l;
  return l;
}

struct Scenario {
  std::string label;
  CaseConfig c;
};

// Dam break, column a wide and 2a high in a box 4a x 2.5a (x 1a deep in 3D),
// spacing from N; kernelHdx = h/dx.
CaseConfig damBreak(int dim, double n, double kernelHdx, const std::string& model,
                    const std::string& kernel) {
  CaseConfig c;
  c.model = model;
  c.dimension = dim;
  const double a = 1.0;
  const double dx = dim == 2 ? a * std::sqrt(2.0 / n) : a * std::cbrt(2.0 / n);
  c.h = kernelHdx * dx;
  c.spacing = dx;
  c.domainMin.assign(static_cast<std::size_t>(dim), 0);
  c.domainMax = {4 * a, 2.5 * a};
  c.blockMin.assign(static_cast<std::size_t>(dim), c.h);
  c.blockMax = {c.h + a, c.h + 2 * a};
  if (dim == 3) {
    // z is up in 3D: the column is a x a wide, 2a high.
    c.domainMax = {4 * a, a + 2 * c.h, 2.5 * a};
    c.blockMax = {c.h + a, c.h + a, c.h + 2 * a};
  }
  if (model == "seed_wcsph") {
    c.dt = 1e-4 * c.h / 0.01;  // the seed's wave speed per h
  } else {
    c.kernel = kernel;
    c.eos = "tait";
    c.c0 = 10 * std::sqrt(2 * 9.81 * 2 * a);  // 10x the largest flow speed
    c.viscosity = "laplacian";
    c.mu = 1e-3 * c.rho0 * c.h;               // small, keeps the run tidy
    c.dt = 0.2 * c.h / c.c0;
  }
  return c;
}

// The wall-particle dam break (dam_break_mm.case's physics): column a wide,
// 2a high against the left wall of a tank 4a x 2.5a, Wendland C2 at h/dx,
// Tait, continuity density with delta-SPH, Monaghan viscosity, wall
// particles of the given treatment.
CaseConfig waterDamBreak(double n, double hdx, const std::string& boundary, const std::string& integrator) {
  CaseConfig c;
  c.model = "wcsph";
  c.dimension = 2;
  const double a = 1.0, dx = a * std::sqrt(2.0 / n);
  c.h = hdx * dx;
  c.spacing = dx;
  c.kernel = "wendland_c2";
  c.eos = "tait";
  c.c0 = 10 * 2 * std::sqrt(9.81 * 2 * a);  // 10 x the surge speed
  c.density = "continuity";
  c.delta = 0.1;
  c.viscosity = "monaghan";
  c.alpha = 0.02;
  c.beta = 0;
  c.boundary = boundary;
  c.negativePressure = "clamp";
  c.hydrostaticStart = true;
  c.domainMin = {0, 0};
  c.domainMax = {4 * a, 2.5 * a};
  c.blockMin = {0, 0};
  c.blockMax = {a, 2 * a};
  c.dt = 0.15 * c.h / c.c0;
  c.integrator = integrator;
  return c;
}

CaseConfig toyStar(int dim, long n) {
  CaseConfig c;
  c.model = "wcsph";
  c.dimension = dim;
  c.kernel = "cubic_spline";
  c.eos = "polytropic";
  c.k = 0.1;
  c.viscosity = "none";
  c.termKeys.reals["damping"] = 1;
  c.g = 0;
  c.walls = false;
  c.starMass = 2;
  c.starRadius = 0.75;
  c.starParticles = {n};
  c.starCenter.assign(static_cast<std::size_t>(dim), 0);
  c.domainMin.assign(static_cast<std::size_t>(dim), -3);
  c.domainMax.assign(static_cast<std::size_t>(dim), 3);
  // ~40 neighbours in 2D, ~45 in 3D: h from the mean spacing.
  const double volume = dim == 2 ? M_PI * 0.75 * 0.75 : 4.0 / 3 * M_PI * std::pow(0.75, 3);
  const double dx = std::pow(volume / static_cast<double>(n), 1.0 / dim);
  c.h = (dim == 2 ? 1.5 : 1.2) * dx;
  c.dt = 0.02 * c.h / 0.1;
  return c;
}

template <int D>
void runScenario(const Scenario& sc, const std::vector<double>& threads, int steps, int repeats) {
  double oneThread = 0;
  for (double t : threads) {
    omp_set_num_threads(static_cast<int>(t));
    std::vector<double> rates;
    double nbrs = 0, bytes = 0;
    std::size_t n = 0;
    for (int r = 0; r < repeats; ++r) {
      sph::validateCase(sc.c);
      const sph::ResolvedCase c = sph::withDefaults(sc.c);
      auto init = sph::buildInitialState<D>(c);
      const bool scale = !init.massesGiven;
      n = init.particles.size();
      sph::Scene<D> scene = sph::makeScene<D>(c, std::move(init));
      scene.initialise(scale);
      scene.step();  // warm-up: first touch, grid table, neighbour buffers
      const auto t0 = std::chrono::steady_clock::now();
      int done = 0;
      for (; done < steps; ++done)
        if (scene.step()) {
          std::fprintf(stderr, "sph-bench: %s blew up at step %d\n", sc.label.c_str(), done);
          break;
        }
      const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      rates.push_back(static_cast<double>(n) * done / sec);
      nbrs = scene.meanNeighbours();
      bytes = static_cast<double>(scene.bytesAllocated()) / static_cast<double>(n);
    }
    const double med = median(rates);
    if (t == threads.front()) oneThread = med;
    char range[40];
    std::snprintf(range, sizeof range, "%.3g..%.3g", *std::min_element(rates.begin(), rates.end()),
                  *std::max_element(rates.begin(), rates.end()));
    std::printf("%-34s %2dD %8zu %7d %6.1f %12.4g %18s %7.2f %8.0f\n", sc.label.c_str(), D, n,
                static_cast<int>(t), nbrs, med, range, med / oneThread, bytes);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> ns{10000, 100000}, hdxs{1.35, 2.5}, threads{1, 2};
  std::string suite = "all", integrator = "leap_frog";
  int steps = 200, repeats = 5;
  const char* usage =
      "usage: sph-bench [--suite seed|water|kernels|3d|star|all] [--n 10000,100000]\n"
      "                 [--hdx 1.35,2.5] [--steps 200] [--repeats 5] [--threads 1,2]\n"
      "                 [--integrator leap_frog|two_step_leap_frog] (the water suite's)\n";
  for (int i = 1; i < argc; i += 2) {
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
      std::fputs(usage, stdout);
      return 0;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "sph-bench: option %s needs a value\n%s", argv[i], usage);
      return 2;
    }
    if (!std::strcmp(argv[i], "--n")) ns = parseList(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--hdx")) hdxs = parseList(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--threads")) threads = parseList(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--steps")) steps = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--repeats")) repeats = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--suite")) suite = argv[i + 1];
    else if (!std::strcmp(argv[i], "--integrator")) integrator = argv[i + 1];
    else {
      std::fprintf(stderr, "sph-bench: unknown option %s\n%s", argv[i], usage);
      return 2;
    }
  }
  std::vector<Scenario> s2, s3;
  const bool all = suite == "all";
  if (!all && suite != "seed" && suite != "kernels" && suite != "water" && suite != "3d" && suite != "star") {
    std::fprintf(stderr, "sph-bench: --suite %s is not one of seed, water, kernels, 3d, star, all\n", suite.c_str());
    return 2;
  }
  if (all || suite == "seed")
    for (double n : ns)
      for (double hdx : hdxs) {
        char label[64];
        std::snprintf(label, sizeof label, "seed dam break h/dx=%.2f", hdx);
        s2.push_back({label, damBreak(2, n, hdx, "seed_wcsph", "")});
      }
  if (all || suite == "kernels") {
    // Usual supports: cubic/Wendland 2h with h = 1.3 dx, Gaussian 3h with
    // h = 1.0 dx, Mueller h = 2.6 dx.
    const std::pair<const char*, double> kernels[] = {
        {"cubic_spline", 1.3}, {"wendland_c2", 1.3}, {"gaussian", 1.0}, {"muller", 2.6}};
    for (const auto& [k, hdx] : kernels)
      s2.push_back({std::string("wcsph dam break ") + k, damBreak(2, ns.front(), hdx, "wcsph", k)});
  }
  if (all || suite == "water")
    for (double n : ns)
      for (const char* boundary : {"dummy", "dynamic"}) {
        char label[64];
        std::snprintf(label, sizeof label, "water %s h/dx=1.3", boundary);
        s2.push_back({label, waterDamBreak(n, 1.3, boundary, integrator)});
      }
  if (all || suite == "3d") s3.push_back({"wcsph dam break cubic_spline", damBreak(3, 50000, 1.3, "wcsph", "cubic_spline")});
  if (all || suite == "star") {
    s2.push_back({"toy star", toyStar(2, 2000)});
    s3.push_back({"toy star", toyStar(3, 10000)});
  }
  std::printf("# sph-bench: %d steps per repeat, median of %d repeats; p-s/s = particle-steps per second\n",
              steps, repeats);
  std::printf("# load average before: %.2f on %d cores\n", loadAverage(), omp_get_num_procs());
  std::printf("%-34s %3s %8s %7s %6s %12s %18s %7s %8s\n", "scenario", "dim", "N", "threads", "nbrs",
              "median p-s/s", "min..max", "speedup", "bytes/p");
  for (const auto& sc : s2) runScenario<2>(sc, threads, steps, repeats);
  for (const auto& sc : s3) runScenario<3>(sc, threads, steps, repeats);
  std::printf("# load average after: %.2f\n", loadAverage());
  return 0;
}
