// The seed scheme against an independent implementation of it, written here
// from the seed document alone (docs/methods/seed-model.md lists it; none of
// sph's physics code is called): the two-, three- and four-particle cases
// run by the real executable are compared, snapshot by snapshot, with the
// positions this file computes.
//
// The seed document (2D, support radius h, q = r / h < 1):
//   rho_i = sum_j m 4/(pi h^2) (1 - q^2)^3                    (j = i included)
//   p_i   = k (rho_i - rho0)
//   F_p,i = - sum_{j != i} m/rho_j (p_i + p_j)/2 (-30/(pi h^3)) r_ij (1 - q)^2 / q
//   F_v,i = - mu sum_{j != i} m/rho_j v_ij 40/(pi h^4) (1 - q)
//   F_g,i = (0, -rho_i g),   a_i = (F_p,i + F_v,i + F_g,i) / rho_i
//   v^{1/2} = v^0 + a^0 dt/2;  v^{t+1/2} = v^{t-1/2} + a^t dt;  x^{t+1} = x^t + v^{t+1/2} dt
//   m = N rho0 / sum_i rho_i (densities with m = 1), once at the start
//   walls: closer than h to a wall, x = (wall +- h), u_normal = -e u_normal.
// The leap-frog holds only v^{t-1/2}; which velocity v_ij the viscous term
// sees at step t >= 1 is the question (issue 21). Two readings:
//   half-step   v^{t-1/2}, the only velocity the scheme holds;
//   integer     v^{t-1/2} + a^{t-1} dt/2, an estimate of v^t (reflected by
//               the walls with the half-step velocity).
// Both are computed here; sph must match the one docs/methods/seed-model.md
// chose to round-off, and the two must differ by far more than that, so
// that the comparison can tell them apart.
#include "pvd_reader.hpp"
#include "stored_precision.hpp"
#include "cli_support.hpp"

#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace {

using P2 = std::array<double, 2>;

enum class ViscousVelocity { kHalfStep, kInteger };

// The seed scheme, straight from the document, for a handful of particles:
// all pairs, no neighbour search, no sorting.
struct SeedReference {
  double h = 0.01, k = 2000, rho0 = 1000, mu = 1, g = 9.81, e = 0.5, dt = 1e-4;
  P2 lo{0, 0}, hi{1, 1};
  ViscousVelocity reading = ViscousVelocity::kHalfStep;

  std::vector<P2> x, v, vHalf, vEstimate;
  std::vector<double> rho, p;
  double m = 1;
  long step = 0;

  void start(const std::vector<P2>& x0) {
    x = x0;
    v.assign(x.size(), P2{0, 0});
    vHalf = vEstimate = v;
    m = 1;
    density();
    double sum = 0;
    for (double r : rho) sum += r;
    m = static_cast<double>(x.size()) * rho0 / sum;
  }

  void density() {
    const double c = 4 / (M_PI * h * h);
    rho.assign(x.size(), 0);
    p.assign(x.size(), 0);
    for (std::size_t i = 0; i < x.size(); ++i) {
      for (std::size_t j = 0; j < x.size(); ++j) {
        const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1];
        const double q = std::sqrt(dx * dx + dy * dy) / h;
        if (q < 1) rho[i] += m * c * std::pow(1 - q * q, 3);
      }
      p[i] = k * (rho[i] - rho0);
    }
  }

  std::vector<P2> accelerations(const std::vector<P2>& vel) {
    density();
    std::vector<P2> a(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      P2 F{0, 0};
      for (std::size_t j = 0; j < x.size(); ++j) {
        if (j == i) continue;
        const double rx = x[i][0] - x[j][0], ry = x[i][1] - x[j][1];
        const double q = std::sqrt(rx * rx + ry * ry) / h;
        if (q >= 1) continue;
        const double pressure = -m / rho[j] * (p[i] + p[j]) / 2 * (-30 / (M_PI * h * h * h)) * (1 - q) * (1 - q) / q;
        const double viscous = -mu * m / rho[j] * 40 / (M_PI * std::pow(h, 4)) * (1 - q);
        F[0] += pressure * rx + viscous * (vel[i][0] - vel[j][0]);
        F[1] += pressure * ry + viscous * (vel[i][1] - vel[j][1]);
      }
      F[1] += -rho[i] * g;
      a[i] = {F[0] / rho[i], F[1] / rho[i]};
    }
    return a;
  }

  void advance() {
    const bool first = step == 0;
    const std::vector<P2>& vel = first ? v : reading == ViscousVelocity::kHalfStep ? vHalf : vEstimate;
    const std::vector<P2> a = accelerations(vel);
    for (std::size_t i = 0; i < x.size(); ++i)
      for (int d = 0; d < 2; ++d) {
        vHalf[i][d] = (first ? v[i][d] + a[i][d] * dt / 2 : vHalf[i][d] + a[i][d] * dt);
        x[i][d] += vHalf[i][d] * dt;
        vEstimate[i][d] = vHalf[i][d] + a[i][d] * dt / 2;
        if (x[i][d] < lo[d] + h || x[i][d] > hi[d] - h) {
          x[i][d] = x[i][d] < lo[d] + h ? lo[d] + h : hi[d] - h;
          vHalf[i][d] *= -e;
          vEstimate[i][d] *= -e;
        }
      }
    ++step;
  }
};

// The positions (by id) of every snapshot of a series, and its steps.
struct Snapshots {
  std::vector<long> steps;
  std::vector<std::vector<P2>> x;
};

Snapshots readSeries(const std::filesystem::path& pvd, double dt) {
  Snapshots s;
  for (const auto& e : sph::test::readPvd(pvd)) {
    vtkDataArray* id = e.data->GetPointData()->GetArray("id");
    BOOST_TEST_REQUIRE(id != nullptr);
    std::vector<P2> x(static_cast<std::size_t>(e.data->GetNumberOfPoints()));
    for (vtkIdType i = 0; i < e.data->GetNumberOfPoints(); ++i) {
      double p[3];
      e.data->GetPoint(i, p);
      x.at(static_cast<std::size_t>(id->GetTuple1(i))) = {p[0], p[1]};
    }
    s.steps.push_back(std::lround(e.time / dt));
    s.x.push_back(x);
  }
  return s;
}

// The largest distance between the reference and the snapshots' positions
// over the whole run.
double largestDeviation(SeedReference ref, const std::vector<P2>& x0, const Snapshots& s) {
  ref.start(x0);
  double worst = 0;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    while (ref.step < s.steps[k]) ref.advance();
    for (std::size_t i = 0; i < x0.size(); ++i)
      worst = std::max(worst, std::hypot(ref.x[i][0] - s.x[k][i][0], ref.x[i][1] - s.x[k][i][1]));
  }
  return worst;
}

struct SeedCase {
  const char* name;
  std::vector<P2> points;  // as in cases/NAME.case (h 0.01, k 2000, rho0 1000, mu 1, g 9.81, e 0.5, dt 1e-4)
};

}  // namespace

BOOST_AUTO_TEST_SUITE(seed_reference)

// sph's seed_wcsph reads the viscous velocity as the half-step v^{t-1/2}
// (docs/methods/seed-model.md, "The viscous term's velocity"). Tolerance
// 1e-11 m, 30x the largest measured gap: both sides do the same arithmetic in a different order (sph sorts
// the particles by cell and sums its neighbours in list order, computes
// v^{t+1/2} as (v^t + a dt/2) + a dt/2, scales the masses after the density
// pass), so they differ by round-off, ~1e-16 relative per operation, which
// the close encounters of these cases (the pressure force grows as 1/q)
// amplify; measured 2026-12-03: 3.9e-14, 1.2e-13 and 3.5e-13 m. The other
// reading lies 4.2e-5, 2.4e-4 and 1.5e-3 m from sph (reported below), over
// 4e6x the tolerance: the comparison tells the readings apart. (Before the
// seed model took the half-step reading, sph matched the integer-time one
// to 3.6e-14 to 1.2e-13 m and this test failed by those same distances.)
BOOST_AUTO_TEST_CASE(few_particle_cases_match_the_seed_document) {
  const std::vector<SeedCase> cases{
      {"two_particles", {{0.5, 0.5}, {0.5, 0.01}}},
      {"three_particles", {{0.5, 0.5}, {0.495, 0.01}, {0.505, 0.01}}},
      {"four_particles", {{0.505, 0.5}, {0.515, 0.5}, {0.51, 0.45}, {0.5, 0.45}}},
  };
  const auto dir = sph::test::scratchDir("seed_reference");
  for (const SeedCase& c : cases) {
    const auto out = dir / c.name;
    const auto r = sph::test::runSph({"run", sph::test::caseFile(c.name), "--output", out.string(), "--threads", "1",
                                      "--no-progress"});
    BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
    const Snapshots s = readSeries(out / (std::string(c.name) + ".pvd"), 1e-4);
    BOOST_TEST_REQUIRE(s.steps.size() == 121u);  // 1.2 s, a snapshot every 100 steps
    SeedReference half, integer;
    integer.reading = ViscousVelocity::kInteger;
    const double toHalf = largestDeviation(half, c.points, s), toInteger = largestDeviation(integer, c.points, s);
    BOOST_TEST_MESSAGE(c.name << ": sph against the half-step reading " << toHalf << " m, against the integer-time "
                              << "reading " << toInteger << " m (over 1.2 s, " << s.steps.size() << " snapshots)");
    // (A mixed-precision build stores p and m in float: its tolerance is
    // float's epsilon over positions of order 1 m; it read 1.6e-8 to 4.9e-8 m.)
    BOOST_TEST(toHalf < std::max(1e-11, sph::test::kNarrowEpsilon), c.name << ": " << toHalf << " m");
    BOOST_TEST(toInteger > 1e5 * 1e-11, c.name << ": the readings are " << toInteger << " m apart");
  }
}

BOOST_AUTO_TEST_SUITE_END()
