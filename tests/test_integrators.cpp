// Time integrators on problems with exact answers:
// - free fall (one particle, gravity): leap-frog and RK4 exact to round-off;
//   symplectic and explicit Euler off by -/+ g t dt / 2, as stated in
//   tests/reference/single_particle_bounce.csv;
// - a harmonic oscillator (the toy star's -lambda x on one particle): energy
//   bounded over 1e5 steps for the symplectic schemes, growing for explicit
//   Euler, decaying at its filter's rate for the two-step leap-frog; RK4's
//   error falls at fourth order with dt.
#include "sph/models/wcsph.hpp"
#include "test_support.hpp"

#include <cmath>
#include <random>
#include <string>

using namespace sph;

namespace {

Scene<2> oneParticle(const std::string& integrator, Real dt, Real g, Real lambda, Vec<2> x0, Vec<2> v0) {
  CaseConfig c = test::bareWcsph(2);
  c.integrator = integrator;
  c.dt = dt;
  c.g = g;
  c.points = {x0[0], x0[1]};
  c.velocity = {v0[0], v0[1]};
  Scene<2> s = test::sceneOf<2>(c);
  if (lambda > 0) {
    // Harmonic oscillator: a star attraction without a star.
    WcsphSpec<2> spec{CubicSpline<2>(c.h), LinearEos{c.k, c.rho0}, NoViscosity{}, c.rho0, {}, 0};
    spec.bodies.star = StarAttraction<2>{lambda};
    Particles<2> P = s.particles();
    Scene<2> osc(P, makeWcsph<2>(spec),
                 std::nullopt, StateCheck<2>{Vec<2>::Constant(-1e6), Vec<2>::Constant(1e6)},
                 TimeStepControl{dt}, 0, makeIntegrator<2>(integrator));
    BOOST_REQUIRE(!osc.initialise(false));
    return osc;
  }
  return s;
}

// y(t_n) - (y0 - g t^2/2) after n steps, largest deviation from `offset(t)`.
Real freeFallError(const std::string& integrator, Real dt, int steps, Real offsetSign) {
  const Real g = 9.81, y0 = 0.5;
  Scene<2> s = oneParticle(integrator, dt, g, 0, Vec<2>(0.5, y0), Vec<2>::Zero());
  Real worst = 0;
  for (int n = 1; n <= steps; ++n) {
    BOOST_REQUIRE(!s.step());
    const Real t = n * dt;
    const Real expected = y0 - g * t * t / 2 + offsetSign * g * t * dt / 2;
    worst = std::max(worst, std::abs(s.particles().x[0][1] - expected));
  }
  return worst;
}

Real energy(const Scene<2>& s) { return s.energy().total(); }

}  // namespace

BOOST_AUTO_TEST_SUITE(integrators)

// Round-off bound: ~300 steps of additions to O(1) numbers, ~1e-13.
BOOST_AUTO_TEST_CASE(free_fall_leap_frog_and_rk4_are_exact) {
  BOOST_TEST(freeFallError("leap_frog", 1e-3, 300, 0) < 1e-12);
  BOOST_TEST(freeFallError("rk4", 1e-3, 300, 0) < 1e-12);
  // The two-step leap-frog too: its Euler start, v^{n+1} = vbar^{n-1} +
  // 2 dt g and x^{n+1} = x^n + dt v^n + dt^2 g/2 are exact for constant g,
  // and the filter vanishes on a velocity linear in t.
  BOOST_TEST(freeFallError("two_step_leap_frog", 1e-3, 300, 0) < 1e-12);
}

// The offsets -g t dt/2 (symplectic Euler) and +g t dt/2 (explicit Euler)
// are exact for constant gravity; without them the error would be g t dt/2
// = 1.5e-3 m at t = 0.3 s.
BOOST_AUTO_TEST_CASE(free_fall_euler_offsets_match_reference) {
  BOOST_TEST(freeFallError("symplectic_euler", 1e-3, 300, -1) < 1e-12);
  BOOST_TEST(freeFallError("euler", 1e-3, 300, +1) < 1e-12);
  BOOST_TEST(freeFallError("symplectic_euler", 1e-3, 300, 0) > 1e-3);
}

// omega = 1 (lambda = 1), dt = 0.01: 1e5 steps = 159 periods.
BOOST_AUTO_TEST_CASE(oscillator_energy_bounded_for_symplectic_schemes) {
  for (const std::string name : {"leap_frog", "symplectic_euler"}) {
    Scene<2> s = oneParticle(name, 0.01, 0, 1.0, Vec<2>(1, 0), Vec<2>(0, 0.5));
    const Real e0 = energy(s);
    Real worstEarly = 0, worstLate = 0;
    for (int n = 1; n <= 100000; ++n) {
      BOOST_REQUIRE(!s.step());
      const Real err = std::abs(energy(s) / e0 - 1);
      (n <= 10000 ? worstEarly : worstLate) = std::max(n <= 10000 ? worstEarly : worstLate, err);
    }
    BOOST_TEST_CONTEXT(name) {
      // Bounded: the error of a symplectic scheme oscillates, O(dt) for
      // symplectic Euler (~dt/2 = 5e-3), O(dt^2) for leap-frog (~1e-5)...
      BOOST_TEST(worstLate < 1e-2);
      // ...and does not grow: the last 90% of the run stays within 1.5x the
      // first 10%.
      BOOST_TEST(worstLate < 1.5 * worstEarly + 1e-12);
    }
  }
}

// Explicit Euler multiplies the oscillator energy by (1 + omega^2 dt^2)
// every step: e^{10} after 1e5 steps at dt = 0.01.
BOOST_AUTO_TEST_CASE(oscillator_energy_grows_with_explicit_euler) {
  Scene<2> s = oneParticle("euler", 0.01, 0, 1.0, Vec<2>(1, 0), Vec<2>(0, 0.5));
  const Real e0 = energy(s);
  for (int n = 1; n <= 100000; ++n) BOOST_REQUIRE(!s.step());
  const Real growth = energy(s) / e0;
  BOOST_TEST(growth == std::exp(1e5 * std::log1p(1e-4)), boost::test_tools::tolerance(1e-6));
}

// The two-step leap-frog's Robert-Asselin filter (nu = 0.05) damps the
// physical root. Here only v goes through the filtered two-step (x takes
// its Taylor step), and the eigenvalues of that 3 x 3 step map (x, v, vbar)
// give |lambda| = 1 - nu (omega dt)^2 / (4 (1 - nu)) + O((omega dt)^4)
// (for the acoustic pair, where rho is filtered too, twice that:
// integrators/two_step_leap_frog.hpp): energy x exp(-nu z^2 n / (2 (1 - nu))).
// omega = 1, dt = 0.01, 2e4 steps: x 0.94876. Tolerance 1e-3: the next
// order (omega dt)^2 relative, the start's parasitic mode (damped 10% per
// step) and the energy's O((omega dt)^2) oscillation, 1e-4 each; without
// the filter the energy would stay within 1e-4 of 1, with nu = 0.1 x 0.90.
BOOST_AUTO_TEST_CASE(two_step_leap_frog_damps_at_the_filter_rate) {
  Scene<2> s = oneParticle("two_step_leap_frog", 0.01, 0, 1.0, Vec<2>(1, 0), Vec<2>(0, 1));
  const Real e0 = energy(s), nu = TwoStepLeapFrog<2>::kFilter;
  const int steps = 20000;
  for (int n = 1; n <= steps; ++n) BOOST_REQUIRE(!s.step());
  const Real expected = std::exp(-nu * 1e-4 * steps / (2 * (1 - nu)));
  BOOST_TEST(std::abs(energy(s) / e0 - expected) < 1e-3, "energy ratio " << energy(s) / e0 << ", expected " << expected);
}

// Error of the phase-space state at t = 1.5 against x = cos t, v = -sin t.
// (Not a whole period: there the position error of both schemes converges
// one order faster than the scheme's order, which would hide it.)
std::vector<Real> oscillatorErrors(const std::string& integrator, std::initializer_list<int> stepCounts) {
  std::vector<Real> errors;
  const Real T = 1.5;
  for (int steps : stepCounts) {
    Scene<2> s = oneParticle(integrator, T / steps, 0, 1.0, Vec<2>(1, 0), Vec<2>(0, 0));
    for (int n = 0; n < steps; ++n) BOOST_REQUIRE(!s.step());
    const Vec<2> dx = s.particles().x[0] - Vec<2>(std::cos(T), 0);
    const Vec<2> dv = s.particles().v[0] - Vec<2>(-std::sin(T), 0);
    errors.push_back(std::sqrt(dx.squaredNorm() + dv.squaredNorm()));
  }
  return errors;
}

// RK4: halving dt divides the error by ~16. Tolerance: the observed order
// within 0.3 of 4.
BOOST_AUTO_TEST_CASE(rk4_converges_at_fourth_order) {
  const std::vector<Real> errors = oscillatorErrors("rk4", {10, 20, 40});
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const Real order = std::log2(errors[k - 1] / errors[k]);
    BOOST_TEST(std::abs(order - 4) < 0.3, "observed order " << order);
  }
}

// Leap-frog is second order on the same problem.
BOOST_AUTO_TEST_CASE(leap_frog_converges_at_second_order) {
  const std::vector<Real> errors = oscillatorErrors("leap_frog", {20, 40, 80});
  for (std::size_t k = 1; k < errors.size(); ++k)
    BOOST_TEST(std::abs(std::log2(errors[k - 1] / errors[k]) - 2) < 0.2);
}

// RK4 with many interacting particles: each of its four evaluations re-sorts
// the particles, carrying x0, v0, dx, dv along. The order estimated from
// three step sizes (Richardson: log2 |x_dt - x_dt/2| / |x_dt/2 - x_dt/4|)
// is 4 only if that bookkeeping is right. Tolerance 0.3.
BOOST_AUTO_TEST_CASE(rk4_is_fourth_order_with_resorting_particles) {
  auto run = [](int steps) {
    CaseConfig c = test::bareWcsph(2);
    c.integrator = "rk4", c.eos = "tait", c.c0 = 10, c.rho0 = 1000;
    c.h = 0.013, c.spacing = 0.01, c.blockMin = {0, 0}, c.blockMax = {0.3, 0.3};
    c.dt = 0.016 / steps;
    Scene<2> s = test::sceneOf<2>(c);
    for (std::size_t i = 0; i < s.particles().size(); ++i) {
      const Vec<2> x = s.particles().x[i];
      s.particles().v[i] = 0.3 * Vec<2>(std::sin(10 * x[1]), std::cos(10 * x[0]));  // shears the lattice
    }
    for (int n = 0; n < steps; ++n) BOOST_REQUIRE(!s.step());
    std::vector<Vec<2>> byId(s.particles().size());
    for (std::size_t i = 0; i < byId.size(); ++i)
      byId[static_cast<std::size_t>(s.particles().id[i])] = s.particles().x[i];
    return byId;
  };
  const auto a = run(20), b = run(40), c = run(80);
  Real e1 = 0, e2 = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    e1 = std::max(e1, (a[i] - b[i]).norm());
    e2 = std::max(e2, (b[i] - c[i]).norm());
  }
  BOOST_TEST(e2 > 0.0);
  const Real order = std::log2(e1 / e2);
  BOOST_TEST(std::abs(order - 4) < 0.3, "observed order " << order << " (e1 " << e1 << ", e2 " << e2 << ")");
}

// Every integrator writes only what it declares (integrator_support.hpp):
// advance() the state it advances (x, v, and rho with continuity density)
// and its own fields (needs()), finish() only finishes(); the scene
// refreshes the ghosts and halos of those alone. Every allocated field gets
// random values; the evaluations and the density-rate pass are stand-ins
// that write new random rates (a, drho), as a model's passes would. A
// field that changed outside the declaration fails, naming it.
BOOST_AUTO_TEST_CASE(integrators_write_only_what_they_declare) {
  for (const bool density : {true, false})
    for (const Integrator<2>& chosen : {Integrator<2>{LeapFrog<2>{}}, Integrator<2>{SymplecticEuler<2>{}},
                                        Integrator<2>{RungeKutta4<2>{}}, Integrator<2>{ExplicitEuler<2>{}},
                                        Integrator<2>{TwoStepLeapFrog<2>{}}})
      std::visit(
        [&](auto integrator) {
          using I = decltype(integrator);
          const std::string what = std::string(I::name) + (density ? ", continuity" : ", summation");
          const std::size_t n = 60, nFluid = 45;
          std::mt19937 rng(11);
          std::uniform_real_distribution<Real> u(0.5, 1.5);
          Particles<2> P;
          P.x.resize(n), P.v.resize(n), P.m.resize(n), P.id.resize(n);
          for (std::size_t i = 0; i < n; ++i) P.id[i] = static_cast<std::int64_t>(i);
          P.resize(n, nFluid);
          P.allocate(I::needs(density) | fieldBit(kFieldVXsph) | (density ? fieldBit(kFieldDrho) : FieldSet(0)));
          auto randomise = [&](FieldSet fields) {
            P.forEachField([&](const FieldInfo& info, auto& field) {
              if (((fields >> info.id) & 1u) == 0 || info.id == kFieldId || info.id == kFieldKind) return;
              for (auto& value : field) {
                using T = std::decay_t<decltype(value)>;
                if constexpr (std::is_floating_point_v<T>) value = u(rng);
                else if constexpr (std::is_class_v<T>) value = T::NullaryExpr([&] { return u(rng); });
              }
            });
          };
          randomise(P.allocated());
          if constexpr (std::is_same_v<I, TwoStepLeapFrog<2>>) integrator.step = 3;  // past its Euler start
          const FieldSet rates = fieldBits(kFieldA, kFieldDrho);
          // The fields that changed from `before` to now, rates aside.
          auto changed = [&](const Particles<2>& before) {
            FieldSet out = 0;
            FieldArrays<2>::zip(
                [&](const FieldInfo& info, const auto& was, const auto& now) {
                  if (((rates >> info.id) & 1u) == 0 && was != now) out |= fieldBit(info.id);
                },
                static_cast<const FieldArrays<2>&>(before), static_cast<const FieldArrays<2>&>(P));
            return out;
          };
          auto names = [](FieldSet f) {
            std::string s;
            for (const FieldInfo& info : kFieldTable)
              if ((f >> info.id) & 1u) s += std::string(" ") + info.name;
            return s;
          };
          const Particles<2> start = P;
          integrator.advance(P, 1e-3, [&] { randomise(rates & P.allocated()); }, NoConstraint{},
                             [&] { randomise(fieldBit(kFieldDrho) & P.allocated()); });
          const FieldSet advanced = changed(start), allowed = advancedState(density) | I::needs(density);
          BOOST_TEST((advanced & ~allowed) == 0u, what << ": advance() wrote undeclared" << names(advanced & ~allowed));
          BOOST_TEST((advanced & fieldBits(kFieldX, kFieldV)) == fieldBits(kFieldX, kFieldV), what);
          const Particles<2> evaluated = P;
          for (std::size_t i = 0; i < n; ++i) integrator.finish(P, i, 1e-3);
          const FieldSet finished = changed(evaluated);
          BOOST_TEST((finished & ~I::finishes()) == 0u, what << ": finish() wrote undeclared" << names(finished & ~I::finishes()));
        },
        chosen);
}

BOOST_AUTO_TEST_SUITE_END()
