// Particle shifting (particle_shifting.hpp) and the Taylor-Green initial
// flow (initial_flow = taylor_green): a perfect lattice is left alone (its
// concentration gradient is zero by symmetry), a disordered one is made
// more even, a free surface is not shifted, and the initial vortex is the
// formula it claims (Taylor & Green 1937; the decay itself is checked
// against tests/reference/tgv2d_decay.csv by validation/validate.py
// taylor_green, ctest label validation).
#include "sph/model_registry.hpp"
#include "stored_precision.hpp"
#include "refused_naming.hpp"
#include "test_support.hpp"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace sph;

namespace {

// A fully periodic box of 20 x 20 particles moving with a uniform velocity
// (no force acts on a uniform lattice in uniform motion), shifting on.
CaseConfig periodicLattice() {
  CaseConfig c = test::bareWcsph(2);
  c.kernel = "wendland_c2";
  c.spacing = 0.05;
  c.h = 0.075;
  c.periodic = "xy";
  c.domainMin = {0, 0};
  c.domainMax = {1, 1};
  c.blockMin = c.domainMin;
  c.blockMax = c.domainMax;
  c.velocity = {1, 0.5};
  c.eos = "linear";
  c.k = 100;
  c.density = "continuity";
  c.shifting = "fickian";
  c.dt = 1e-3;
  return c;
}

// Spread of the particles' kernel sums sum_j V_j W_ij (0 on a lattice).
Real kernelSumSpread(const Scene<2>& s, Real h) {
  const auto& P = s.particles();
  const WendlandC2<2> W(h);
  const PeriodicBox<2> box = s.periodicBox();
  std::vector<Real> sums(P.fluidCount(), 0);
  for (std::size_t i = 0; i < P.fluidCount(); ++i)
    for (std::size_t j = 0; j < P.fluidCount(); ++j) {
      const Real r = box.minimumImage(Vec<2>(P.x[i] - P.x[j])).norm();
      if (r < 2 * h) sums[i] += P.m[j] / P.rho[j] * W.W(r);
    }
  Real mean = 0, var = 0;
  for (Real x : sums) mean += x;
  mean /= static_cast<Real>(sums.size());
  for (Real x : sums) var += (x - mean) * (x - mean);
  return std::sqrt(var / static_cast<Real>(sums.size())) / mean;
}

// The scene of c with its particles jittered by up to `fraction` of a
// spacing (seeded); a periodic box wraps them as the scene sorts them.
Scene<2> jitteredScene(const CaseConfig& c, Real fraction, unsigned seed) {
  validateCase(c);
  const ResolvedCase cd = withDefaults(c);
  InitialState<2> init = buildInitialState<2>(cd);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> u(-fraction * c.spacing, fraction * c.spacing);
  for (auto& x : init.particles.x) x += Vec<2>(u(rng), u(rng));
  Scene<2> s = makeScene<2>(cd, std::move(init));
  BOOST_REQUIRE(!s.initialise(false));
  return s;
}

// Particle shifting's sums by brute force over every pair (minimum image)
// at the particles' state: sum_j V_j W_ij with the particle's own term, and
// grad C_i = sum_j V_j (1 + 0.2 (W_ij / W(dx))^4) grad_i W_ij.
struct ShiftSums {
  std::vector<Real> sum;
  std::vector<Vec<2>> grad;
};
ShiftSums bruteShiftSums(const Scene<2>& s, const CaseConfig& c) {
  const auto& P = s.particles();
  const WendlandC2<2> W(c.h);
  const PeriodicBox<2> box = s.periodicBox();
  const Real invWdx = 1 / W.W(c.spacing);
  ShiftSums out{std::vector<Real>(P.fluidCount()), std::vector<Vec<2>>(P.fluidCount())};
  for (std::size_t i = 0; i < P.fluidCount(); ++i) {
    Real sum = P.m[i] / P.rho[i] * W.W(0);
    Vec<2> grad = Vec<2>::Zero();
    for (std::size_t j = 0; j < P.fluidCount(); ++j) {
      const Vec<2> rij = box.minimumImage(Vec<2>(P.x[i] - P.x[j]));
      const Real r = rij.norm();
      if (j == i || r >= 2 * c.h) continue;
      const Real Vj = P.m[j] / P.rho[j], q = W.W(r) * invWdx;
      sum += Vj * W.W(r);
      grad += Vj * (1 + 0.2 * q * q * q * q) * (W.dWdr(r) / r) * rij;
    }
    out.sum[i] = sum;
    out.grad[i] = grad;
  }
  return out;
}

// The largest difference of the particles' shiftSum from the brute-force sums.
Real worstShiftSum(const Scene<2>& s, const ShiftSums& brute) {
  Real worst = 0;
  for (std::size_t i = 0; i < brute.sum.size(); ++i)
    worst = std::max(worst, std::abs(s.particles().shiftSum[i] - brute.sum[i]));
  return worst;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(shifting)

// On a perfect lattice grad C = 0: the particles move with the flow only,
// every pair distance stays what it was (to round-off), after 50 steps.
BOOST_AUTO_TEST_CASE(a_perfect_lattice_is_not_shifted) {
  Scene<2> s = test::sceneOf<2>(periodicLattice());
  const auto x0 = s.particles().x;
  const auto id0 = s.particles().id;
  for (int k = 0; k < 50; ++k) BOOST_REQUIRE(!s.step());
  const auto& P = s.particles();
  // Positions by original id.
  std::vector<Vec<2>> now(P.size());
  for (std::size_t i = 0; i < P.size(); ++i) now[P.id[i]] = P.x[i];
  std::vector<Vec<2>> then(x0.size());
  for (std::size_t i = 0; i < x0.size(); ++i) then[id0[i]] = x0[i];
  const PeriodicBox<2> box = s.periodicBox();
  const Vec<2> move = box.minimumImage(Vec<2>(now[0] - then[0]));
  Real worst = 0;
  for (std::size_t i = 0; i < now.size(); ++i)
    worst = std::max(worst, box.minimumImage(Vec<2>(now[i] - then[i] - move)).norm());
  BOOST_TEST_MESSAGE("perfect lattice, 50 shifted steps: worst departure from a rigid move " << worst << " m");
  BOOST_TEST(worst < 1e-12);
  BOOST_TEST(std::abs(move[0] - 0.05) < 1e-9);  // 50 steps of 1e-3 s at 1 m/s
}

// The force pass leaves the shift's sums in the particles
// (terms/shifting_sums.hpp): on a jittered periodic lattice they are the
// brute-force sums, to 1e-12 of their scale (other summation orders).
BOOST_AUTO_TEST_CASE(the_force_pass_takes_the_shift_sums) {
  const CaseConfig c = periodicLattice();
  const Scene<2> s = jitteredScene(c, 0.15, 11);
  const auto& P = s.particles();
  BOOST_TEST_REQUIRE(P.shiftSum.size() >= P.fluidCount());
  const ShiftSums brute = bruteShiftSums(s, c);
  Real worstGrad = 0, gradScale = 0;
  for (std::size_t i = 0; i < P.fluidCount(); ++i) {
    worstGrad = std::max(worstGrad, (P.shiftGrad[i] - brute.grad[i]).norm());
    gradScale = std::max(gradScale, brute.grad[i].norm());
  }
  const Real worstSum = worstShiftSum(s, brute);
  BOOST_TEST_MESSAGE("shift sums against brute force: " << worstSum << " (sum), " << worstGrad << " of "
                                                        << gradScale << " (grad C)");
  BOOST_TEST(gradScale > 1);  // the jitter gives a gradient to check
  BOOST_TEST(worstSum < 1e-12);
  BOOST_TEST(worstGrad < 1e-12 * gradScale);
}

// The shift takes them only while they are the sums of the particles'
// state: not after a step whose density re-initialisation (Shepard, every
// 3 steps) changed rho after the evaluation, when they are stale (they
// differ from the brute-force sums by far more than round-off). The
// Taylor-Green flow makes rho uneven, so that Shepard changes it.
BOOST_AUTO_TEST_CASE(the_shift_takes_the_sums_only_at_their_state) {
  CaseConfig c = periodicLattice();
  c.velocity.clear();
  c.initialFlow = "taylor_green";
  c.densityReinit = "shepard";
  c.densityReinitEvery = 3;
  Scene<2> s = jitteredScene(c, 0.15, 11);
  BOOST_TEST(s.model().shiftSumsAtState());
  for (int step = 1; step <= 4; ++step) {
    BOOST_REQUIRE(!s.step());
    const bool reinitialised = step == 3;
    const Real worst = worstShiftSum(s, bruteShiftSums(s, c));
    BOOST_TEST_MESSAGE("step " << step << ": shift sums " << worst << " from brute force");
    BOOST_TEST(s.model().shiftSumsAtState() == !reinitialised, "step " << step);
    if (reinitialised) BOOST_TEST(worst > 1e-6);
    else BOOST_TEST(worst < 1e-12);
  }
}

// A lattice jittered by 0.15 dx: the shift evens it out (the spread of
// the kernel sums falls), where the same run without shifting does not.
BOOST_AUTO_TEST_CASE(a_disordered_lattice_becomes_more_even) {
  auto spreadAfter = [](bool shift, Real& before) {
    CaseConfig c = periodicLattice();
    if (!shift) c.shifting = "none";
    Scene<2> s = jitteredScene(c, 0.15, 7);
    before = kernelSumSpread(s, c.h);
    for (int k = 0; k < 200; ++k) BOOST_REQUIRE(!s.step());
    return kernelSumSpread(s, c.h);
  };
  Real before = 0, beforeNone = 0;
  const Real shifted = spreadAfter(true, before), unshifted = spreadAfter(false, beforeNone);
  BOOST_TEST_MESSAGE("kernel-sum spread: jittered " << before << ", 200 steps with shifting " << shifted
                                                    << ", without " << unshifted);
  BOOST_TEST(before == beforeNone);
  BOOST_TEST(shifted < 0.5 * before);
  BOOST_TEST(shifted < 0.5 * unshifted);
}

// A free block in a large box: its surface particles (kernel sum < 0.9)
// stay where the flow takes them; only the interior may shift.
BOOST_AUTO_TEST_CASE(the_free_surface_is_not_shifted) {
  CaseConfig c = periodicLattice();
  c.periodic = "none";
  c.domainMin = {-1, -1};
  c.domainMax = {2, 2};
  c.blockMin = {0, 0};
  c.blockMax = {0.5, 0.5};
  Scene<2> s = jitteredScene(c, 0.1, 3);
  auto P = s.particles();  // copy: positions and the neighbour list at x^n
  ParticleShifting<2> shift(makeKernel<2>(withDefaults(c)), 4, c.spacing, c.rho0);
  shift.apply(P, s.neighbours(), 1e-3);
  std::size_t edge = 0, interior = 0, movedInterior = 0;
  for (std::size_t i = 0; i < P.fluidCount(); ++i) {
    const Vec<2>& x = s.particles().x[i];
    const bool nearSurface = x.minCoeff() < 2 * c.h || x.maxCoeff() > 0.5 - 2 * c.h;
    const bool moved = (P.x[i] - x).norm() > 0;
    if (x.minCoeff() < c.spacing || x.maxCoeff() > 0.5 - c.spacing) {
      ++edge;
      BOOST_TEST(!moved, "surface particle " << i << " at " << x.transpose() << " was shifted");
    } else if (!nearSurface) {
      ++interior;
      movedInterior += moved;
    }
  }
  BOOST_TEST(edge > 30u);
  BOOST_TEST(movedInterior == interior);
}

// initial_flow = taylor_green: the velocity and pressure of each particle
// are the vortex formula at its position (continuity density: the EOS of
// the density it was given returns the pressure exactly, to round-off).
BOOST_AUTO_TEST_CASE(taylor_green_initial_field_is_the_formula) {
  CaseConfig c = periodicLattice();
  c.velocity.clear();
  c.shifting = "none";
  c.initialFlow = "taylor_green";
  c.flowSpeed = 2;
  c.rho0 = 1000;
  Scene<2> s = test::sceneOf<2>(c);
  const auto& P = s.particles();
  const Real pi = std::acos(Real(-1)), U = c.flowSpeed;
  Real worstV = 0, worstP = 0;
  for (std::size_t i = 0; i < P.fluidCount(); ++i) {
    const Real x = P.x[i][0], y = P.x[i][1];
    const Vec<2> v(-U * std::cos(2 * pi * x) * std::sin(2 * pi * y), U * std::sin(2 * pi * x) * std::cos(2 * pi * y));
    const Real p = -c.rho0 * U * U / 4 * (std::cos(4 * pi * x) + std::cos(4 * pi * y));
    worstV = std::max(worstV, (P.v[i] - v).norm() / U);
    worstP = std::max(worstP, std::abs(P.p[i] - p) / (c.rho0 * U * U));
  }
  BOOST_TEST(worstV < 1e-12);
  BOOST_TEST(worstP < test::storedTolerance(1e-9));  // (p is stored narrow)
}

BOOST_AUTO_TEST_CASE(bad_shifting_and_initial_flow_input_is_refused) {
  CaseConfig c = periodicLattice();
  c.spacing = 0;
  c.blockMin.clear();
  c.blockMax.clear();
  c.points = {0.5, 0.5};
  BOOST_TEST(test::refusedNaming(c, "shifting"));  // needs the spacing
  CaseConfig t = periodicLattice();
  t.initialFlow = "taylor_green";
  t.periodic = "x";
  BOOST_TEST(test::refusedNaming(t, "initial_flow"));  // needs periodic xy
  t.periodic = "xy";
  t.domainMax = {1, 0.5};
  t.blockMax = {1, 0.5};
  BOOST_TEST(test::refusedNaming(t, "square"));
  CaseConfig b = periodicLattice();
  b.eos = "polytropic";
  b.backgroundPressure = 10;
  BOOST_TEST(test::refusedNaming(b, "background_pressure"));  // linear or tait only
}

BOOST_AUTO_TEST_SUITE_END()
