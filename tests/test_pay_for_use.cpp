// A scene pays only for what it enables: terms that a case switches off are
// not constructed, their passes never run (executedTerms() reports the term
// types the pair loop was instantiated with), and the arrays they need are
// not allocated.
#include "sph/terms/term_bits.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <string>

using namespace sph;

namespace {

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

template <int D>
std::vector<std::string> termsOf(const Scene<D>& s) {
  return s.model().termNames();
}

// The passes the last evaluation actually ran: the bits come from the term
// types instantiated in the pair loop and from the body-force loops that ran.
template <int D>
unsigned executed(const Scene<D>& s) {
  return s.model().executedTerms();
}

using namespace term_bits;

CaseConfig block(int dimension) {
  CaseConfig c = test::bareWcsph(dimension);
  c.h = 0.02;
  c.spacing = 0.015;
  c.blockMin.assign(static_cast<std::size_t>(dimension), 0.1);
  c.blockMax.assign(static_cast<std::size_t>(dimension), 0.25);
  return c;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(pay_for_use)

BOOST_AUTO_TEST_CASE(a_minimal_scene_allocates_no_optional_field) {
  CaseConfig c = block(2);
  c.integrator = "symplectic_euler";
  Scene<2> s = test::sceneOf<2>(c);
  BOOST_REQUIRE(!s.step());
  const unsigned ran = executed(s);
  BOOST_TEST((ran & kSymmetricPressure) != 0u);
  BOOST_TEST((ran & (kLaplacianViscosity | kMonaghanViscosity | kGravity | kXsph | kDamping | kStarAttraction)) == 0u);
  const auto& P = s.particles();
  BOOST_TEST(P.size() == 100u);
  for (const auto* f : {&P.vHalf, &P.vXsph, &P.x0, &P.v0, &P.dx, &P.dv}) BOOST_TEST(f->empty());
  BOOST_TEST(P.c.empty());
  const auto terms = termsOf(s);
  BOOST_TEST(!has(terms, "laplacian_viscosity"));
  BOOST_TEST(!has(terms, "monaghan_viscosity"));
  BOOST_TEST(!has(terms, "gravity"));
  BOOST_TEST(!has(terms, "xsph"));
  BOOST_TEST(has(terms, "symmetric_pressure"));
}

BOOST_AUTO_TEST_CASE(enabled_terms_allocate_exactly_their_fields) {
  CaseConfig c = block(3);
  c.viscosity = "monaghan";
  c.xsph = 0.5;
  c.integrator = "rk4";
  c.g = 9.81;
  Scene<3> s = test::sceneOf<3>(c);
  BOOST_REQUIRE(!s.step());
  const unsigned ran = executed(s);
  for (unsigned bit : {kSymmetricPressure, kMonaghanViscosity, kXsph, kGravity}) BOOST_TEST((ran & bit) != 0u);
  BOOST_TEST((ran & kLaplacianViscosity) == 0u);
  const auto& P = s.particles();
  const std::size_t n = P.size();
  BOOST_TEST(n == 1000u);
  for (const auto* f : {&P.vXsph, &P.x0, &P.v0, &P.dx, &P.dv}) BOOST_TEST(f->size() == n);
  BOOST_TEST(P.c.size() == n);
  BOOST_TEST(P.vHalf.empty());  // RK4 keeps no half-step velocity
  const auto terms = termsOf(s);
  BOOST_TEST(has(terms, "monaghan_viscosity"));
  BOOST_TEST(has(terms, "xsph"));
  BOOST_TEST(has(terms, "gravity"));
  // The memory difference is exactly those 5 vector fields and one scalar
  // (the sound speed, a narrow field: float in a mixed build) per particle: RK4's 4 stage fields are permuted when a stage re-sorts,
  // through the vector scratch that x's permutation has already (no shadow
  // buffer per field).
  CaseConfig bare = block(3);
  bare.integrator = "symplectic_euler";
  const Scene<3> b = test::sceneOf<3>(bare);
  BOOST_TEST(s.particles().bytesAllocated() - b.particles().bytesAllocated() ==
             n * (5 * sizeof(Vec<3>) + sizeof(Narrow)));
}

BOOST_AUTO_TEST_CASE(viscosity_with_zero_coefficient_is_not_constructed) {
  CaseConfig c = block(2);
  c.viscosity = "laplacian";
  c.mu = 0;
  BOOST_TEST(!has(termsOf(test::sceneOf<2>(c)), "laplacian_viscosity"));
  BOOST_TEST((executed(test::sceneOf<2>(c)) & kLaplacianViscosity) == 0u);
  c.mu = 0.1;
  BOOST_TEST(has(termsOf(test::sceneOf<2>(c)), "laplacian_viscosity"));
  BOOST_TEST((executed(test::sceneOf<2>(c)) & kLaplacianViscosity) != 0u);
  // The seed model: mu = 0 and g = 0 leave its viscosity and gravity out.
  CaseConfig seed;
  seed.points = {0.5, 0.5};
  seed.mu = 0;
  seed.g = 0;
  const auto seedScene = test::sceneOf<2>(seed);
  const auto seedTerms = termsOf(seedScene);
  BOOST_TEST(!has(seedTerms, "seed_viscosity"));
  BOOST_TEST(!has(seedTerms, "gravity"));
  BOOST_TEST((executed(seedScene) & (kSeedViscosity | kGravity)) == 0u);
  BOOST_TEST((executed(seedScene) & kSeedPressure) != 0u);
}

// No walls: no wall fields (kind, vWall), no wall pass, no density rate
// with summation density. Dummy walls bring their fields and their pass,
// vWall only with a viscosity that reads it (laplacian, morris);
// continuity density its rate; dynamic walls no extrapolation pass.
BOOST_AUTO_TEST_CASE(walls_and_continuity_cost_nothing_when_off) {
  CaseConfig c = block(2);
  Scene<2> none = test::sceneOf<2>(c);
  BOOST_REQUIRE(!none.step());
  const auto& P = none.particles();
  BOOST_TEST(!P.hasWalls());
  for (const auto* f : {&P.vWall}) BOOST_TEST(f->empty());
  BOOST_TEST(P.kind.empty());
  BOOST_TEST(P.drho.empty());
  BOOST_TEST((executed(none) & (kAdamiWalls | kDynamicWalls | kRepulsiveWalls | kContinuityDensity |
                                kDensityDiffusion)) == 0u);

  CaseConfig w = block(2);
  w.walls = true;
  w.boundary = "dummy";
  w.domainMin = {0.1, 0.1}, w.domainMax = {0.4, 0.4};
  w.density = "continuity";
  w.delta = 0.1;
  w.eos = "tait", w.c0 = 10;
  Scene<2> dummy = test::sceneOf<2>(w);
  BOOST_REQUIRE(!dummy.step());
  const auto& Q = dummy.particles();
  BOOST_TEST(Q.hasWalls());
  BOOST_TEST(Q.kind.size() == Q.size());
  BOOST_TEST(Q.vWall.empty());  // viscosity none
  BOOST_TEST(Q.drho.size() == Q.size());
  BOOST_TEST(Q.vHalf.size() == Q.size());  // leap-frog's half-step velocity (rho is advanced like x: no half step)
  const unsigned ran = executed(dummy);
  for (unsigned bit : {kAdamiWalls, kContinuityDensity, kDensityDiffusion}) BOOST_TEST((ran & bit) != 0u);
  BOOST_TEST((ran & (kSummationDensity | kRepulsiveWalls)) == 0u);

  // The wall velocity vWall: for the viscosities that read it.
  for (const char* boundary : {"dummy", "dynamic"})
    for (const char* viscosity : {"monaghan", "laplacian", "morris"}) {
      CaseConfig v = w;
      v.boundary = boundary;
      v.viscosity = viscosity;
      v.alpha = 0.02, v.beta = 0;
      Scene<2> s = test::sceneOf<2>(v);
      BOOST_REQUIRE(!s.step());
      const bool reads = std::string(viscosity) != "monaghan";
      BOOST_TEST(s.particles().vWall.size() == (reads ? s.particles().size() : 0u),
                 boundary << " walls, viscosity " << viscosity);
    }

  w.boundary = "dynamic";
  Scene<2> dynamic = test::sceneOf<2>(w);
  BOOST_REQUIRE(!dynamic.step());
  BOOST_TEST((executed(dynamic) & kAdamiWalls) == 0u);
  BOOST_TEST((executed(dynamic) & kContinuityDensity) != 0u);
  BOOST_TEST((executed(dynamic) & kDynamicWalls) != 0u);
}

// Kernel corrections: off, no field, no pass, no bit, and the symmetric
// pressure; each on brings exactly its field and its passes.
BOOST_AUTO_TEST_CASE(kernel_corrections_cost_nothing_when_off) {
  CaseConfig c = block(2);
  c.density = "continuity";
  const Scene<2> off = [&] {
    Scene<2> s = test::sceneOf<2>(c);
    BOOST_REQUIRE(!s.step());
    return s;
  }();
  const std::size_t n = off.particles().size();
  BOOST_TEST(off.particles().rhoReinit.empty());
  BOOST_TEST(off.particles().cspmL.empty());
  BOOST_TEST(off.model().afterStepPasses().empty());
  BOOST_TEST((executed(off) & (kShepardDensity | kMlsDensity | kCspmCorrection | kCspmPressure)) == 0u);
  BOOST_TEST((executed(off) & kSymmetricPressure) != 0u);
  const std::size_t bytesOff = off.particles().bytesAllocated();

  for (const char* reinit : {"shepard", "mls"}) {
    CaseConfig r = c;
    r.densityReinit = reinit;
    r.densityReinitEvery = 1;
    Scene<2> s = test::sceneOf<2>(r);
    BOOST_REQUIRE(!s.step());
    const unsigned bit = std::string(reinit) == "shepard" ? kShepardDensity : kMlsDensity;
    BOOST_TEST((executed(s) & bit) != 0u);
    BOOST_TEST((executed(s) & (kShepardDensity | kMlsDensity) & ~bit) == 0u);
    BOOST_TEST((executed(s) & (kCspmCorrection | kCspmPressure)) == 0u);
    BOOST_TEST(s.particles().rhoReinit.size() == n);
    BOOST_TEST(s.particles().cspmL.empty());
    BOOST_TEST(s.particles().bytesAllocated() - bytesOff == n * sizeof(Real));
    BOOST_TEST(s.model().correctionCounts().reinitSteps == 1);
  }

  CaseConfig g = c;
  g.gradientCorrection = "cspm";
  Scene<2> s = test::sceneOf<2>(g);
  BOOST_REQUIRE(!s.step());
  BOOST_TEST((executed(s) & (kCspmCorrection | kCspmPressure)) == (kCspmCorrection | kCspmPressure));
  BOOST_TEST((executed(s) & (kSymmetricPressure | kShepardDensity | kMlsDensity)) == 0u);
  BOOST_TEST(s.particles().cspmL.size() == n);
  BOOST_TEST(s.particles().rhoReinit.empty());
  // With the neighbour list's skin (wcsph's default), a rebuild carries L
  // with its particle through a scratch of its own (Particles::permute,
  // grown to n + 16 once): the one more array CSPM costs then.
  const std::size_t carry = s.neighbourSkin() > 0 ? (n + 16) * sizeof(Mat<2>) : 0;
  BOOST_TEST(s.particles().bytesAllocated() - bytesOff == n * sizeof(Mat<2>) + carry);
  BOOST_TEST(s.model().afterStepPasses().empty());
}

BOOST_AUTO_TEST_SUITE_END()
