// sph study: the study file (each refusal names the line and key), the
// matrix of runs and their `sph run` arguments, and the runner skipping
// finished runs and re-running changed ones. The analysis itself
// (validation/study.py) is checked by ctest study.ci_small.
#include "sph/case_config.hpp"
#include "sph/study.hpp"
#include "cli_support.hpp"

#include <boost/test/unit_test.hpp>

#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

const fs::path kCases = fs::path(SPH_SOURCE_DIR) / "cases";

sph::Study parse(const std::string& text) { return sph::parseStudy(text, "t.study", kCases); }

// The message of the CaseError that parsing `text` throws ("" if none).
std::string refusal(const std::string& text) {
  try {
    parse(text);
  } catch (const sph::CaseError& e) {
    return e.what();
  }
  return "";
}

const std::string kCase = "case_dam = [\"dam_break_mm.case\", \"dam_break\"]\n";

bool contains(const std::string& s, const std::string& part) {
  const bool ok = s.find(part) != std::string::npos;
  if (!ok) BOOST_TEST_MESSAGE("'" << s << "' does not contain '" << part << "'");
  return ok;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(study)

BOOST_AUTO_TEST_CASE(a_study_file_is_cases_methods_resolutions_and_tolerances) {
  const sph::Study s = parse(kCase +
                             "overrides = [\"end_time = 0.3\"]\n"
                             "method_a = [\"kernel = cubic_spline\", \"hydrostatic_start = false\"]\n"
                             "method_b = []\n"
                             "resolution_coarse = [\"spacing = 0.02\", \"h = 0.03\", \"end_time = 0.1\"]\n"
                             "resolution_fine = [\"spacing = 0.01\", \"domain_max = [2, 1]\"]\n"
                             "tolerance = [0.05, 0.1]\n");
  BOOST_TEST(s.cases.size() == 1u);
  BOOST_TEST(s.cases[0].name == "dam");
  BOOST_TEST(s.cases[0].caseFile == kCases / "dam_break_mm.case");
  BOOST_TEST(s.methods.size() == 2u);
  BOOST_TEST(s.resolutions.size() == 2u);
  BOOST_TEST(s.tolerances.size() == 2u);
  const auto runs = sph::studyRuns(s, "out");
  BOOST_TEST_REQUIRE(runs.size() == 4u);  // 1 case x 2 methods x 2 resolutions, resolutions innermost
  BOOST_TEST(runs[0].name == "dam__a__coarse");
  BOOST_TEST(runs[1].name == "dam__a__fine");
  BOOST_TEST(runs[3].folder == fs::path("out") / "runs" / "dam__b__fine");
  // The resolution's end_time replaces the common one, in its place.
  const std::vector<std::string> args = sph::runArguments(s, runs[0]);
  const std::vector<std::string> expected = {"run",    (kCases / "dam_break_mm.case").string(),
                                             "--output", (fs::path("out") / "runs" / "dam__a__coarse").string(),
                                             "--no-progress", "--end_time", "0.1", "--kernel", "cubic_spline",
                                             "--no-hydrostatic_start", "--spacing", "0.02", "--h", "0.03", "--threads", "1"};
  BOOST_TEST(args == expected, boost::test_tools::per_element());
  // A list value is one argument per element.
  const std::vector<std::string> fine = sph::runArguments(s, runs[1]);
  BOOST_TEST(contains(std::string(" ") + [&] {
                        std::string j;
                        for (const auto& a : fine) j += a + " ";
                        return j;
                      }(),
                      " --domain_max 2 1 "));
}

BOOST_AUTO_TEST_CASE(defaults_one_method_one_resolution_tolerance_5_percent) {
  const sph::Study s = parse(kCase);
  BOOST_TEST(s.methods.size() == 1u);
  BOOST_TEST(s.resolutions.size() == 1u);
  BOOST_TEST(s.tolerances.at(0) == 0.05);
}

BOOST_AUTO_TEST_CASE(refusals_name_the_line_and_key) {
  BOOST_TEST(contains(refusal(""), "has no case_NAME"));
  BOOST_TEST(contains(refusal(kCase + "methd_a = []\n"), "line 2: unknown key 'methd_a'"));
  BOOST_TEST(contains(refusal(kCase + "method_a = [\"kernal = gaussian\"]\n"), "unknown key 'kernal'"));
  BOOST_TEST(contains(refusal(kCase + "method_a = [\"kernal = gaussian\"]\n"), "did you mean 'kernel'"));
  BOOST_TEST(contains(refusal(kCase + "method_a = [\"output = x\"]\n"), "key 'output' cannot be set by a study"));
  BOOST_TEST(contains(refusal(kCase + "method_a = [\"kernel\"]\n"), "'kernel' is not 'key = value'"));
  BOOST_TEST(contains(refusal(kCase + "method_a = [\"kernel = \"]\n"), "key 'kernel' has no value"));
  BOOST_TEST(contains(refusal("case_x = [\"nowhere.case\", \"dam_break\"]\n"), "nowhere.case of case_x cannot be read"));
  BOOST_TEST(contains(refusal("case_x = [\"dam_break_mm.case\", \"speed\"]\n"),
                      "observable 'speed' of case_x is unknown: it must be one of dam_break, hydrostatic"));
  BOOST_TEST(contains(refusal("case_x = \"dam_break_mm.case\"\n"), "must be [\"CASE_FILE\", \"OBSERVABLE\"] or"));
  BOOST_TEST(contains(refusal(kCase + "tolerance = -1\n"), "tolerance '-1' must be a number > 0"));
  BOOST_TEST(contains(refusal(kCase + "method_ = []\n"), "needs a name after 'method_'"));
  BOOST_TEST(contains(refusal(kCase + kCase), "given twice"));
}

BOOST_AUTO_TEST_CASE(sph_study_refuses_bad_input_with_exit_2) {
  const auto missing = sph::test::runSph({"study", "no_such.study"});
  BOOST_TEST(missing.exitCode == 2);
  BOOST_TEST(contains(missing.output, "study file no_such.study cannot be read"));
  const auto none = sph::test::runSph({"study"});
  BOOST_TEST(none.exitCode == 2);
  BOOST_TEST(contains(none.output, "sph study needs a study file"));
  const auto jobs = sph::test::runSph({"study", (fs::path(SPH_SOURCE_DIR) / "studies" / "ci_small.study").string(),
                                       "--jobs", "0"});
  BOOST_TEST(jobs.exitCode == 2);
  BOOST_TEST(contains(jobs.output, "--jobs"));
}

// The runner: a second call keeps finished runs; a run whose values the
// study file changed is run anew. The analysis is replaced by `true` here.
BOOST_AUTO_TEST_CASE(an_interrupted_or_repeated_study_keeps_finished_runs) {
  const fs::path dir = sph::test::scratchDir("study_resume");
  auto write = [&](const std::string& restitution) {
    std::ofstream(dir / "s.study") << "case_fall = [\"" << (kCases / "one_particle.case").string()
                                   << "\", \"dam_break\"]\n"
                                      "overrides = [\"end_time = 0.05\"]\n"
                                      "method_a = [\"restitution = 0.5\"]\n"
                                      "method_b = [\"restitution = "
                                   << restitution << "\"]\n";
  };
  write("0.9");
  ::setenv("SPH_PYTHON", "/bin/true", 1);
  const std::vector<std::string> args = {"study", (dir / "s.study").string(), "--output", (dir / "out").string(),
                                         "--jobs", "2"};
  const auto first = sph::test::runSph(args);
  BOOST_TEST(first.exitCode == 0, first.output);
  BOOST_TEST(contains(first.output, "fall__a__case: started, finished"));
  BOOST_TEST(contains(first.output, "fall__b__case: started, finished"));
  BOOST_TEST(fs::exists(dir / "out" / "study.json"));
  BOOST_TEST(fs::exists(dir / "out" / "runs" / "fall__a__case" / "run.json"));
  const auto second = sph::test::runSph(args);
  BOOST_TEST(second.exitCode == 0, second.output);
  BOOST_TEST(contains(second.output, "fall__a__case: done before, kept"));
  BOOST_TEST(contains(second.output, "fall__b__case: done before, kept"));
  write("0.8");
  const auto third = sph::test::runSph(args);
  BOOST_TEST(third.exitCode == 0, third.output);
  BOOST_TEST(contains(third.output, "fall__a__case: done before, kept"));
  BOOST_TEST(contains(third.output, "fall__b__case: started anew, finished"));
  ::unsetenv("SPH_PYTHON");
  fs::remove_all(dir);
}

BOOST_AUTO_TEST_SUITE_END()
