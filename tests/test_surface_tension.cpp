// Colour-field surface tension (terms/colour_surface_tension.hpp) and
// Monaghan's artificial pressure against the tensile instability
// (terms/artificial_pressure.hpp).
//
// Suite surface_tension: the colour-field normal of a flat interface, the
// curvature of a circular drop at two resolutions, no force in the bulk, and
// the Laplace pressure jump of cases/droplet_surface_tension.case against
// tests/reference/droplet_laplace_rayleigh.csv. (The tensile instability:
// test_tensile.cpp.)
#include "pvd_reader.hpp"
#include "test_support.hpp"
#include "sph/terms/colour_surface_tension.hpp"

#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <algorithm>

using namespace sph;

namespace {

// A lattice of n x n particles of spacing dx filling [lo, lo + n dx]^2,
// each moved by a uniform random amount in [-jitter, jitter] dx per axis.
std::vector<Real> lattice(int n, Real dx, Real lo, Real jitter, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> u(-jitter, jitter);
  std::vector<Real> pts;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      pts.push_back(lo + (i + 0.5) * dx + u(rng) * dx);
      pts.push_back(lo + (j + 0.5) * dx + u(rng) * dx);
    }
  return pts;
}

// A wcsph case over those points with the colour-field force on.
CaseConfig colourCase(const std::string& kernel, Real h, Real dx, std::vector<Real> points,
                      const std::string& method = "morris") {
  CaseConfig c = test::bareWcsph(2);
  c.kernel = kernel;
  c.h = h;
  c.spacing = dx;
  c.rho0 = 1;
  c.k = 100;
  c.points = std::move(points);
  c.surfaceTension = method;
  c.sigma = 1;
  return c;
}

struct ColourSample {
  Vec<2> x, n;
  Real kappa, colour, a;  // a: |surface-tension acceleration|
};

std::vector<ColourSample> colourField(const CaseConfig& c) {
  Scene<2> s = test::sceneOf<2>(c);
  const auto& P = s.particles();
  BOOST_TEST_REQUIRE(P.colourNormal.size() == P.size());
  const ColourSurfaceTension<2> force{c.sigma, c.surfaceThreshold / c.h};
  std::vector<ColourSample> out;
  for (std::size_t i = 0; i < P.fluidCount(); ++i)
    out.push_back({P.x[i], P.colourNormal[i], P.curvature[i], P.colour[i], force.acceleration(i, P).norm()});
  return out;
}

constexpr Real kPi = 3.14159265358979323846;

}  // namespace

BOOST_AUTO_TEST_SUITE(surface_tension)

// A flat interface y = 0.5 between colour 1 (below) and 0 (above), on a
// lattice jittered by 10% of dx: n = grad c must point along -y.
BOOST_AUTO_TEST_CASE(flat_interface_normal_points_along_its_normal) {
  for (const auto& [kernel, hOverDx] : {std::pair<std::string, Real>{"muller", 3.0}, {"cubic_spline", 1.3}}) {
    const Real dx = 0.02;
    for (const Real jitter : {0.0, 0.1}) {
      CaseConfig c = colourCase(kernel, hOverDx * dx, dx, lattice(50, dx, 0, jitter));
      c.colourBoxMin = {-1, -1};
      c.colourBoxMax = {2, 0.5};
      Real worst = 0;
      int seen = 0;
      for (const ColourSample& p : colourField(c)) {
        if (std::abs(p.x.x() - 0.5) > 0.25 || std::abs(p.x.y() - 0.5) > 0.2) continue;  // away from the block's edges
        if (p.n.norm() * c.h <= c.surfaceThreshold) continue;
        ++seen;
        const Real angle = std::acos(std::clamp(-p.n.y() / p.n.norm(), Real(-1), Real(1)));
        worst = std::max(worst, angle);
      }
      BOOST_TEST_MESSAGE(kernel << " jitter " << jitter << ": " << seen << " interface particles, worst angle "
                                << worst * 180 / kPi << " deg");
      BOOST_TEST(seen > 40);
      // On the lattice the tangential part cancels pair by pair (mirror
      // symmetry about every lattice column): round-off only. Jittered by
      // +-0.1 dx, each neighbour's contribution turns by about 0.1 dx / r and
      // the errors add at random over the neighbours: measured 3.7 degrees
      // (Mueller, h = 3 dx, ~28 neighbours) and 5.7 (cubic, h = 1.3 dx, ~20);
      // 10 degrees leaves room for another random draw and still fails a
      // wrong normal (a sign error gives 180 degrees; the plain sum instead
      // of the difference form gave 120, from bulk noise above threshold).
      BOOST_TEST(worst < (jitter == 0 ? 1e-9 : 10 * kPi / 180));
    }
  }
}

// A circular drop of radius R (colour 1 inside, 0 outside, one fluid): the
// curvature the force sees is 1/R. The force is sigma kappa n across the
// interface band, so the pressure jump it makes is sigma times
//   kappa_eff = sum_i kappa_i |n_i| / r_i / sum_i |n_i| / r_i
// over the band (the radial integrals of kappa |grad c| and |grad c|;
// the 1/r turns the sums over the area into integrals along a radius).
// Morris's kappa_i is 1/R at every particle of the band; Mueller's
// -lap c / |n| is 1/R only in this integrated sense (pointwise it carries
// (d|n|/dr)/|n| ~ 1/h), so only kappa_eff is checked for it.
BOOST_AUTO_TEST_CASE(curvature_of_a_circular_drop_is_one_over_r_at_two_resolutions) {
  const Real R = 0.2;
  for (const std::string method : {"morris", "muller", "corrected"})
    for (const auto& [kernel, hOverDx] : {std::pair<std::string, Real>{"muller", 3.0}, {"cubic_spline", 1.3}}) {
      for (const int perR : {10, 20}) {
        const Real dx = R / perR;
        const int n = static_cast<int>(std::lround(0.8 / dx));
        CaseConfig c = colourCase(kernel, hOverDx * dx, dx, lattice(n, dx, -0.4, 0), method);
        c.colourEllipseCenter = {0, 0};
        c.colourEllipseRadii = {R, R};
        Real num = 0, den = 0, spread = 0;
        int band = 0;
        for (const ColourSample& p : colourField(c)) {
          const Real r = p.x.norm(), nn = p.n.norm();
          if (nn * c.h <= c.surfaceThreshold) continue;
          num += p.kappa * nn / r;
          den += nn / r;
          spread = std::max(spread, std::abs(p.kappa * R - 1));
          ++band;
        }
        const Real kappaR = num / den * R;
        BOOST_TEST_MESSAGE(method << ", " << kernel << " kernel, R/dx = " << perR << ": kappa_eff R = " << kappaR
                                  << ", largest |kappa_i R - 1| = " << spread << " over " << band << " particles");
        // Tolerances: the smoothed interface spans ~2 supports (R/support
        // = 3.3 and 6.7 for Mueller at h = 3 dx, 3.8 and 7.7 for the cubic
        // at 2.6 dx), so the (support/R)^2 term is several percent at
        // R/dx = 10 and a quarter of that at 20; the lattice's staircase
        // circle adds O(dx/R) of either sign (so the error need not fall
        // monotonically between two resolutions). 10% and 5% for Morris's
        // curvature (measured: 0.8% and 0.8% with the Mueller kernel, 0.6%
        // and 2.2% with the cubic). Mueller's -lap c/|n| is biased and does
        // not converge: measured 0.73 and 0.72 with poly6, 0.96 and 0.95
        // with the cubic (the threshold cuts the tails of the band, where
        // its integrand is large); the gate 30% only keeps it from getting
        // worse unnoticed. The corrected divergence (corrected_surface_tension.hpp)
        // has Morris's gates (the same interface, the same staircase).
        if (method != "muller") BOOST_TEST(std::abs(kappaR - 1) < (perR == 10 ? 0.10 : 0.05));
        else BOOST_TEST(std::abs(kappaR - 1) < 0.30);
      }
    }
}

// In the bulk of either phase the colour gradient is below the threshold
// and the force is exactly zero; at the interface it is not.
BOOST_AUTO_TEST_CASE(no_force_in_the_bulk) {
  const Real dx = 0.02;
  for (const auto& [kernel, hOverDx] : {std::pair<std::string, Real>{"muller", 3.0}, {"cubic_spline", 1.3}}) {
    CaseConfig c = colourCase(kernel, hOverDx * dx, dx, lattice(50, dx, 0, 0.1));
    c.colourBoxMin = {-1, -1};
    c.colourBoxMax = {2, 0.5};
    const Real support = kernel == "muller" ? c.h : 2 * c.h;
    Real bulkMax = 0, interfaceMin = 1e300;
    int bulk = 0;
    for (const ColourSample& p : colourField(c)) {
      const bool inner = p.x.minCoeff() > support + dx && p.x.maxCoeff() < 1 - support - dx;
      if (!inner) continue;
      if (std::abs(p.x.y() - 0.5) > support + dx) {
        ++bulk;
        bulkMax = std::max(bulkMax, p.n.norm() * c.h);
        BOOST_TEST(p.a == 0);
      } else if (std::abs(p.x.y() - 0.5) < 0.5 * dx) {
        interfaceMin = std::min(interfaceMin, p.a);
      }
    }
    BOOST_TEST_MESSAGE(kernel << ": " << bulk << " bulk particles, largest |n| h there " << bulkMax);
    BOOST_TEST(bulk > 500);
    BOOST_TEST(interfaceMin > 0);
  }
}

// cases/droplet_surface_tension.case, run by sph to t = 0.3 s: the square
// drop becomes a circle, and the pressure inside it exceeds the outside by
// the Laplace jump dp = sigma/R (2D; tests/reference/droplet_laplace_rayleigh.csv).
//   inside:  mean p of the drop's particles within 0.5 R of its centroid
//   outside: mean p of the other phase between 1.5 R and 2.5 R from it
//            (clear of the interface band, 2 supports wide, and of the walls)
//   R:       the equal-area radius, sqrt(N_drop dx^2 / pi)
// averaged over the snapshots from t = 0.1 s on (the corners are gone by
// then; the mean takes out the residual pressure waves, about +-5%).
// Shape: max/min over 32 directions of the drop's radial extent, 1.41 for
// the square at t = 0 (its diagonal over its half side). At R/dx = 9 (the
// case) and 18 (dx, h and dt halved): about 3 s and 45 s on an idle core.
BOOST_AUTO_TEST_CASE(square_drop_relaxes_to_a_circle_with_the_laplace_pressure_jump) {
  // The reference: dp_2D = sigma / R, checked on its row for the unit drop.
  std::ifstream ref(test::referenceFile("droplet_laplace_rayleigh.csv"));
  BOOST_TEST_REQUIRE(ref.good());
  std::string line;
  bool unitRow = false;
  while (std::getline(ref, line)) {
    if (line.rfind("2,1,1,0,1,", 0) != 0) continue;  // mode 2, sigma 1, rho_in 1, rho_out 0, R 1
    std::stringstream row(line);
    std::vector<Real> v;
    for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::stod(cell));
    BOOST_TEST(v.at(5) == 1.0);  // dp_2D = sigma / R
    unitRow = true;
  }
  BOOST_TEST_REQUIRE(unitRow);

  // The shipped case (R/dx = 9) and the same at half the spacing (R/dx = 18;
  // h and dt halved with it).
  for (const Real dx : {0.02, 0.01}) {
    const auto dir = test::scratchDir("droplet_st");
    std::vector<std::string> args = {"run", test::caseFile("droplet_surface_tension"), "--output", dir.string(),
                                     "--end_time", "0.3", "--threads", "1", "--no-progress"};
    if (dx == 0.01) args.insert(args.end(), {"--spacing", "0.01", "--h", "0.013", "--dt", "1.5e-4"});
    const auto r = test::runSph(args);
    BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
    const auto series = test::readPvd(dir / "droplet_surface_tension.pvd");
    BOOST_TEST_REQUIRE(series.size() > 10u);
    const Real sigma = 1;
    Real ratioSum = 0, worstShape = 0, firstShape = 0, Rdrop = 0;
    int count = 0;
    for (const auto& entry : series) {
      vtkPolyData* d = entry.data;
      vtkDataArray* p = d->GetPointData()->GetArray("pressure");
      vtkDataArray* colour = d->GetPointData()->GetArray("colour");
      vtkDataArray* kind = d->GetPointData()->GetArray("kind");
      BOOST_TEST_REQUIRE((p && colour && kind));
      std::vector<Vec<2>> drop, other;
      std::vector<Real> pDrop, pOther;
      for (vtkIdType i = 0; i < d->GetNumberOfPoints(); ++i) {
        if (kind->GetTuple1(i) != 0) continue;
        double x[3];
        d->GetPoint(i, x);
        (colour->GetTuple1(i) > 0.5 ? drop : other).push_back(Vec<2>(x[0], x[1]));
        (colour->GetTuple1(i) > 0.5 ? pDrop : pOther).push_back(p->GetTuple1(i));
      }
      Vec<2> centre = Vec<2>::Zero();
      for (const auto& x : drop) centre += x;
      centre /= static_cast<Real>(drop.size());
      const Real R = std::sqrt(static_cast<Real>(drop.size()) * dx * dx / kPi);
      Rdrop = R;
      Real in = 0, out = 0;
      int nIn = 0, nOut = 0;
      for (std::size_t i = 0; i < drop.size(); ++i)
        if ((drop[i] - centre).norm() < 0.5 * R) in += pDrop[i], ++nIn;
      for (std::size_t i = 0; i < other.size(); ++i) {
        const Real rr = (other[i] - centre).norm();
        if (rr > 1.5 * R && rr < 2.5 * R) out += pOther[i], ++nOut;
      }
      std::vector<Real> extent(32, 0);
      for (const auto& x : drop) {
        const Vec<2> d2 = x - centre;
        const int bin = static_cast<int>(std::floor((std::atan2(d2.y(), d2.x()) + kPi) / (2 * kPi) * 32)) % 32;
        extent[static_cast<std::size_t>(bin)] = std::max(extent[static_cast<std::size_t>(bin)], d2.norm());
      }
      const Real shape =
          *std::max_element(extent.begin(), extent.end()) / *std::min_element(extent.begin(), extent.end());
      const Real ratio = (in / nIn - out / nOut) * R / sigma;
      BOOST_TEST_MESSAGE("dx " << dx << ", t = " << entry.time << ": dp R / sigma = " << ratio
                               << ", extent max/min = " << shape);
      if (entry.time == 0) firstShape = shape;
      if (entry.time >= 0.1) {
        ratioSum += ratio;
        ++count;
        worstShape = std::max(worstShape, shape);
      }
    }
    const Real mean = ratioSum / count;
    BOOST_TEST_MESSAGE("R/dx = " << Rdrop / dx << ": mean dp R / sigma from t = 0.1 s: " << mean << " over " << count
                                 << " snapshots");
    BOOST_TEST(firstShape > 1.35);  // a square to start with
    // A circle (to the lattice's staircase, dx/R = 0.11 at R/dx = 9) from 0.1 s on.
    BOOST_TEST(worstShape < 1.12);
    // Laplace within 5% (the goal) at both resolutions. Measured
    // with surface_tension = "corrected" (docs/validation/surface-tension.md): 1.012 at
    // R/dx = 9 and 0.985 at R/dx = 18 over 0.1-0.3 s; what is left is the
    // +-5% pressure waves the mean does not quite take out and the
    // colour gradient's integral across the interface (0.987 on the
    // disordered set). The morris method gives 0.93 and 0.89 over this
    // window (0.1-0.3 s) and fails it.
    BOOST_TEST(std::abs(mean - 1) < 0.05);
  }
}

// Rayleigh oscillation: cases/droplet_oscillation.case, an ellipse with
// semi-axes 0.22 and 0.18 in a second fluid of the same density, oscillates
// in mode 2. Measured, as validation/droplet_oscillation.py does: the
// deformation d = (Ixx - Iyy) / (Ixx + Iyy) of the drop's particles (second
// moments about their centroid) in every snapshot (every 0.01 s); the period
// is twice the mean time between successive zero crossings of d - mean(d),
// linearly interpolated. Reference: Rayleigh's 2D frequency for a cylinder,
// w^2 = n (n^2 - 1) sigma / ((rho_in + rho_out) R^3), from the mode-2 row of
// droplet_laplace_rayleigh.csv with rho_in = rho_out = sigma = 1, scaled
// to the drop's equal-area radius R = sqrt(N dx^2 / pi) by that law.
// Rayleigh's law is inviscid. This case has nu = 0.005 m^2/s, and between
// two fluids the oscillation drives a Stokes layer at the interface that
// lengthens the period: the viscous normal mode of the same cylinder
// (validation/droplet_oscillation.py, viscous_mode: linearised
// Navier-Stokes inside and out, equal rho and mu) has a period of 0.3488 s
// for R = 0.2019, 6.0% longer than Rayleigh's 0.3290 s, so no correct
// solver of this case is within 5% of Rayleigh (a lower viscosity is: 3.7%
// at nu = 0.002, but there this WCSPH drop breaks up, morris and corrected
// alike, at R/dx = 10 and 20).
// Measured with surface_tension = "corrected" (docs/validation/surface-tension.md):
// 0.3531 s, +7.3% of Rayleigh's and +1.2% of the viscous mode (morris:
// +8.5% and +2.3%, its Laplace jump 0.91-0.93 of sigma/R).
// Gates: 3% of the viscous normal mode (what the case should reproduce;
// R/dx = 10 leaves the Stokes layer, sqrt(2 nu / omega) = 0.024 = 1.2 dx,
// barely resolved); 10% of Rayleigh's, a regression gate just past today's
// 7.3% (a wrong law fails it by far: sigma or the density sum off by 2 gives
// 41%, mode 3 half the period).
BOOST_AUTO_TEST_CASE(elliptic_drop_oscillates_at_rayleighs_frequency) {
  std::ifstream ref(test::referenceFile("droplet_laplace_rayleigh.csv"));
  BOOST_TEST_REQUIRE(ref.good());
  std::vector<Real> row;
  for (std::string line; std::getline(ref, line);) {
    if (line.rfind("2,1,1,1,", 0) != 0) continue;  // mode 2, sigma 1, rho_in 1, rho_out 1
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
  }
  BOOST_TEST_REQUIRE(row.size() >= 9u);
  const Real Rref = row[4], omegaRef = row[7];  // columns R, omega_2D

  const auto dir = test::scratchDir("droplet_osc");
  const auto r = test::runSph({"run", test::caseFile("droplet_oscillation"), "--output", dir.string(), "--threads",
                               "1", "--no-progress"});
  BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
  const auto series = test::readPvd(dir / "droplet_oscillation.pvd");
  BOOST_TEST_REQUIRE(series.size() > 50u);
  std::vector<Real> t, d;
  std::size_t nDrop = 0;
  for (const auto& entry : series) {
    vtkPolyData* data = entry.data;
    vtkDataArray* colour = data->GetPointData()->GetArray("colour");
    vtkDataArray* kind = data->GetPointData()->GetArray("kind");
    BOOST_TEST_REQUIRE((colour && kind));
    std::vector<Vec<2>> drop;
    for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i) {
      if (kind->GetTuple1(i) != 0 || colour->GetTuple1(i) < 0.5) continue;
      double x[3];
      data->GetPoint(i, x);
      drop.push_back(Vec<2>(x[0], x[1]));
    }
    Vec<2> centre = Vec<2>::Zero();
    for (const auto& x : drop) centre += x;
    centre /= static_cast<Real>(drop.size());
    Real Ixx = 0, Iyy = 0;
    for (const auto& x : drop) Ixx += std::pow(x[0] - centre[0], 2), Iyy += std::pow(x[1] - centre[1], 2);
    t.push_back(entry.time);
    d.push_back((Ixx - Iyy) / (Ixx + Iyy));
    nDrop = drop.size();
  }
  Real mean = 0;
  for (Real v : d) mean += v / static_cast<Real>(d.size());
  std::vector<Real> crossings;
  for (std::size_t k = 0; k + 1 < d.size(); ++k) {
    const Real a = d[k] - mean, b = d[k + 1] - mean;
    if (a * b < 0) crossings.push_back(t[k] + (t[k + 1] - t[k]) * a / (a - b));
  }
  BOOST_TEST_REQUIRE(crossings.size() >= 4u);  // two periods at least
  const Real period = 2 * (crossings.back() - crossings.front()) / static_cast<Real>(crossings.size() - 1);
  const Real R = std::sqrt(static_cast<Real>(nDrop) * 0.02 * 0.02 / kPi);
  const Real rayleigh = 2 * kPi / (omegaRef * std::pow(Rref / R, 1.5));
  BOOST_TEST_MESSAGE("drop of " << nDrop << " particles, R = " << R << ": " << crossings.size()
                                << " zero crossings, period " << period << " s, Rayleigh " << rayleigh << " s");
  const Real viscousMode = 0.3488;  // s, for R = 0.2019 (320 particles), nu = 0.005: see above
  BOOST_TEST(nDrop == 320u);
  BOOST_TEST_MESSAGE("against the viscous normal mode's " << viscousMode << " s: " << period / viscousMode - 1);
  BOOST_TEST(std::abs(period / viscousMode - 1) < 0.03);
  BOOST_TEST(std::abs(period / rayleigh - 1) < 0.10);  // regression gate
}

// Off, the colour pass, its fields and the force do not exist; on, they do.
BOOST_AUTO_TEST_CASE(surface_tension_and_artificial_pressure_cost_nothing_when_off) {
  CaseConfig c = colourCase("cubic_spline", 0.026, 0.02, lattice(10, 0.02, 0, 0));
  c.surfaceTension = "none";
  {
    Scene<2> s = test::sceneOf<2>(c);
    BOOST_REQUIRE(!s.step());
    const unsigned ran = s.model().executedTerms();
    BOOST_TEST((ran & (term_bits::kColourField | term_bits::kSurfaceTension | term_bits::kArtificialPressure)) == 0u);
    const auto& P = s.particles();
    BOOST_TEST((P.colour.empty() && P.colourNormal.empty() && P.curvature.empty()));
    BOOST_TEST(s.model().passes().size() == 2u);  // density + EOS, forces
  }
  c.surfaceTension = "morris";
  c.termKeys.reals["artificial_pressure"] = 0.2;
  Scene<2> s = test::sceneOf<2>(c);
  BOOST_REQUIRE(!s.step());
  const unsigned ran = s.model().executedTerms();
  for (unsigned bit : {term_bits::kColourField, term_bits::kSurfaceTension, term_bits::kArtificialPressure})
    BOOST_TEST((ran & bit) != 0u);
  BOOST_TEST(s.particles().colourNormal.size() == s.particles().size());
  BOOST_TEST(s.model().passes().size() == 3u);
}

// Bad input: one line naming the key and what is allowed, exit 2.
BOOST_AUTO_TEST_CASE(bad_surface_tension_input_is_refused) {
  const std::string file = test::caseFile("droplet_surface_tension");
  for (const auto& [args, words] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--sigma", "0"}, "sigma > 0"},
           {{"--surface_tension", "marangoni"}, "surface_tension"},
           {{"--colour_box_min", "0.1"}, "colour_box_min"},
           {{"--artificial_pressure", "-1"}, "artificial_pressure"},
           {{"--artificial_pressure_n", "0"}, "artificial_pressure_n"}}) {
    std::vector<std::string> a = {"run", file, "--output", test::scratchDir("bad_st").string()};
    a.insert(a.end(), args.begin(), args.end());
    const auto r = test::runSph(a);
    BOOST_TEST(r.exitCode == 2, r.output);
    BOOST_TEST(r.output.find(words) != std::string::npos, r.output);
  }
}

BOOST_AUTO_TEST_SUITE_END()
