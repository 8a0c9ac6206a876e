// Continuity density and density diffusion, and the EOS pieces they use:
// - d rho/dt of the continuity equation equals the time derivative of the
//   summation density (an identity of the chain rule, edges included),
//   checked by a central difference of the summation density;
// - density diffusion leaves a uniform state unchanged (both forms) and a
//   hydrostatic state unchanged (Fourtakas), while the Molteni form does not
//   (the test can fail);
// - momentum is conserved with continuity and diffusion;
// - Tait with gamma = 7 by multiplication equals pow(); every EOS inverse
//   inverts;
// - the density-rate walk in SIMD blocks (passes/density_rate_blocks.hpp)
//   gives the scalar pair loop's rates up to the order of the sum.
#include "sph/boundaries/wall_sums.hpp"
#include "sph/passes/density_rate_blocks.hpp"
#include "sph/passes/seed_forces.hpp"
#include "sph/terms/continuity_density.hpp"
#include "sph/terms/density_diffusion.hpp"
#include "sph/terms/equation_of_state.hpp"
#include "reordered_sum_bound.hpp"
#include "test_support.hpp"

#include <limits>
#include <random>

using namespace sph;

namespace {

// A jittered lattice block, no walls, no gravity.
CaseConfig block(const std::string& density) {
  CaseConfig c = test::bareWcsph(2);
  c.kernel = "wendland_c2";
  c.spacing = 0.01;
  c.h = 0.015;
  c.eos = "linear";
  c.k = 100;
  c.density = density;
  c.blockMin = {0, 0};
  c.blockMax = {0.2, 0.2};
  return c;
}

template <class F>
void forEachParticle(Scene<2>& s, F f) {
  auto& P = s.particles();
  for (std::size_t i = 0; i < P.size(); ++i) f(P, i);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(continuity)

// rho_i(t) = sum_j m_j W(x_i(t) - x_j(t)) with x(t) = x0 + t v: its
// derivative at t = 0 is sum_j m_j (v_i - v_j) . grad_i W_ij exactly. A
// central difference with step 1e-6 s agrees to O(eps^2) plus round-off:
// 1e-6 of the largest rate.
// The diffusion term derives its constants from the chosen form (Molteni &
// Colagrossi 2009 eq. 9; Fourtakas et al. 2019): 2 delta h c0, eta^2 =
// 0.01 h^2, and rho0 g / c0^2 for the hydrostatic part. Worked by hand:
// delta 0.1, h 0.02 m, c0 40 m/s -> 0.16 m^2/s; eta^2 4e-6 m^2; rho0 1000,
// g -9.81 -> -6.13125 kg/m^4. The model's term is the same one.
BOOST_AUTO_TEST_CASE(diffusion_derives_its_coefficient) {
  const Vec<2> g(0, -9.81);
  const auto fourtakas = DensityDiffusion<2>::build({0.1, true, "x"}, 0.02, 40, 1000, g);
  BOOST_TEST(fourtakas.coefficient == 0.16, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(fourtakas.eta2 == 4e-6, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(fourtakas.hydrostatic[1] == -6.13125, boost::test_tools::tolerance(1e-12));
  const auto molteni = DensityDiffusion<2>::build({0.1, false, "x"}, 0.02, 40, 1000, g);
  BOOST_TEST(molteni.hydrostatic.isZero());
  BOOST_TEST(!DensityDiffusion<2>::build({0, true, "x"}, 0.02, 40, 1000, g).active());
  // Through the registry: the case's diffusion key picks the form.
  CaseConfig c = block("continuity");
  c.delta = 0.1;
  c.diffusion = "molteni";
  BOOST_TEST(!densityDiffusion(c).hydrostatic);
  BOOST_TEST(densityDiffusion(c).delta == 0.1);
  c.diffusion = "fourtakas";
  BOOST_TEST(densityDiffusion(c).hydrostatic);
}

// With pressures clamped at rho_c (negative_pressure = clamp) the diffusion
// reads max(rho, rho_c): two particles of a splash, both below rho_c, do
// not diffuse at all without gravity (with it, by the Fourtakas form's
// hydrostatic part alone); against a denser one, a particle below rho_c counts as
// rho_c. Without gravity psi_ij is the density difference alone, so the
// clamped rate is the unclamped one scaled by the ratio of the differences
// read (worked by hand: 300 against 600 -> 0; 300 against 1010 with rho_c =
// 1000 -> 10/710 of the unclamped rate; both above rho_c -> unchanged).
BOOST_AUTO_TEST_CASE(clamped_pressures_diffuse_the_density_the_pressure_reads) {
  const Vec<2> none = Vec<2>::Zero();
  const DensityDiffusionChoice choice{0.1, true, "x"};
  const auto free = DensityDiffusion<2>::build(choice, 0.02, 40, 1000, none);
  const auto clamped = DensityDiffusion<2>::build(choice, 0.02, 40, 1000, none, 1000);
  BOOST_TEST(clamped.floor == 1000.0);
  BOOST_TEST(free.floor == -std::numeric_limits<Real>::infinity());
  CaseConfig c = block("continuity");
  Scene<2> s = test::sceneOf<2>(c);
  Particles<2>& P = s.particles();
  Pair<2> pair{0, 1, Vec<2>(0.01, 0.0), 0.01, 0.25, 0, Vec<2>(-3e4, 0.0), Vec<2>(-3e4, 0.0)};
  auto rate = [&](const DensityDiffusion<2>& d, Real rhoi, Real rhoj) {
    P.rho[0] = rhoi, P.rho[1] = rhoj;
    PairRates<2> r;
    d.add(pair, P, r);
    return r.drho;
  };
  BOOST_TEST(rate(free, 300, 600) != 0.0);
  BOOST_TEST(rate(clamped, 300, 600) == 0.0);
  BOOST_TEST(rate(clamped, 600, 300) == 0.0);
  BOOST_TEST(rate(clamped, 300, 1010) == rate(free, 300, 1010) * 10 / 710, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(rate(clamped, 1005, 1010) == rate(free, 1005, 1010));
}

// The model sets that floor from the case: two fluid particles at rest,
// 0.01 m apart, both below rho0 (300 and 600 kg/m^3), no gravity, so
// d rho/dt is the diffusion alone. Negative pressures kept: they diffuse
// (a rate of order 2 delta h c0 300 V |grad W| / r); clamped by the key or
// by eos = linear_clamped: exactly 0.
BOOST_AUTO_TEST_CASE(the_model_floors_the_diffusion_where_pressures_are_clamped) {
  auto rates = [](const std::string& eos, const std::string& negative) {
    CaseConfig c = test::bareWcsph(2);
    c.kernel = "wendland_c2", c.spacing = 0.01, c.h = 0.015, c.rho0 = 1000;
    c.eos = eos, c.c0 = 20, c.k = 400, c.negativePressure = negative;
    c.density = "continuity", c.delta = 0.1;
    c.points = {0, 0, 0.01, 0};
    Scene<2> s = test::sceneOf<2>(c);
    Particles<2>& P = s.particles();
    for (std::size_t i = 0; i < P.fluidCount(); ++i) P.rho[i] = P.id[i] == 0 ? 300 : 600;
    BOOST_REQUIRE(!s.initialise(false));  // evaluated again with these densities
    BOOST_REQUIRE(P.fluidCount() == 2u);
    const std::size_t light = P.id[0] == 0 ? 0 : 1;
    return std::make_pair(P.drho[light], P.drho[1 - light]);  // (300's rate, 600's)
  };
  const auto kept = rates("tait", "none");
  BOOST_TEST(kept.first > 1.0);    // the lighter drawn up ...
  BOOST_TEST(kept.second < -1.0);  // ... the denser down
  const auto clamped = rates("tait", "clamp");
  BOOST_TEST(clamped.first == 0.0);
  BOOST_TEST(clamped.second == 0.0);
  const auto linear = rates("linear_clamped", "none");
  BOOST_TEST(linear.first == 0.0);
  BOOST_TEST(linear.second == 0.0);
}

BOOST_AUTO_TEST_CASE(rate_equals_the_derivative_of_summation_density) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> jitter(-0.002, 0.002);
  auto velocity = [](const Vec<2>& x) { return Vec<2>(std::sin(20 * x[1]), 0.5 * x[0] * x[0] - x[1]); };
  CaseConfig rate = block("continuity");
  Scene<2> s = test::sceneOf<2>(rate);
  forEachParticle(s, [&](Particles<2>& P, std::size_t i) {
    P.x[i] += Vec<2>(jitter(rng), jitter(rng));
    P.v[i] = velocity(P.x[i]);
  });
  // A scene of these positions and velocities; its initial evaluation gives
  // d rho/dt; two scenes of the shifted positions give rho by summation.
  auto rebuilt = [&](const std::string& density, Real t) {
    CaseConfig c = block(density);
    c.blockMin.clear(), c.blockMax.clear();
    for (std::size_t i = 0; i < s.particles().size(); ++i) {
      const Vec<2> x = s.particles().x[i] + t * s.particles().v[i];
      c.points.insert(c.points.end(), {x[0], x[1]});
    }
    validateCase(c);
    InitialState<2> init = buildInitialState<2>(withDefaults(c));
    for (std::size_t i = 0; i < init.particles.size(); ++i) {
      init.particles.v[i] = s.particles().v[i];
      init.particles.m[i] = 1000 * 0.01 * 0.01;
      init.particles.rho[i] = 1000;
    }
    Scene<2> out = makeScene<2>(withDefaults(c), std::move(init));
    BOOST_REQUIRE(!out.initialise(false));
    return out;
  };
  const Scene<2> now = rebuilt("continuity", 0);
  const Real eps = 1e-6;
  const Scene<2> ahead = rebuilt("summation", eps), behind = rebuilt("summation", -eps);
  auto byId = [](const Scene<2>& sc, auto field) {
    std::map<std::int64_t, Real> m;
    for (std::size_t i = 0; i < sc.particles().size(); ++i) m[sc.particles().id[i]] = field(sc.particles(), i);
    return m;
  };
  const auto drho = byId(now, [](const Particles<2>& P, std::size_t i) { return P.drho[i]; });
  const auto rhoA = byId(ahead, [](const Particles<2>& P, std::size_t i) { return P.rho[i]; });
  const auto rhoB = byId(behind, [](const Particles<2>& P, std::size_t i) { return P.rho[i]; });
  Real scale = 0, worst = 0;
  for (const auto& [id, r] : drho) scale = std::max(scale, std::abs(r));
  BOOST_TEST_REQUIRE(scale > 1.0);  // the field does compress the particles
  for (const auto& [id, r] : drho) worst = std::max(worst, std::abs((rhoA.at(id) - rhoB.at(id)) / (2 * eps) - r));
  BOOST_TEST(worst < 1e-6 * scale, "worst " << worst << " of " << scale);
}

// At rest (v = 0) the continuity term is zero, so d rho/dt is the diffusion
// alone. Uniform density: psi = 0 for both forms. Hydrostatic density for
// the linear EOS, rho = rho0 (1 + g (H - y)/k): psi = 0 for fourtakas to
// round-off (1e-9 of the Molteni value), while molteni diffuses.
BOOST_AUTO_TEST_CASE(diffusion_keeps_uniform_and_hydrostatic_states) {
  auto rates = [](const std::string& form, bool hydrostatic) {
    CaseConfig c = block("continuity");
    c.delta = 0.1;
    c.diffusion = form;
    c.g = hydrostatic ? 9.81 : 0;
    Scene<2> s = test::sceneOf<2>(c);
    for (std::size_t i = 0; i < s.particles().size(); ++i)
      s.particles().rho[i] = hydrostatic ? 1000 * (1 + 9.81 * (0.2 - s.particles().x[i][1]) / 100) : 1000;
    // Evaluate again on these densities (the particles do not move: dt = 0).
    CaseConfig again = c;
    InitialState<2> init;
    init.particles = s.particles();
    Scene<2> t = makeScene<2>(withDefaults(again), std::move(init));
    BOOST_REQUIRE(!t.initialise(false));
    Real worst = 0;
    for (std::size_t i = 0; i < t.particles().size(); ++i) worst = std::max<Real>(worst, std::abs(t.particles().drho[i]));
    return worst;
  };
  BOOST_TEST(rates("molteni", false) < 1e-9);
  BOOST_TEST(rates("fourtakas", false) < 1e-9);
  const Real molteni = rates("molteni", true), fourtakas = rates("fourtakas", true);
  BOOST_TEST(molteni > 1e-3);
  BOOST_TEST(fourtakas < 1e-9 * molteni + 1e-12);
}

// A jittered block with random velocities: continuity, diffusion and
// Monaghan viscosity keep total momentum to round-off (pairwise
// antisymmetric forces; the density terms move no momentum).
BOOST_AUTO_TEST_CASE(momentum_is_conserved_with_continuity_and_diffusion) {
  CaseConfig c = block("continuity");
  c.delta = 0.1;
  c.viscosity = "monaghan";
  c.eos = "tait", c.c0 = 20, c.rho0 = 1000;
  c.dt = 1e-4;
  Scene<2> s = test::sceneOf<2>(c);
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> u(-1, 1);
  for (auto& v : s.particles().v) v = Vec<2>(u(rng), u(rng));
  const auto [p0, scale] = test::momentum(s.particles());
  for (int n = 0; n < 100; ++n) BOOST_REQUIRE(!s.step());
  BOOST_TEST((test::momentum(s.particles()).first - p0).norm() < 1e-12 * scale);
}

BOOST_AUTO_TEST_CASE(tait_by_multiplication_equals_pow_and_every_eos_inverts) {
  const TaitEos whole(1000, 20, 7), fractional(1000, 20, 7.5);
  BOOST_TEST(whole.whole);
  BOOST_TEST(!fractional.whole);
  for (Real rho : {950.0, 999.0, 1000.0, 1003.0, 1050.0}) {
    const Real B = 1000 * 20 * 20 / 7.0;
    BOOST_TEST(whole.pressure(rho) == B * (std::pow(rho / 1000, 7) - 1), boost::test_tools::tolerance(1e-12));
    BOOST_TEST(whole.soundSpeed(rho) == 20 * std::pow(rho / 1000, 3), boost::test_tools::tolerance(1e-13));
    BOOST_TEST(whole.density(whole.pressure(rho)) == rho, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(fractional.density(fractional.pressure(rho)) == rho, boost::test_tools::tolerance(1e-12));
    const LinearEos lin{100, 1000};
    BOOST_TEST(lin.density(lin.pressure(rho)) == rho, boost::test_tools::tolerance(1e-14));
    const PolytropicEos poly{0.1, 1};
    BOOST_TEST(poly.density(poly.pressure(rho)) == rho, boost::test_tools::tolerance(1e-12));
  }
}

// The blocks' rates against the scalar pair loop's (pair_loop.hpp, the
// density-rate pass's packs), on a dam-break column after 60 steps (the
// particles disordered, the list's skin holding pairs beyond the support,
// rows of every length), with dummy walls (walls in the sums) and dynamic
// walls (their own rates), with each diffusion form and none, with
// Wendland C2 and the cubic spline. Tolerance:
// the blocks add the same terms in another order, so each rate is within
// 4 n eps sum_j |t_j| of the scalar loop's (reordered_sum_bound.hpp; the
// largest difference is printed against it). The wall neighbours take the
// blocks too (continuity alone). A block that dropped the diffusion,
// diffused against a wall, or counted a padding lane (a repeat of the
// block's first pair), would be off by a whole term. (A pair beyond the support adds an
// exact 0 either way: the kernel's gradient is 0 there.) (The pass uses the blocks only where they pay, with AVX2 or
// AVX-512; the function is compared here on every build.)
template <int D, class K>
void checkDensityRateBlocks(const char* kernelName) {
  for (const char* boundary : {"dummy", "dynamic"}) {
    CaseConfig c = test::waterColumn(boundary, 0.3, D);
    c.kernel = kernelName;
    const Scene<D> s = test::settled<D>(c, 60);
    const Particles<D>& P = s.particles();
    const K kernel(c.h);
    const WallSums walls{true, std::string(boundary) == "dynamic"};
    for (int form = 0; form < 4; ++form) {  // none, Molteni, Fourtakas, Fourtakas with pressures clamped at rho0
      DensityDiffusionChoice choice;
      choice.delta = form == 0 ? 0.0 : 0.1;
      choice.hydrostatic = form >= 2;
      const Real zeroPressure = form == 3 ? c.rho0 : -std::numeric_limits<Real>::infinity();
      const DensityDiffusion<D> diffusion =
          DensityDiffusion<D>::build(choice, c.h, c.c0, c.rho0, gravityVector<D>(c), zeroPressure);
      if (form == 3) {  // the floor is read: some fluid particles of the column are below rho0
        std::size_t below = 0;
        for (std::size_t i = 0; i < P.fluidCount(); ++i) below += P.rho[i] < c.rho0;
        BOOST_TEST_INFO(D << "D, " << boundary << ": " << below << " fluid particles below rho0");
        BOOST_TEST(below > 0u);
      }
      Particles<D> lender = P;  // lends the arrays the loops' prologue fills
      const ParticlePrologue<D> prologue = pairArrays(lender, false, diffusion.active(), true);
      DensityDiffusion<D> here = diffusion;
      here.volume = prologue.volume;
      Particles<D> blocks = P, scalar = P;
      std::fill(blocks.drho.begin(), blocks.drho.end(), -1.0);
      std::fill(scalar.drho.begin(), scalar.drho.end(), -2.0);
      const ContinuityDensity rate{true};
      Particles<D> magnitude = P;
      const auto fluidPairs = std::make_tuple(rate, here);
      const auto wallPairs = std::make_tuple(rate);
      const auto wallOwn = std::make_tuple(ContinuityDensity{walls.densityRates});
      auto loop = [&](Particles<D>& Q, const auto& fluid, const auto& wall, const auto& own, const auto& fluidRow,
                      const auto& wallRow) {
        runPairLoop(Q, s.neighbours(), kernel, kernel.support(), fluid, wall, own, DensityRateEpilogue<D>{},
                    DensityRateEpilogue<D>{}, PairLoopParts{walls.inSums, walls.densityRates},
                    NoGradientCorrection{}, prologue, fluidRow, wallRow);
      };
      // The wall neighbours in blocks too: continuity alone, as the pass.
      const Real* m = realMasses(blocks, prologue);
      loop(blocks, fluidPairs, wallPairs, wallOwn, DensityRateRow<D, K>{blocks, kernel, here, m},
           DensityRateRow<D, K, false>{blocks, kernel, here, m});
      loop(scalar, fluidPairs, wallPairs, wallOwn, PairByPair{}, PairByPair{});
      loop(magnitude, test::magnitudesOf(fluidPairs), test::magnitudesOf(wallPairs), test::magnitudesOf(wallOwn),
           PairByPair{}, PairByPair{});
      std::size_t beyond = 0, differ = 0, moving = 0;
      Real worst = 0;  // the largest difference over its bound
      const std::size_t n = walls.densityRates ? P.size() : P.fluidCount();
      for (std::size_t i = 0; i < n; ++i) {
        const typename NeighbourList<D>::Row row = s.neighbours().row(i);
        const Real bound = test::reorderedSumBound(row.end - row.begin, magnitude.drho[i]);
        const Real difference = std::abs(blocks.drho[i] - scalar.drho[i]);
        beyond += !(difference <= bound);
        if (bound > 0) worst = std::max(worst, difference / bound);
        differ += blocks.drho[i] != scalar.drho[i];
        moving += std::abs(scalar.drho[i]) > 1;
      }
      BOOST_TEST_MESSAGE(D << "D, " << kernelName << ", " << boundary << ", diffusion form " << form << ": " << differ << " of " << n
                                  << " rates differ in their last bits, the largest difference " << worst
                                  << " of its bound");
      BOOST_TEST_INFO(D << "D, " << kernelName << ", " << boundary << ", diffusion form " << form);
      BOOST_TEST(beyond == 0u);
      BOOST_TEST(moving > P.fluidCount() / 4);  // the rates are not trivially zero
    }
  }
}

BOOST_AUTO_TEST_CASE(density_rate_blocks_match_the_scalar_loop) {
  checkDensityRateBlocks<2, WendlandC2<2>>("wendland_c2");
  checkDensityRateBlocks<3, WendlandC2<3>>("wendland_c2");
  checkDensityRateBlocks<2, CubicSpline<2>>("cubic_spline");
  checkDensityRateBlocks<3, CubicSpline<3>>("cubic_spline");
}

BOOST_AUTO_TEST_SUITE_END()
