// The kernel family (cubic spline, Wendland C2, truncated Gaussian, Mueller's
// poly6/spiky/viscosity set), each in 2D and 3D: normalisation on a lattice,
// vanishing gradient sums, sign and compact support, gradW and laplacianW
// against finite differences of the kernels they come from, and the constants
// in tests/reference (computed elsewhere, not by this code).
#include "sph/kernels/kernels.hpp"
#include "cli_support.hpp"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

using sph::Real;
using sph::Vec;

namespace {

using AllKernels =
    std::tuple<sph::CubicSpline<2>, sph::CubicSpline<3>, sph::WendlandC2<2>, sph::WendlandC2<3>,
               sph::Gaussian<2>, sph::Gaussian<3>, sph::Muller<2>, sph::Muller<3>>;

template <class K>
struct IsMuller : std::false_type {};
template <int D>
struct IsMuller<sph::Muller<D>> : std::true_type {};

// The kernel gradW differentiates (spiky for Mueller) and the one laplacianW
// is the Laplacian of (viscosity for Mueller).
template <class K>
Real gradSource(const K& k, Real r) {
  if constexpr (IsMuller<K>::value)
    return k.spikyW(r);
  else
    return k.W(r);
}
template <class K>
Real laplacianSource(const K& k, Real r) {
  if constexpr (IsMuller<K>::value)
    return k.viscosityW(r);
  else
    return k.W(r);
}

// Radii (as fractions of the support) where the Laplacian is the true one and
// smooth: away from r = 0 (Mueller's viscosity kernel is singular there), the
// cubic's knots q = 1, 2 (fractions 0.5, 1) and the support.
const std::vector<Real> kLaplacianFractions{0.2, 0.3, 0.42, 0.58, 0.66, 0.78, 0.9, 0.96};
const std::vector<Real> kGradientFractions{0.02, 0.1,  0.25, 0.4,  0.49,
                                           0.51, 0.62, 0.75, 0.88, 0.93};

// A unit direction that is not along any lattice axis.
template <int D>
Vec<D> direction() {
  Vec<D> n;
  if constexpr (D == 2)
    n << 0.6, -0.8;
  else
    n << 0.48, -0.6, 0.64;
  return n.normalized();
}

// Area of the unit sphere in D dimensions.
template <int D>
constexpr Real sphereArea() {
  return D == 2 ? 2 * M_PI : 4 * M_PI;
}

// int f(|x|) d^D x over the ball of radius R, by the midpoint rule in r with n
// cells (never evaluates r = 0, so integrable singularities are fine).
template <int D, class F>
Real radialIntegral(F f, Real R, int n) {
  const Real dr = R / n;
  Real sum = 0;
  for (int i = 0; i < n; ++i) {
    const Real r = (i + Real(0.5)) * dr;
    sum += f(r) * std::pow(r, D - 1);
  }
  return sphereArea<D>() * sum * dr;
}

// Visit every lattice offset (i_1..i_D) with |i_k| <= n.
template <int D, class F>
void forLattice(int n, F f) {
  Eigen::Matrix<int, D, 1> idx = Eigen::Matrix<int, D, 1>::Constant(-n);
  while (true) {
    f(idx);
    int k = 0;
    while (k < D && idx[k] == n) idx[k++] = -n;
    if (k == D) return;
    ++idx[k];
  }
}

// A CSV file from tests/reference: '#' lines skipped, the first other line
// is the header; each row maps column name -> text.
using Row = std::map<std::string, std::string>;
std::vector<Row> readReference(const std::string& name) {
  const std::string path = sph::test::referenceFile(name);
  std::ifstream in(path);
  BOOST_REQUIRE_MESSAGE(in.good(), "missing reference file " << path);
  std::vector<std::string> header;
  std::vector<Row> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (header.empty()) {
      header = cells;
      continue;
    }
    BOOST_REQUIRE_MESSAGE(cells.size() == header.size(), "bad row in " << path << ": " << line);
    Row row;
    for (std::size_t i = 0; i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  BOOST_REQUIRE_MESSAGE(!rows.empty(), "no data rows in " << path);
  return rows;
}

Real number(const Row& row, const std::string& column) {
  const auto it = row.find(column);
  BOOST_REQUIRE_MESSAGE(it != row.end(), "no column " << column);
  return std::stod(it->second);
}

const Row& findRow(const std::vector<Row>& rows, const std::string& kernel, int dim) {
  for (const auto& row : rows)
    if (row.at("kernel") == kernel && std::stoi(row.at("dim")) == dim) return row;
  BOOST_FAIL("kernel_constants.csv has no row " << kernel << ", dim " << dim);
  return rows.front();
}

// The row name in kernel_constants.csv for our W (and for Mueller, also the
// rows of the kernels behind gradW and laplacianW).
template <class K>
std::string referenceName() {
  const std::string n = K::name;
  if (n == "cubic_spline") return "cubic_spline_M4";
  if (n == "wendland_c2") return "wendland_C2";
  if (n == "gaussian") return "gaussian_trunc3";
  return "poly6";
}

// Location and value of max |g(q)| over q in [0, qMax], on a grid of step dq.
template <class G>
std::pair<Real, Real> maxAbs(G g, Real qMax, Real dq) {
  Real qBest = 0, best = -1;
  const long n = std::lround(qMax / dq);
  for (long i = 0; i <= n; ++i) {
    const Real q = i * dq, v = std::abs(g(q));
    if (v > best) best = v, qBest = q;
  }
  return {qBest, best};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(kernel_family)

BOOST_AUTO_TEST_CASE(names_are_the_case_file_names) {
  BOOST_TEST(std::string(sph::CubicSpline<2>::name) == "cubic_spline");
  BOOST_TEST(std::string(sph::WendlandC2<3>::name) == "wendland_c2");
  BOOST_TEST(std::string(sph::Gaussian<2>::name) == "gaussian");
  BOOST_TEST(std::string(sph::Muller<3>::name) == "muller");
  BOOST_TEST(sph::CubicSpline<2>(0.1).support() == 0.2);
  BOOST_TEST(sph::WendlandC2<3>(0.1).support() == 0.2);
  BOOST_TEST(sph::Gaussian<2>(0.1).support() == 0.1 * 3);
  BOOST_TEST(sph::Muller<3>(0.1).support() == 0.1);
}

// sum dx^D W(x_n) over the lattice x_n = n dx covering the support is the
// integral of W. dx = support/80 in 2D, support/30 in 3D (61^3 nodes), h = 0.07
// (not 1, so h scaling is exercised). Tolerance 1e-4 (the issue's). Measured
// lattice errors: <= 5e-9 for cubic, Wendland and poly6 (smooth, compact);
// ~4e-6 for the Gaussian (lattice-point-count noise from its jump of
// 1.2e-4 W(0) at 3h); the spiky kernel (behind Mueller's gradW, checked too)
// has a cusp on the central node, which costs 8e-5 at support/30 in 2D, hence
// the finer 2D lattice (4e-6 there, and in 3D). A wrong normalisation (e.g.
// the untruncated Gaussian's 1/pi or 1/pi^(3/2)) is off by >= 1.2e-4.
BOOST_AUTO_TEST_CASE_TEMPLATE(integral_of_W_on_a_lattice_is_one, K, AllKernels) {
  constexpr int D = K::dim;
  const K k(0.07);
  const int n = D == 2 ? 80 : 30;
  const Real dx = k.support() / n, dV = std::pow(dx, D);
  Real sumW = 0, sumGradSource = 0;
  forLattice<D>(n, [&](const Eigen::Matrix<int, D, 1>& idx) {
    const Real r = dx * idx.template cast<Real>().norm();
    sumW += dV * k.W(r);
    sumGradSource += dV * gradSource(k, r);
  });
  BOOST_TEST_INFO(K::name << " D=" << D);
  BOOST_TEST(sumW == 1.0, boost::test_tools::tolerance(1e-4));
  BOOST_TEST(sumGradSource == 1.0, boost::test_tools::tolerance(1e-4));
}

// Mueller's viscosity kernel is singular at r = 0 (1/r in 3D, log r in 2D), so
// it is integrated radially (midpoint rule, 2e5 cells: error ~1e-9 even with
// the r log r integrand). Tolerance 1e-7: far above the quadrature error, far
// below what a wrong constant or shape term would give.
BOOST_AUTO_TEST_CASE_TEMPLATE(viscosity_kernel_integrates_to_one, K, AllKernels) {
  if constexpr (IsMuller<K>::value) {
    constexpr int D = K::dim;
    const K k(0.07);
    const Real integral =
        radialIntegral<D>([&](Real r) { return k.viscosityW(r); }, k.support(), 200000);
    BOOST_TEST_INFO("D=" << D);
    BOOST_TEST(integral == 1.0, boost::test_tools::tolerance(1e-7));
  } else {
    BOOST_TEST_MESSAGE(K::name << ": W is its own viscosity kernel");
  }
}

// Around a node x_i off the origin, the lattice x_j = x_i + n dx is symmetric,
// so sum_j gradW(x_i - x_j) vanishes; rounding in x_i - x_j leaves ~1e-16 per
// term. Tolerance 1e-12 of sum |gradW|: any term not odd in rij (a component
// taken as |rij_k|, a direction-dependent factor) fails by O(1).
BOOST_AUTO_TEST_CASE_TEMPLATE(gradW_sums_to_zero_on_a_symmetric_lattice, K, AllKernels) {
  constexpr int D = K::dim;
  const K k(0.05);
  Vec<D> xi = Vec<D>::Zero();
  xi(0) = 0.37;
  xi(1) = -0.21;
  const int n = 9;
  const Real dx = k.support() / (n - Real(1.7));  // lattice reaches past the support
  Vec<D> sum = Vec<D>::Zero();
  Real sumAbs = 0;
  int inside = 0;
  forLattice<D>(n, [&](const Eigen::Matrix<int, D, 1>& idx) {
    const Vec<D> xj = xi + dx * idx.template cast<Real>();
    const Vec<D> rij = xi - xj;
    const Real r = rij.norm();
    const Vec<D> g = k.gradW(rij, r);
    sum += g;
    sumAbs += g.norm();
    if (r > 0 && r < k.support()) ++inside;
  });
  BOOST_TEST_INFO(K::name << " D=" << D);
  BOOST_TEST(inside > 20);
  BOOST_TEST(sumAbs > 0.0);
  BOOST_TEST(sum.norm() <= 1e-12 * sumAbs);
}

// W >= 0, non-increasing, dW/dr <= 0; W, dW/dr, gradW and laplacianW exactly 0
// at and beyond the support, W > 0 just inside it. Exact comparisons: the
// cut-off is a branch, not a limit.
BOOST_AUTO_TEST_CASE_TEMPLATE(W_is_nonnegative_and_compactly_supported, K, AllKernels) {
  constexpr int D = K::dim;
  for (Real h : {0.013, 0.1, 0.7, 3.0}) {
    const K k(h);
    const Real s = k.support();
    BOOST_TEST_INFO(K::name << " D=" << D << " h=" << h);
    Real previous = k.W(0);
    BOOST_TEST(previous > 0.0);
    bool nonnegative = true, nonincreasing = true, slopeNonpositive = true;
    const int n = 20000;
    for (int i = 1; i <= n; ++i) {
      const Real r = 1.5 * s * i / n, w = k.W(r);
      nonnegative = nonnegative && w >= 0 && gradSource(k, r) >= 0 && laplacianSource(k, r) >= 0;
      nonincreasing = nonincreasing && w <= previous;
      slopeNonpositive = slopeNonpositive && k.dWdr(r) <= 0;
      previous = w;
    }
    BOOST_TEST(nonnegative);
    BOOST_TEST(nonincreasing);
    BOOST_TEST(slopeNonpositive);
    BOOST_TEST(k.W(s * (1 - 1e-6)) > 0.0);
    for (Real r : {s, std::nextafter(s, 2 * s), s * (1 + 1e-12), 1.01 * s, 2 * s, 1e3 * s}) {
      Vec<D> rij = Vec<D>::Zero();
      rij(0) = r;
      BOOST_TEST(k.W(r) == 0.0);
      BOOST_TEST(k.dWdr(r) == 0.0);
      BOOST_TEST(k.laplacianW(r) == 0.0);
      BOOST_TEST(k.gradW(rij, r).norm() == 0.0);
      BOOST_TEST(gradSource(k, r) == 0.0);
      BOOST_TEST(laplacianSource(k, r) == 0.0);
    }
    BOOST_TEST(k.gradW(Vec<D>::Zero(), 0.0).norm() == 0.0);
  }
}

// gradW(x, |x|) against the central difference (G(x + e e_k) - G(x - e e_k))
// / (2e) of G = W (spikyW for Mueller) along a direction off the lattice axes,
// e = 1e-4 min(r, h): the Cartesian third derivatives of G(|x|) grow like
// |G'| / r^2 near the origin (spiky's G' does not vanish there), so the step
// shrinks with r. The difference's error (truncation e^2/6 |G'''| plus rounding
// eps |G| / e) is then at most 3e-8 / h^(D+1) (measured, Mueller; 3e-9 for the
// others); tolerance 1e-6 / h^(D+1), against
// gradient components of 1e-4 to 10 / h^(D+1) at the radii tested (each is
// required to exceed 10 tol), so a wrong sign or constant fails.
BOOST_AUTO_TEST_CASE_TEMPLATE(gradW_matches_finite_difference, K, AllKernels) {
  constexpr int D = K::dim;
  const Real h = 0.2;
  const K k(h);
  const Real tol = 1e-6 / std::pow(h, D + 1);
  for (Real f : kGradientFractions) {
    const Vec<D> x = f * k.support() * direction<D>();
    const Real e = 1e-4 * std::min(x.norm(), h);
    const Vec<D> g = k.gradW(x, x.norm());
    for (int a = 0; a < D; ++a) {
      Vec<D> step = Vec<D>::Zero();
      step(a) = e;
      const Real fd =
          (gradSource(k, (x + step).norm()) - gradSource(k, (x - step).norm())) / (2 * e);
      BOOST_TEST_INFO(K::name << " D=" << D << " r/support=" << f << " axis " << a);
      BOOST_TEST(std::abs(g(a) - fd) <= tol);
      BOOST_TEST(std::abs(g(a)) > 10 * tol);
    }
    // dWdr is the radial derivative behind gradW.
    BOOST_TEST(g.norm() == std::abs(k.dWdr(x.norm())), boost::test_tools::tolerance(1e-14));
  }
}

// dWdr_r, the (dW/dr) / r the pair loop forms for every pair (written
// without the division where dW/dr carries a factor r: Wendland C2, the
// Gaussian, the cubic spline's inner part), is dW/dr divided by r: at 200
// radii across the support to 1e-13 relative (a few roundings apart), 0 at
// and beyond the support, and finite at r = 0, where it is the limit the
// division takes at r = 1e-9 h (to 1e-8 relative: the kernels are smooth
// in r^2 there; Mueller's spiky derivative has no finite limit, so the
// default form itself stands at r = 0).
BOOST_AUTO_TEST_CASE_TEMPLATE(dWdr_over_r_is_dWdr_divided_by_r, K, AllKernels) {
  const Real h = 0.2;
  const K k(h);
  for (int s = 1; s < 200; ++s) {
    const Real r = k.support() * s / 200.0;
    BOOST_TEST_INFO(K::name << " D=" << K::dim << " r/support=" << s / 200.0);
    BOOST_TEST(k.dWdr_r(r) == k.dWdr(r) / r, boost::test_tools::tolerance(1e-13));
    BOOST_TEST(k.dWdr_r(r) < 0);
  }
  BOOST_TEST(k.dWdr_r(k.support()) == 0);
  BOOST_TEST(k.dWdr_r(2 * k.support()) == 0);
  const Real tiny = 1e-9 * h;
  BOOST_TEST(std::isfinite(k.dWdr_r(0)));
  BOOST_TEST(k.dWdr_r(0) == k.dWdr(tiny) / tiny, boost::test_tools::tolerance(1e-8));
}

// The SIMD rows' lane forms (pair_loop_blocks.hpp: both parts of the cubic
// spline formed and one selected) give W's and dWdr_r's values, bit for
// bit: at r = 0, across the support (both sides of q = 1 included), at it
// and beyond. A lane form with another order of operations, or one that
// took the wrong part near q = 1, differs.
using RowKernels = std::tuple<sph::CubicSpline<2>, sph::CubicSpline<3>, sph::WendlandC2<2>, sph::WendlandC2<3>>;
BOOST_AUTO_TEST_CASE_TEMPLATE(lane_forms_are_W_and_dWdr_r_bit_for_bit, K, RowKernels) {
  const Real h = 0.013;
  const K k(h);
  std::vector<Real> radii{0, h, std::nextafter(h, 0.0), std::nextafter(h, 1.0), k.support(),
                          std::nextafter(k.support(), 0.0), 3 * h};
  for (int s = 1; s < 1000; ++s) radii.push_back(k.support() * s / 997.0);
  for (const Real r : radii) {
    BOOST_TEST_INFO(K::name << " D=" << K::dim << " r/h=" << r / h);
    BOOST_TEST(k.laneW(r) == k.W(r));
    BOOST_TEST(k.laneDWdr_r(r) == k.dWdr_r(r));
  }
}

// laplacianW against the Cartesian 2D+1-point finite-difference Laplacian of
// L = W (viscosityW for Mueller), e = 1e-4 h, at radii where it is the true,
// smooth Laplacian (see kLaplacianFractions). Error: truncation e^2/12 |L''''|
// plus rounding 4 D eps |L| / e^2; measured at most 7e-6 relative (Mueller's
// viscosity kernel, whose derivatives grow like 1/r^5 towards r = 0) and
// 3e-7 for the others. Tolerance 1e-4 relative to the value plus
// 1e-6 / h^(D+2) absolute (for the cubic's, Wendland's and the Gaussian's
// sign changes, where the value passes through 0); a wrong coefficient of
// the Laplacian is off by O(1).
BOOST_AUTO_TEST_CASE_TEMPLATE(laplacianW_matches_finite_difference, K, AllKernels) {
  constexpr int D = K::dim;
  const Real h = 0.2;
  const K k(h);
  const Real e = 1e-4 * h, absTol = 1e-6 / std::pow(h, D + 2);
  for (Real f : kLaplacianFractions) {
    const Vec<D> x = f * k.support() * direction<D>();
    const Real centre = laplacianSource(k, x.norm());
    Real fd = 0;
    for (int a = 0; a < D; ++a) {
      Vec<D> step = Vec<D>::Zero();
      step(a) = e;
      fd += (laplacianSource(k, (x + step).norm()) - 2 * centre +
             laplacianSource(k, (x - step).norm())) /
            (e * e);
    }
    const Real lap = k.laplacianW(x.norm());
    BOOST_TEST_INFO(K::name << " D=" << D << " r/support=" << f << " lap=" << lap << " fd=" << fd);
    BOOST_TEST(std::abs(lap - fd) <= 1e-4 * std::abs(lap) + absTol);
  }
}

// kernel_constants.csv (exact symbolic integration, computed elsewhere): with
// h chosen != 1, W(0) h^D = sigma = W0_hd; M2 = int (r/h)^2 W dV; the q where
// |dW/dr| peaks and max |dW/dr| h^(D+1).
// Tolerances: sigma, W0_hd are printed to 10 significant digits -> 1e-9
// relative. M2 (8 digits) by radial midpoint quadrature with 4e5 cells (error
// ~1e-10) -> 1e-7 relative. maxgrad by a grid scan of step 1e-6 in q (value
// error ~1e-12 at a smooth maximum; the CSV's 10 digits) -> 1e-8 relative.
// q_maxgrad has 5 decimals, and gaussian_trunc3's 0.70710 is truncated, not
// rounded, from 1/sqrt(2) = 0.7071068 -> 1.1e-5 absolute (1e-5 for the CSV
// plus the 1e-6 grid).
BOOST_AUTO_TEST_CASE_TEMPLATE(constants_match_kernel_constants_csv, K, AllKernels) {
  constexpr int D = K::dim;
  const auto rows = readReference("kernel_constants.csv");
  const Real h = 0.37;
  const K k(h);
  const Real hD = std::pow(h, D), hD1 = std::pow(h, D + 1);
  const Row& row = findRow(rows, referenceName<K>(), D);
  BOOST_TEST_INFO(K::name << " D=" << D);
  BOOST_TEST(number(row, "support") * h == k.support(), boost::test_tools::tolerance(1e-14));
  BOOST_TEST(k.W(0) * hD == number(row, "sigma"), boost::test_tools::tolerance(1e-9));
  BOOST_TEST(k.W(0) * hD == number(row, "W0_hd"), boost::test_tools::tolerance(1e-9));
  const auto m2 = [&](auto w) {
    return radialIntegral<D>([&](Real r) { return (r / h) * (r / h) * w(r); }, k.support(), 400000);
  };
  BOOST_TEST(m2([&](Real r) { return k.W(r); }) == number(row, "M2"),
             boost::test_tools::tolerance(1e-7));

  if constexpr (!IsMuller<K>::value) {
    const auto [qPeak, peak] = maxAbs([&](Real q) { return k.dWdr(q * h); }, k.support() / h, 1e-6);
    BOOST_TEST(std::abs(qPeak - number(row, "q_maxgrad")) <= 1.1e-5);
    BOOST_TEST(peak * hD1 == number(row, "maxgrad_hd1"), boost::test_tools::tolerance(1e-8));
  } else {
    // poly6's slope, from a central difference of W (step 1e-5 h: error
    // ~1e-10 relative) -> 1e-7 relative.
    const Real e = 1e-5 * h;
    const auto [qPeak, peak] =
        maxAbs([&](Real q) { return (k.W(q * h + e) - k.W(std::abs(q * h - e))) / (2 * e); },
               1 - 1e-4, 1e-6);
    BOOST_TEST(std::abs(qPeak - number(row, "q_maxgrad")) <= 1.1e-5);
    BOOST_TEST(peak * hD1 == number(row, "maxgrad_hd1"), boost::test_tools::tolerance(1e-7));

    // The spiky kernel behind gradW and dWdr.
    const Row& spiky = findRow(rows, "spiky", D);
    BOOST_TEST(k.spikyW(0) * hD == number(spiky, "sigma"), boost::test_tools::tolerance(1e-9));
    BOOST_TEST(k.spikyW(0) * hD == number(spiky, "W0_hd"), boost::test_tools::tolerance(1e-9));
    BOOST_TEST(m2([&](Real r) { return k.spikyW(r); }) == number(spiky, "M2"),
               boost::test_tools::tolerance(1e-7));
    const auto [qS, peakS] = maxAbs([&](Real q) { return k.dWdr(q * h); }, 1, 1e-6);
    BOOST_TEST(std::abs(qS - number(spiky, "q_maxgrad")) <= 1.1e-5);
    // |dW_s/dr| peaks at r -> 0 with 3 sigma / h^(D+1) (30/pi in 2D), but the
    // CSV's values are 2.0e-6 relative below that in 1D, 2D and 3D, i.e. they
    // were evaluated at q ~ 1e-6 instead of 0: tolerance 3e-6 relative.
    BOOST_TEST(peakS * hD1 == number(spiky, "maxgrad_hd1"), boost::test_tools::tolerance(3e-6));

    // The viscosity kernel, 3D only: the CSV's 2D row is a different kernel
    // (see csv_2d_viscosity_row_is_a_different_kernel). Its W0 is nan and
    // maxgrad infinite (singular at 0): only sigma and M2 are checked, sigma
    // through the paper's shape f(q) = -q^3/2 + q^2 + 1/(2q) - 1.
    if constexpr (D == 3) {
      const Row& visc = findRow(rows, "viscosity_mueller", D);
      for (Real q : {0.1, 0.5, 0.9}) {
        const Real shape = -q * q * q / 2 + q * q + 1 / (2 * q) - 1;
        BOOST_TEST(k.viscosityW(q * h) * hD / shape == number(visc, "sigma"),
                   boost::test_tools::tolerance(1e-9));
      }
      BOOST_TEST(m2([&](Real r) { return k.viscosityW(r); }) == number(visc, "M2"),
                 boost::test_tools::tolerance(1e-7));
    }
  }
}

// kernel_constants.csv's viscosity_mueller 2D row (sigma = 10/(3 pi),
// M2 = 0.0793650794) is the 3D kernel's shape renormalised over the disc. Its
// 2D Laplacian is 5/(3 pi h^4)(1 + 8q^3 - 9q^4)/q^3, not the linear
// 40/(pi h^5)(h - r) the issue asks for; Muller<2> uses the log-shaped kernel
// whose Laplacian that is (derivation in muller.hpp), and its M2 is 5/42.
// This test pins the discrepancy: the CSV row normalises the 3D shape (radial
// quadrature, 1e-7 as above); its finite-difference Laplacian (e = 1e-4 h,
// ~1e-6 relative error) is 37.0 at q = 0.25 and 1.46 at q = 0.8 against
// laplacianW's 9.55 and 2.55 (h = 1), far more than any numerical error
// (threshold 10%; the two cross near q = 0.5, so that point is not used);
// and our kernel's M2 is not the CSV's.
BOOST_AUTO_TEST_CASE(csv_2d_viscosity_row_is_a_different_kernel) {
  const auto rows = readReference("kernel_constants.csv");
  const Row& row = findRow(rows, "viscosity_mueller", 2);
  const Real h = 1, sigma = number(row, "sigma");
  const auto csvKernel = [&](Real r) {
    const Real q = r / h;
    return q < 1 ? sigma / (h * h) * (-q * q * q / 2 + q * q + 1 / (2 * q) - 1) : 0.0;
  };
  BOOST_TEST(radialIntegral<2>(csvKernel, h, 200000) == 1.0, boost::test_tools::tolerance(1e-7));
  const sph::Muller<2> k(h);
  const Real e = 1e-4 * h;
  for (Real q : {0.25, 0.8}) {
    const Real r = q * h;
    const Real csvLaplacian = (csvKernel(r + e) - 2 * csvKernel(r) + csvKernel(r - e)) / (e * e) +
                              (csvKernel(r + e) - csvKernel(r - e)) / (2 * e) / r;
    BOOST_TEST_MESSAGE("CSV 2D viscosity kernel: laplacian("
                       << q << " h) = " << csvLaplacian
                       << ", Muller<2>::laplacianW = " << k.laplacianW(r));
    BOOST_TEST(std::abs(csvLaplacian - k.laplacianW(r)) > 0.1 * k.laplacianW(r));
  }
  const Real ourM2 = radialIntegral<2>([&](Real s) { return s * s * k.viscosityW(s); }, h, 200000);
  BOOST_TEST(std::abs(ourM2 - number(row, "M2")) > 0.1 * ourM2);
}

// two_particle_examples.csv (m = 1, h = 1, derived analytically elsewhere):
// W(0), W(r), dW/dr(r) and rho_i = m (W(0) + W(r)) for the cubic spline and
// Wendland C2 in 2D and 3D (1D rows skipped). Printed to 6 decimals ->
// absolute tolerance 1e-6 (half a unit in the last place is 5e-7). All 12
// rows must be found.
BOOST_AUTO_TEST_CASE(two_particle_examples_csv) {
  const auto rows = readReference("two_particle_examples.csv");
  int checked = 0;
  const auto check = [&](const auto& k, const Row& row) {
    const Real r = number(row, "r/h") * k.h();
    BOOST_TEST_INFO(row.at("kernel") << " dim " << row.at("dim") << " r/h " << row.at("r/h"));
    BOOST_TEST(std::abs(k.W(0) - number(row, "W(0)")) <= 1e-6);
    BOOST_TEST(std::abs(k.W(r) - number(row, "W(r)")) <= 1e-6);
    BOOST_TEST(std::abs(k.dWdr(r) - number(row, "dW/dr(r)")) <= 1e-6);
    BOOST_TEST(std::abs(k.W(0) + k.W(r) - number(row, "rho_i")) <= 1e-6);
    ++checked;
  };
  for (const auto& row : rows) {
    const std::string kernel = row.at("kernel");
    const int dim = std::stoi(row.at("dim"));
    if (dim == 1) continue;
    if (kernel == "cubic" && dim == 2) check(sph::CubicSpline<2>(1.0), row);
    if (kernel == "cubic" && dim == 3) check(sph::CubicSpline<3>(1.0), row);
    if (kernel == "wendlandC2" && dim == 2) check(sph::WendlandC2<2>(1.0), row);
    if (kernel == "wendlandC2" && dim == 3) check(sph::WendlandC2<3>(1.0), row);
  }
  BOOST_TEST(checked == 12);
}

BOOST_AUTO_TEST_SUITE_END()
