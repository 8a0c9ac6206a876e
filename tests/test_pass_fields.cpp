// The fields each pass declares it reads and writes (fields.hpp:
// FieldAccess; each pass's fields(), next to its run()). Model::sync()
// refreshes the periodic ghosts of a pass's declared writes only, so a
// write left out of a declaration would leave the ghosts stale, and a read
// left out would leave a halo exchange without a field the pass needs.
//
// For every pass of the models the shipped cases build (cases/*.case, and
// variants of them that switch on the options a declaration depends on:
// CSPM, Shepard and MLS re-initialisation, dynamic and repulsive walls,
// summation density, XSPH, the curvature methods, artificial pressure), in
// every mode the step gives it (the density rate in the force pass or apart;
// a re-initialisation due), for the density-rate pass the leap-frog and
// symplectic Euler integrators run apart and for the scene's own passes at
// the start of a step (shifting, wall motion), on the state after two steps:
//   (a) every field outside its writes is bit for bit what it was, at every
//       particle, ghosts included;
//   (b) poisoned fields outside its reads (NaN; the integer fields a value
//       no particle has) leave its writes bit for bit as they are without
//       the poison, wherever the pass changed them (an entry the pass leaves
//       as it was, e.g. a wall's a, is left as it was with the poison too;
//       so that "changed" means something, the fields it writes and does
//       not read start at a value no pass computes).
// Exact comparisons: the pass runs twice on the same input, in the same
// order, with the same threads, so no tolerance is needed.
#include "sph/case_file.hpp"
#include "sph/case_keys.hpp"
#include "test_support.hpp"

#include <boost/test/unit_test.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

using namespace sph;

namespace {

// key = value pairs as a case file gives them, onto a case.
void setKey(CaseConfig& c, const std::string& key, const std::vector<std::string>& values) {
  const KeySpec* k = findKey(key);
  BOOST_REQUIRE_MESSAGE(k, "unknown key " << key);
  std::visit(
      [&](auto member) {
        auto& field = keyRef(c, member);
        using F = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<F, std::string>) field = values.at(0);
        else if constexpr (std::is_same_v<F, bool>) field = values.at(0) == "true";
        else if constexpr (std::is_same_v<F, std::vector<Real>>) {
          field.clear();
          for (const auto& v : values) field.push_back(std::stod(v));
        } else if constexpr (std::is_same_v<F, std::vector<long>>) {
          field.clear();
          for (const auto& v : values) field.push_back(std::stol(v));
        } else if constexpr (std::is_same_v<F, Real>) field = std::stod(values.at(0));
        else field = static_cast<F>(std::stol(values.at(0)));
      },
      k->field);
  c.given.insert(key);
}

// A shipped case (cases/NAME.case), with overrides "key=value".
CaseConfig shippedCase(const std::string& name, const std::vector<std::pair<std::string, std::string>>& overrides) {
  const std::string path = test::caseFile(name);
  std::ifstream in(path);
  BOOST_REQUIRE_MESSAGE(in, "cannot read " << path);
  CaseConfig c;
  c.caseFile = path;
  for (const CaseEntry& e : readCaseFile(in)) {
    std::vector<std::string> values = e.values;
    if (e.key == "particle_file" && std::filesystem::path(values.at(0)).is_relative())
      values[0] = std::string(SPH_SOURCE_DIR) + "/" + values[0];  // (relative to the source tree)
    setKey(c, e.key, values);
  }
  for (const auto& [key, value] : overrides) setKey(c, key, {value});
  return c;
}

template <class T>
bool sameBits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

template <class T>
T poison() {
  if constexpr (std::is_floating_point_v<T>) return std::numeric_limits<T>::quiet_NaN();
  else if constexpr (std::is_integral_v<T>) return static_cast<T>(0x5A5A5A5A5A5A5A5Aull);
  else return T::Constant(std::numeric_limits<Real>::quiet_NaN());
}

std::string fieldNames(FieldSet s) {
  std::string names;
  for (const FieldInfo& f : kFieldTable)
    if ((s >> f.id) & 1u) names += std::string(names.empty() ? "" : " ") + f.name;
  return names.empty() ? "-" : names;
}

// Checks (a) and (b) for one run of a pass: `run(P)` runs it on P, `access`
// is what it declares. Returns the number of failures.
template <int D, class Run>
int checkPass(const std::string& what, const Particles<D>& state, const FieldAccess& access, Run&& run) {
  const FieldSet allocated = state.allocated();
  auto fill = [&](Particles<D>& P, FieldSet fields, auto value) {
    P.forEachField([&](const FieldInfo& info, auto& field) {
      if (((allocated & fields) >> info.id) & 1u)
        for (auto& x : field) x = value(x);
    });
  };
  // The fields it writes and does not read start at a value it never
  // computes: a pass run again on the state it made (the summation density
  // at the positions of its last evaluation) would otherwise give back its
  // input, and that entry would pass for one the pass left alone.
  Particles<D> input = state;
  fill(input, access.writes & ~access.reads, [](auto x) {
    using T = decltype(x);
    if constexpr (std::is_integral_v<T>) return x;
    else if constexpr (std::is_floating_point_v<T>) return T(-1.2345e-7);
    else return T(T::Constant(Real(-1.2345e-7)));
  });
  Particles<D> reference = input;
  run(reference);
  Particles<D> poisoned = input;
  fill(poisoned, ~access.reads, [](auto x) { return poison<decltype(x)>(); });
  Particles<D> poisonedInput = poisoned;
  run(poisoned);
  int failures = 0;
  FieldArrays<D>::zip(
      [&](const FieldInfo& info, const auto& in, const auto& ref, const auto& poisIn, const auto& pois) {
        if (((allocated >> info.id) & 1u) == 0) return;
        const bool written = (access.writes >> info.id) & 1u;
        for (std::size_t k = 0; k < in.size(); ++k) {
          if (!written && !sameBits(in[k], ref[k])) {
            BOOST_ERROR(what << ": writes " << info.name << " (particle " << k << " of " << in.size()
                             << "), which it does not declare (writes: " << fieldNames(access.writes) << ")");
            ++failures;
            return;
          }
          const bool passedThrough = sameBits(in[k], ref[k]) && sameBits(poisIn[k], pois[k]);
          if (written && !sameBits(ref[k], pois[k]) && !passedThrough) {
            BOOST_ERROR(what << ": its " << info.name << " (particle " << k << " of " << in.size()
                             << ") changes when fields outside its reads are poisoned (reads: "
                             << fieldNames(access.reads) << ")");
            ++failures;
            return;
          }
        }
      },
      input, reference, poisonedInput, poisoned);
  return failures;
}

// Every pass of a scene's model, in the modes a step gives it.
template <int D>
void checkScene(const std::string& name, const CaseConfig& c) {
  Scene<D> scene = test::sceneOf<D>(c);
  for (int s = 0; s < 2; ++s) BOOST_REQUIRE(!scene.step());
  const Particles<D>& P = scene.particles();
  const NeighbourList<D>& list = scene.neighbours();
  const Model<D>& model = scene.model();
  StepContext ctx{std::max(c.densityReinitEvery, 1L), scene.time(), scene.lastTimeStep().dt};
  int failures = 0, passes = 0;
  auto check = [&](const PassList<D>& list_, const char* where) {
    for (const auto& pass : list_)
      for (bool apart : {false, true}) {
        ctx.densityRateApart = apart;
        const std::string what = name + " " + where + " pass " + pass->name() + (apart ? " (density rate apart)" : "");
        failures += checkPass<D>(what, P, pass->fields(ctx), [&](Particles<D>& Q) { pass->run(Q, list, ctx); });
        ++passes;
      }
  };
  check(model.passes(), "model");
  check(model.afterStepPasses(), "after-step");
  check(model.densityRatePasses(), "density-rate");
  // The scene's own passes at the start of a step (shifting, wall motion).
  const StepContext next{scene.stepIndex() + 1, scene.time() + ctx.dt, ctx.dt, scene.time()};
  auto checkOwn = [&](const auto& pass, const char* what) {
    if (!pass) return;
    failures += checkPass<D>(name + " " + what + " pass", P, pass->fields(next),
                             [&](Particles<D>& Q) { pass->run(Q, list, next); });
    ++passes;
  };
  checkOwn(scene.shiftingPass(), "shifting");
  checkOwn(scene.wallMotionPass(), "wall-motion");
  BOOST_TEST_MESSAGE(name << ": " << P.size() << " particles, " << P.totalSize() - P.size() << " ghosts, " << passes
                          << " pass runs checked, " << failures << " failures");
}

void checkCase(const std::string& name, const std::vector<std::pair<std::string, std::string>>& overrides = {}) {
  CaseConfig c = shippedCase(name, overrides);
  std::string label = name;
  for (const auto& [k, v] : overrides) label += " " + k + "=" + v;
  if (c.dimension == 3) checkScene<3>(label, c);
  else checkScene<2>(label, c);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(pass_fields)

BOOST_AUTO_TEST_CASE(shipped_cases) {
  for (const char* name : {"dam_break", "dam_break_seed", "block_drop", "droplet", "couette_2d", "poiseuille_2d",
                           "taylor_green_2d", "droplet_surface_tension", "hydrostatic_tank", "star_collision_2d",
                           "tensile_block", "toy_star_2d", "wave_paddle", "several_bodies", "dam_break_obstacle",
                           "poiseuille_3d", "spheric2_dam_break_box"})
    checkCase(name);
}

BOOST_AUTO_TEST_CASE(variants) {
  checkCase("dam_break", {{"gradient_correction", "cspm"}, {"density_reinit", "mls"}});
  checkCase("dam_break", {{"density_reinit", "shepard"}, {"xsph", "0.5"}, {"diffusion", "molteni"}});
  checkCase("dam_break", {{"boundary", "dynamic"}});
  checkCase("dam_break", {{"boundary", "repulsive"}, {"viscosity", "laplacian"}, {"mu", "0.001"}});
  checkCase("dam_break", {{"density", "summation"}, {"delta", "0"}, {"viscosity", "morris"}, {"wall_slip", "free_slip"}});
  checkCase("droplet_surface_tension", {{"surface_tension", "muller"}});
  checkCase("droplet_surface_tension", {{"surface_tension", "morris"}, {"gradient_correction", "cspm"}});
  checkCase("droplet_surface_tension", {{"periodic", "xy"}, {"walls", "false"}, {"lid", "false"}});  // the colour pass's ghosts
  checkCase("tensile_block", {{"artificial_pressure", "0.2"}});
  checkCase("taylor_green_2d", {{"viscosity", "monaghan"}, {"xsph", "0.5"}, {"integrator", "rk4"}});
}

BOOST_AUTO_TEST_SUITE_END()
