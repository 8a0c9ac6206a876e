// sph-bench: throughput of the seed scheme's dam break.
//
// Prints particle-steps per second (median of several repeats) for a dam
// break of about N particles at a given h/dx, with 1 and 2 threads, plus the
// mean neighbours per particle and the memory per particle. Not a test: it
// prints figures and asserts nothing.
//
//   sph-bench [--n 10000,100000] [--hdx 1.35,2.5] [--steps 200] [--repeats 5]
//             [--threads 1,2]
#include "sph/particle_sources.hpp"
#include "sph/scene.hpp"

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

long residentKiB() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
  return 0;
}

double loadAverage() {
  std::ifstream in("/proc/loadavg");
  double l = 0;
  in >> l;
  return l;
}

// Dam break column a wide, 2a high in a box 4a x 2.5a; dx from N.
sph::CaseConfig damBreak(double n, double hdx) {
  sph::CaseConfig c;
  const double a = 1.0;
  const double dx = a * std::sqrt(2.0 / n);
  c.h = hdx * dx;
  c.spacing = dx;
  c.domainMin = {0, 0};
  c.domainMax = {4 * a, 2.5 * a};
  c.blockMin = {c.h, c.h};
  c.blockMax = {c.h + a, c.h + 2 * a};
  // Keep the seed scheme's wave speed per h: dt scales with h.
  c.dt = 1e-4 * c.h / 0.01;
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> ns{10000, 100000}, hdxs{1.35, 2.5}, threads{1, 2};
  int steps = 200, repeats = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--n")) ns = parseList(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--hdx")) hdxs = parseList(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--threads")) threads = parseList(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--steps")) steps = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--repeats")) repeats = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "sph-bench: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  std::printf("# seed_wcsph dam break, 2D, %d steps per repeat, median of %d repeats\n", steps,
              repeats);
  std::printf("# load average before: %.2f on %d cores\n", loadAverage(), omp_get_num_procs());
  std::printf("%10s %6s %7s %8s %14s %14s %9s %10s\n", "N", "h/dx", "threads", "nbrs",
              "median p-s/s", "min..max", "speedup", "bytes/p");
  for (double nTarget : ns) {
    for (double hdx : hdxs) {
      const sph::CaseConfig c = damBreak(nTarget, hdx);
      double oneThread = 0;
      for (double t : threads) {
        omp_set_num_threads(static_cast<int>(t));
        std::vector<double> rates;
        double nbrs = 0, bytes = 0;
        std::size_t n = 0;
        for (int r = 0; r < repeats; ++r) {
          const long rss0 = residentKiB();
          auto init = sph::buildInitialState<2>(c);
          n = init.particles.size();
          const sph::Vec<2> lo(c.domainMin[0], c.domainMin[1]), hi(c.domainMax[0], c.domainMax[1]);
          sph::Scene<2> scene(std::move(init.particles),
                              sph::SeedWcsph<2>({c.h, c.k, c.rho0, c.mu, c.g}),
                              sph::DampedReflectingWalls<2>{lo, hi, c.h, c.restitution},
                              sph::StateCheck<2>{lo, hi}, sph::TimeStepControl{c.dt});
          scene.initialise(true);
          scene.step();  // warm-up: first-touch, grid table
          const auto t0 = std::chrono::steady_clock::now();
          for (int s = 0; s < steps; ++s)
            if (scene.step()) {
              std::fprintf(stderr, "sph-bench: the run blew up at step %d (N %zu, h/dx %g)\n", s, n, hdx);
              break;
            }
          const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          rates.push_back(static_cast<double>(n) * steps / sec);
          nbrs = scene.meanNeighbours();
          bytes = static_cast<double>(scene.bytesAllocated()) / static_cast<double>(n);
          (void)rss0;
        }
        const double med = median(rates);
        if (t == threads.front()) oneThread = med;
        char range[40];
        std::snprintf(range, sizeof range, "%.3g..%.3g", *std::min_element(rates.begin(), rates.end()),
                      *std::max_element(rates.begin(), rates.end()));
        std::printf("%10zu %6.2f %7d %8.1f %14.4g %14s %9.2f %10.0f\n", n, hdx, static_cast<int>(t),
                    nbrs, med, range, med / oneThread, bytes);
        std::fflush(stdout);
      }
    }
  }
  std::printf("# load average after: %.2f\n", loadAverage());
  return 0;
}
