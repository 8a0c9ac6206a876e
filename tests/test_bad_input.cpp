// Bad input never runs and never writes: each case of the catalogue gives one
// line naming the key or file, a non-zero exit status, and no output folder.
#include "sph/types.hpp"
#include "cli_support.hpp"

#include <fstream>

using namespace sph;

namespace {

// Run `sph run` with the given arguments and an output folder inside a fresh
// scratch folder; require failure, a one-line message containing `expected`,
// and nothing written.
void expectRejected(const std::vector<std::string>& args, const std::string& expected,
                    const std::string& caseName = "dam_break_seed") {
  const auto dir = test::scratchDir("bad");
  const auto out = dir / "out";
  std::vector<std::string> all{"run"};
  if (!caseName.empty()) all.push_back(test::caseFile(caseName));
  all.insert(all.end(), {"--output", out.string()});
  all.insert(all.end(), args.begin(), args.end());
  const auto r = test::runSph(all);
  BOOST_TEST_CONTEXT("arguments ending " << args.back()) {
    BOOST_TEST(r.exitCode == 2, r.output);
    BOOST_TEST(r.output.find(expected) != std::string::npos, "message was: " << r.output);
    BOOST_TEST(r.output.rfind("sph: error: ", 0) == 0, r.output);
    BOOST_TEST(std::count(r.output.begin(), r.output.end(), '\n') == 1, r.output);
    BOOST_TEST(!std::filesystem::exists(out));
  }
}

std::string writeFile(const std::string& name, const std::string& text) {
  const auto dir = test::scratchDir("input_" + name);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(bad_input)

BOOST_AUTO_TEST_CASE(unknown_key_in_case_file) {
  const std::string file = writeFile("typo.case", "points = [0.5, 0.5]\nviscosty = 3\n");
  const auto out = test::scratchDir("bad_typo") / "out";
  const auto r = test::runSph({"run", file, "--output", out.string()});
  BOOST_TEST(r.exitCode == 2);
  BOOST_TEST(r.output.find("unknown key 'viscosty'") != std::string::npos, r.output);
  BOOST_TEST(!std::filesystem::exists(out));
}

BOOST_AUTO_TEST_CASE(unknown_flag) { expectRejected({"--viscosty", "3"}, "unknown key 'viscosty' (on the command line)"); }
BOOST_AUTO_TEST_CASE(wrong_type) { expectRejected({"--h", "abc"}, "--h = abc"); }
BOOST_AUTO_TEST_CASE(h_not_positive) { expectRejected({"--h", "0"}, "h = 0 is out of range: it must be 1e-09 to 1e+09"); }
BOOST_AUTO_TEST_CASE(dt_not_positive) { expectRejected({"--dt", "-1e-4"}, "dt = -0.0001 is out of range: it must be > 0"); }
BOOST_AUTO_TEST_CASE(rho0_not_positive) { expectRejected({"--rho0", "0"}, "rho0 = 0 is out of range"); }
// The precision is the build's (cmake -DSPH_PRECISION): a case asking for
// the other is refused with the option that builds it, on a model with
// walls (dam_break) as on the seed's.
BOOST_AUTO_TEST_CASE(precision_of_another_build) {
  const std::string other = std::string(kBuildPrecision) == "double" ? "mixed" : "double";
  for (const char* caseName : {"dam_break_seed", "dam_break"})
    expectRejected({"--precision", other},
                   "precision = " + other + " needs sph built with cmake -DSPH_PRECISION=" + other +
                       " (this build stores " + kBuildPrecision + ")",
                   caseName);
  expectRejected({"--precision", "single"}, "precision");
}
BOOST_AUTO_TEST_CASE(restitution_outside_unit_interval) {
  expectRejected({"--restitution", "1.5"}, "restitution = 1.5 is out of range: it must be 0 to 1");
  expectRejected({"--restitution", "-0.1"}, "restitution = -0.1 is out of range");
}
BOOST_AUTO_TEST_CASE(output_every_below_one) { expectRejected({"--output_every", "0"}, "output_every = 0"); }
BOOST_AUTO_TEST_CASE(unknown_model) { expectRejected({"--model", "sph2000"}, "model = \"sph2000\" is not known"); }
BOOST_AUTO_TEST_CASE(dimension_out_of_range) { expectRejected({"--dimension", "4"}, "dimension = 4"); }
BOOST_AUTO_TEST_CASE(threads_out_of_range) { expectRejected({"--threads", "100000"}, "threads = 100000 is out of range"); }
BOOST_AUTO_TEST_CASE(too_many_steps) { expectRejected({"--dt", "1e-300"}, "end_time / dt = "); }
BOOST_AUTO_TEST_CASE(too_many_particles) {
  expectRejected({"--spacing", "1e-7"}, "spacing gives about");
  expectRejected({"--star_particles", "100000000000"}, "star_particles holds 1e+11: every value must be 1 to 1e+09", "toy_star_2d");
  expectRejected({"--star_particles", "600000000", "600000000"}, "star_particles gives about", "star_collision_2d");
}
BOOST_AUTO_TEST_CASE(non_finite_coefficients) {
  expectRejected({"--damping", "inf"}, "damping = inf is out of range", "toy_star_2d");
  expectRejected({"--alpha", "inf"}, "alpha = inf", "star_collision_2d");
}
BOOST_AUTO_TEST_CASE(vector_of_wrong_length) { expectRejected({"--domain_min", "0"}, "domain_min has 1 values"); }

BOOST_AUTO_TEST_CASE(particle_outside_domain) {
  expectRejected({"--points", "1.5", "0.5"}, "outside the domain", "one_particle");
  expectRejected({"--block_max", "1.2", "0.5"}, "outside the domain");
}

// Toy stars (issue 21): a star's mass and radius must be > 0; a zero,
// negative or missing one is named with its range, not reported as "zero
// particles" (star_mass = 0) or as a range "0 to 1e+12" that includes 0.
BOOST_AUTO_TEST_CASE(star_mass_and_radius_named_with_their_ranges) {
  expectRejected({"--star_mass", "0"}, "star_mass = 0 is out of range: it must be > 0 and <= 1e+12", "toy_star_2d");
  expectRejected({"--star_mass", "-2"}, "star_mass = -2 is out of range: it must be > 0 and <= 1e+12", "toy_star_2d");
  expectRejected({"--star_radius", "0"}, "star_radius = 0 is out of range: it must be > 0 and <= 1e+09", "toy_star_2d");
  std::ifstream in(test::caseFile("toy_star_2d"));
  std::string noMass, noRadius, line;
  while (std::getline(in, line)) {
    if (line.rfind("star_mass", 0) != 0) noMass += line + "\n";
    if (line.rfind("star_radius", 0) != 0) noRadius += line + "\n";
  }
  expectRejected({writeFile("no_mass.case", noMass)}, "star_mass is missing: the case describes a toy star", "");
  expectRejected({writeFile("no_radius.case", noRadius)}, "star_radius is missing: a toy star's radius R must be > 0",
                 "");
}

// A star whose ball leaves the domain names star_center and star_radius.
BOOST_AUTO_TEST_CASE(star_outside_the_domain_names_its_centre_and_radius) {
  expectRejected({"--star_center", "2.5", "0"},
                 "star 1 (star_center = [2.5, 0], star_radius = 0.75) reaches outside the domain along axis 1",
                 "toy_star_2d");
  expectRejected({"--star_radius", "3.5"}, "star_radius = 3.5) reaches outside the domain", "toy_star_2d");
}

BOOST_AUTO_TEST_CASE(zero_particles) {
  const std::string file = writeFile("empty.case", "# no particles at all\nh = 0.01\n");
  const auto out = test::scratchDir("bad_empty") / "out";
  const auto r = test::runSph({"run", file, "--output", out.string()});
  BOOST_TEST(r.exitCode == 2);
  BOOST_TEST(r.output.find("zero particles") != std::string::npos, r.output);
  BOOST_TEST(!std::filesystem::exists(out));
}

BOOST_AUTO_TEST_CASE(missing_particle_file) {
  expectRejected({"--particle_file", "/nonexistent/particles.csv"},
                 "particle_file /nonexistent/particles.csv does not exist");
}

BOOST_AUTO_TEST_CASE(malformed_particle_files) {
  expectRejected({"--particle_file", writeFile("nohead.csv", "1,2\n3,4\n")}, "needs columns x, y");
  expectRejected({"--particle_file", writeFile("text.csv", "x,y\n0.5,abc\n")}, "line 2: column 2 is not a finite number");
  expectRejected({"--particle_file", writeFile("fake.vtp", "not xml at all")}, "fake.vtp");
  expectRejected({"--particle_file", writeFile("p.txt", "x,y\n0.5,0.5\n")}, "must end in .csv, .vtp or .pvtp");
}

BOOST_AUTO_TEST_CASE(output_folder_cannot_be_created) {
  const std::string file = writeFile("a_file", "x");
  const auto r = test::runSph({"run", test::caseFile("one_particle"), "--output", file + "/sub"});
  BOOST_TEST(r.exitCode == 2);
  BOOST_TEST(r.output.find("output folder " + file + "/sub cannot be created") != std::string::npos, r.output);
  // A path that fails deep down leaves none of the folders it did create.
  const auto base = test::scratchDir("deep");
  const std::string tooLong(300, 'a');
  const auto r2 = test::runSph({"run", test::caseFile("one_particle"), "--output", (base / "new" / tooLong).string()});
  BOOST_TEST(r2.exitCode == 2);
  BOOST_TEST(!std::filesystem::exists(base / "new"));
}

BOOST_AUTO_TEST_CASE(missing_case_file) {
  const auto r = test::runSph({"run", "/nonexistent/dam.case"});
  BOOST_TEST(r.exitCode == 2);
  BOOST_TEST(r.output.find("case file /nonexistent/dam.case cannot be read") != std::string::npos, r.output);
}

BOOST_AUTO_TEST_CASE(help_and_version_succeed) {
  const auto help = test::runSph({"--help"});
  BOOST_TEST(help.exitCode == 0);
  for (const char* key : {"--h ", "--k ", "--rho0", "--mu", "--restitution", "--dt", "--end_time",
                          "--output_every", "--block_min", "--disc_radius", "--points", "--particle_file"})
    BOOST_TEST(help.output.find(key) != std::string::npos, "help lacks " << key);
  const auto version = test::runSph({"--version"});
  BOOST_TEST(version.exitCode == 0);
  BOOST_TEST(version.output == std::string("sph ") + SPH_VERSION + " (precision " + sph::kBuildPrecision + ")\n");
}

BOOST_AUTO_TEST_SUITE_END()
