// The case-file reader (sph/case_file.hpp) on its own: the TOML subset, its
// refusals with line numbers, binary input, size cap and linear time; the
// "did you mean" suggestion; and the real executable reading case files
// (byte-order mark, CRLF, spaces in the path) and refusing bad ones with one
// line, exit status 2 and nothing written.
#include "cli_support.hpp"

#include "sph/case_file.hpp"

#include <chrono>
#include <fstream>

using namespace sph;

namespace {

// The CaseFileError that parsing `text` throws (fails the test if none).
CaseFileError refusal(const std::string& text) {
  try {
    parseCaseText(text);
  } catch (const CaseFileError& e) {
    return e;
  }
  BOOST_FAIL("no error for: " << escapeControl(text));
  return CaseFileError(0, "");
}

void expectRefused(const std::string& text, std::size_t line, const std::string& expected) {
  const CaseFileError e = refusal(text);
  BOOST_TEST_CONTEXT("text: " << escapeControl(text)) {
    BOOST_TEST(e.line() == line);
    BOOST_TEST(std::string(e.what()).find(expected) != std::string::npos, "message was: " << e.what());
  }
}

std::string writeFile(const std::string& name, const std::string& text) {
  const auto dir = test::scratchDir("case_file_" + std::to_string(std::hash<std::string>{}(name)));
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

// A one-particle case that runs in a few steps.
const std::string kTiny =
    "# one particle, two steps\n"
    "model = \"seed_wcsph\"\n"
    "dimension = 2\n"
    "dt = 1e-4\n"
    "end_time = 2e-4   # two steps\n"
    "output_every = 1\n"
    "points = [0.5, 0.5]\n";

void expectRuns(const std::string& caseFile, const std::string& pvd) {
  const auto out = test::scratchDir("case_file_run") / "out";
  const auto r = test::runSph({"run", caseFile, "--output", out.string()});
  BOOST_TEST(r.exitCode == 0, r.output);
  BOOST_TEST(std::filesystem::exists(out / pvd), r.output);
}

// `sph args... [--output DIR]` fails with exit status 2, one line starting
// "sph: error: " that contains `expected` and no raw control character, and
// writes nothing.
test::Result expectRefusedRun(std::vector<std::string> args, const std::string& expected) {
  const auto out = test::scratchDir("case_file_bad") / "out";
  if (!args.empty() && args.front() == "run") args.insert(args.end(), {"--output", out.string()});
  const auto r = test::runSph(args);
  BOOST_TEST_CONTEXT("sph " << escapeControl(args.size() > 1 ? args[1] : args.front())) {
    BOOST_TEST(r.exitCode == 2, r.output);
    BOOST_TEST(r.output.rfind("sph: error: ", 0) == 0, escapeControl(r.output));
    BOOST_TEST(r.output.find(expected) != std::string::npos, "message was: " << escapeControl(r.output));
    BOOST_TEST(std::count(r.output.begin(), r.output.end(), '\n') == 1, escapeControl(r.output));
    BOOST_TEST(escapeControl(r.output.substr(0, r.output.size() - 1)) + "\n" == r.output);
    BOOST_TEST(!std::filesystem::exists(out));
  }
  return r;
}

std::string bigArray(const char* key, std::size_t n) {
  std::string text = std::string(key) + " = [";
  for (std::size_t i = 0; i < n; ++i) text += i ? ", 0.25" : "0.25";
  return text + "]\n";
}

double secondsToParse(const std::string& text, std::size_t expectedValues) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto entries = parseCaseText(text);
  const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - t0;
  BOOST_TEST(entries.size() == 1u);
  BOOST_TEST(entries.front().values.size() == expectedValues);
  BOOST_TEST(entries.front().values.back() == "0.25");
  return dt.count();
}

const std::vector<std::string> kKeys{"output", "name", "model", "h", "k", "g", "mu", "rho0", "viscosity",
                                     "end_time", "output_every", "dt", "domain_min", "domain_max"};

}  // namespace

BOOST_AUTO_TEST_SUITE(case_file)

BOOST_AUTO_TEST_CASE(keys_values_lines_and_comments) {
  const auto e = parseCaseText(
      "# a comment\n"
      "\n"
      "  h = 0.01   # support radius\n"
      "model = \"wcsph\"#no space\n"
      "walls = false\n"
      "points = [0.5, 0.5, 1e-3]\n");
  BOOST_REQUIRE(e.size() == 4u);
  BOOST_TEST(e[0].line == 3u);
  BOOST_TEST(e[0].key == "h");
  BOOST_TEST(e[0].values == std::vector<std::string>{"0.01"});
  BOOST_TEST(!e[0].array);
  BOOST_TEST(e[1].key == "model");
  BOOST_TEST(e[1].values == std::vector<std::string>{"wcsph"});
  BOOST_TEST(e[2].values == std::vector<std::string>{"false"});
  BOOST_TEST(e[3].line == 6u);
  BOOST_TEST(e[3].array);
  BOOST_TEST((e[3].values == std::vector<std::string>{"0.5", "0.5", "1e-3"}));
  BOOST_TEST(parseCaseText("").empty());
  BOOST_TEST(parseCaseText("# only a comment").empty());
}

BOOST_AUTO_TEST_CASE(byte_order_mark_and_crlf_read_as_plain_text) {
  const std::string plain = "h = 0.01 # x\nname = \"a b\"\npoints = [1,\n  2]\n";
  std::string crlf;
  for (char c : plain) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  for (const std::string& text : {"\xEF\xBB\xBF" + plain, crlf, "\xEF\xBB\xBF" + crlf}) {
    const auto e = parseCaseText(text);
    BOOST_REQUIRE(e.size() == 3u);
    BOOST_TEST(e[0].key == "h");
    BOOST_TEST(e[0].values.front() == "0.01");
    BOOST_TEST(e[1].values.front() == "a b");
    BOOST_TEST((e[2].values == std::vector<std::string>{"1", "2"}));
    BOOST_TEST(e[2].line == 3u);
  }
  // A byte-order mark anywhere else is not a key.
  expectRefused("h = 1\n\xEF\xBB\xBFk = 2\n", 2, "expected 'key = value'");
}

BOOST_AUTO_TEST_CASE(strings_with_escapes) {
  const auto e = parseCaseText(
      "a = \"say \\\"hi\\\" \\\\ back\"\n"
      "b = \"not # a comment\"  # a comment\n"
      "c = 'C:\\path\\no escapes'\n"
      "d = \"\"\n"
      "e = \"tab\there, ü\"\n");
  BOOST_REQUIRE(e.size() == 5u);
  BOOST_TEST(e[0].values.front() == "say \"hi\" \\ back");
  BOOST_TEST(e[1].values.front() == "not # a comment");
  BOOST_TEST(e[2].values.front() == "C:\\path\\no escapes");
  BOOST_TEST(e[3].values.front() == "");
  BOOST_TEST(e[4].values.front() == "tab\there, ü");
  expectRefused("a = \"bad \\n escape\"\n", 1, "only \\\" and \\\\ are allowed");
  expectRefused("x = 1\na = \"open\nb = 2\n", 2, "unterminated string in the value of 'a'");
  expectRefused("a = 'open", 1, "unterminated string");
  expectRefused("a = \"ends in a backslash\\", 1, "escape");
}

BOOST_AUTO_TEST_CASE(arrays) {
  const auto e = parseCaseText(
      "a = []\n"
      "b = [ \"x\", 'y' , \"z,]\" ]\n"
      "c = [1, 2, 3,]   # trailing comma\n"
      "d = [  # spans lines\n"
      "  1, 2,   # first row\n"
      "\n"
      "  3, 4\n"
      "]\n"
      "e = 5\n");
  BOOST_REQUIRE(e.size() == 5u);
  BOOST_TEST(e[0].array);
  BOOST_TEST(e[0].values.empty());
  BOOST_TEST((e[1].values == std::vector<std::string>{"x", "y", "z,]"}));
  BOOST_TEST((e[2].values == std::vector<std::string>{"1", "2", "3"}));
  BOOST_TEST(e[3].line == 4u);
  BOOST_TEST((e[3].values == std::vector<std::string>{"1", "2", "3", "4"}));
  BOOST_TEST(e[4].line == 9u);
  expectRefused("h = 1\na = [1, 2\n", 2, "unterminated array: the '[' of 'a' has no ']'");
  expectRefused("a = [1, 2\nb = 3\n", 2, "the array of 'a' (line 1) needs ','");
  expectRefused("a = [1 2]\n", 1, "needs ','");
  expectRefused("a = [[1], [2]]\n", 1, "holds an array");
  expectRefused("a = [1, , 2]\n", 1, "expected a value for 'a'");
  expectRefused("a = [1, 2] 3\n", 1, "unexpected '3' after the value of 'a'");
}

BOOST_AUTO_TEST_CASE(key_given_twice_names_both_lines) {
  expectRefused("h = 1\nk = 2\n\nh = 3\n", 4, "key 'h' is given twice (lines 1 and 4)");
  expectRefused("h = 1\nh = 1\n", 2, "key 'h' is given twice (lines 1 and 2)");
  expectRefused("a = [1,\n 2]\nb = 1\na = [3]\n", 4, "key 'a' is given twice (lines 1 and 4)");
}

BOOST_AUTO_TEST_CASE(malformed_lines) {
  expectRefused("h = 1\njust some words\n", 2, "expected 'key = value' (a key is letters, digits, '_' and '-'), found 'just some words'");
  expectRefused("= 3\n", 1, "expected 'key = value'");
  expectRefused("[section]\nh = 1\n", 1, "found '[section]'");
  expectRefused("walls\n", 1, "expected 'key = value'");
  expectRefused("a.b = 1\n", 1, "found 'a.b = 1'");
  expectRefused("h =\n", 1, "key 'h' has no value");
  expectRefused("h = # nothing\n", 1, "key 'h' has no value");
  expectRefused("model = seed wcsph\n", 1, "unexpected 'wcsph' after the value of 'model': quote strings");
  expectRefused("h = 1 = 2\n", 1, "unexpected '= 2'");
  expectRefused("a = \"x\" \"y\"\n", 1, "unexpected '\"y\"'");
}

BOOST_AUTO_TEST_CASE(binary_and_control_characters) {
  expectRefused(std::string("h = 1\nk = 2\0 3\n", 12), 2, "not a case file: it holds a NUL byte");
  expectRefused(std::string("\0\0\0\0", 4), 1, "not a case file: it holds a NUL byte");
  expectRefused("h = 1\x01\n", 1, "control character \\x01");
  expectRefused("name = \"a\x1b[31mb\"\n", 1, "control character \\x1b");
  expectRefused("# comment \x07 bell\n", 1, "control character \\x07");
  expectRefused("h = 1\rk = 2\n", 1, "control character \\x0d");
  expectRefused("k\x1b[2J = 1\n", 1, "found 'k\\x1b[2J = 1'");
  // Messages never hold the raw control characters.
  for (const char* text : {"h = 1\x01\n", "k\x1b[2J = 1\n", "name = \"\x1b\"\n", "h = [1, \x1b]\n", "h = 1 \x1b\n"}) {
    const std::string what = refusal(text).what();
    BOOST_TEST(what == escapeControl(what), escapeControl(what));
  }
  // readCaseFile stops at the first NUL and names its line.
  std::istringstream withNul(std::string("h = 1\nk = 2\n\n\0rest", 17));
  BOOST_CHECK_EXCEPTION(readCaseFile(withNul), CaseFileError,
                        [](const CaseFileError& e) { return e.line() == 4 && std::string(e.what()).find("NUL") != std::string::npos; });
}

BOOST_AUTO_TEST_CASE(size_is_capped_and_dev_zero_ends) {
  std::istringstream small("h = 1\n");
  BOOST_TEST(readCaseFile(small, 6).size() == 1u);
  std::istringstream large(std::string(200, '#'));
  BOOST_CHECK_EXCEPTION(readCaseFile(large, 100), CaseFileError, [](const CaseFileError& e) {
    return e.line() == 0 && std::string(e.what()) == "not a case file: it is larger than 100 bytes";
  });
  // No NUL and no newline: the cap alone ends the read.
  std::istringstream huge(std::string((std::size_t{1} << 20) + 1, '#'));
  BOOST_CHECK_EXCEPTION(readCaseFile(huge, std::size_t{1} << 20), CaseFileError,
                        [](const CaseFileError& e) { return std::string(e.what()).find("larger than 1 MB") != std::string::npos; });
  std::ifstream zero("/dev/zero", std::ios::binary);
  BOOST_REQUIRE(zero.good());
  BOOST_CHECK_EXCEPTION(readCaseFile(zero), CaseFileError,
                        [](const CaseFileError& e) { return e.line() == 1 && std::string(e.what()).find("not a case file") == 0; });
}

// Linear time: ten times the values take about ten times as long. The bound
// is 5x that, plus a second of slack, so that a slow machine cannot fail it
// but a quadratic reader (100x) does; the times are printed.
BOOST_AUTO_TEST_CASE(long_array_parses_in_linear_time) {
  const std::string small = bigArray("points", 100000), large = bigArray("points", 1000000);
  const double t5 = secondsToParse(small, 100000);
  const double t6 = secondsToParse(large, 1000000);
  BOOST_TEST_MESSAGE("parse of 1e5 values: " << t5 << " s, 1e6 values: " << t6 << " s (" << t6 / t5 << "x)");
  BOOST_TEST(t6 < 50 * t5 + 1.0);
}

BOOST_AUTO_TEST_CASE(edit_distance) {
  BOOST_TEST(editDistance("", "") == 0u);
  BOOST_TEST(editDistance("abc", "") == 3u);
  BOOST_TEST(editDistance("kitten", "sitting") == 3u);
  BOOST_TEST(editDistance("end_tme", "end_time") == 1u);
  BOOST_TEST(editDistance("ned_time", "end_time") == 1u);  // a swap costs 1
  BOOST_TEST(editDistance("ca", "abc") == 3u);             // optimal string alignment
}

BOOST_AUTO_TEST_CASE(closest_key) {
  BOOST_TEST(closestKey("end_tme", kKeys).value_or("-") == "end_time");
  BOOST_TEST(closestKey("viscosty", kKeys).value_or("-") == "viscosity");
  BOOST_TEST(closestKey("outputevery", kKeys).value_or("-") == "output_every");
  BOOST_TEST(closestKey("END_TIME", kKeys).value_or("-") == "end_time");
  BOOST_TEST(closestKey("rho", kKeys).value_or("-") == "rho0");
  BOOST_TEST(closestKey("domainmax", kKeys).value_or("-") == "domain_max");
  BOOST_TEST(closestKey("modle", kKeys).value_or("-") == "model");
  BOOST_TEST(!closestKey("x", kKeys));  // one letter: any one-letter key is one edit away
  BOOST_TEST(!closestKey("temperature", kKeys));
  BOOST_TEST(!closestKey("end", kKeys));
  BOOST_TEST(!closestKey("anything", {}));
  BOOST_TEST(!closestKey(std::string(100000, 'a'), kKeys));
  BOOST_TEST(unknownKeyMessage("end_tme", "on the command line", kKeys) ==
             "unknown key 'end_tme' (on the command line); did you mean 'end_time'? ('sph run --help' lists the keys)");
  BOOST_TEST(unknownKeyMessage("zz\x1b", "case file a.case line 3", kKeys) ==
             "unknown key 'zz\\x1b' (case file a.case line 3) ('sph run --help' lists the keys)");
}

BOOST_AUTO_TEST_CASE(escape_control_and_run_names) {
  BOOST_TEST(escapeControl("plain ü text") == "plain ü text");
  BOOST_TEST(escapeControl("a\x1b[31mb\n\x7f") == "a\\x1b[31mb\\x0a\\x7f");
  BOOST_TEST(escapeControl(std::string("\0", 1)) == "\\x00");
  BOOST_TEST(defaultRunName("cases/dam_break.case") == "dam_break");
  BOOST_TEST(defaultRunName("/tmp/my dir/my case.case") == "my_case");
  BOOST_TEST(defaultRunName("a/v1.2.case") == "v1.2");
  BOOST_TEST(defaultRunName("") == "sph");
}

// The real executable.

BOOST_AUTO_TEST_CASE(byte_order_mark_crlf_and_spaces_run) {
  expectRuns(writeFile("bom.case", "\xEF\xBB\xBF" + kTiny), "bom.pvd");
  std::string crlf;
  for (char c : kTiny) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  expectRuns(writeFile("crlf.case", crlf), "crlf.pvd");
  expectRuns(writeFile("my case.case", kTiny), "my_case.pvd");
}

BOOST_AUTO_TEST_CASE(refused_case_files) {
  const std::string twice = writeFile("twice.case", kTiny + "\ndt = 2e-4\n");
  expectRefusedRun({"run", twice}, "case file " + twice + " line 9: key 'dt' is given twice (lines 4 and 9)");
  const std::string words = writeFile("words.case", kTiny + "some words\n");
  expectRefusedRun({"run", words}, "case file " + words + " line 8: expected 'key = value'");
  const std::string open = writeFile("open.case", kTiny + "name = \"x\n");
  expectRefusedRun({"run", open}, "line 8: unterminated string in the value of 'name'");
  const std::string array = writeFile("array.case", "domain_min = [0, 0\n");
  expectRefusedRun({"run", array}, "line 1: unterminated array: the '[' of 'domain_min' has no ']'");
  const std::string binary = writeFile("binary.case", std::string("h = 1\n\0\0\0", 9));
  expectRefusedRun({"run", binary}, "case file " + binary + " line 2: not a case file: it holds a NUL byte");
  const std::string dir = test::scratchDir("case_file_dir").string();
  expectRefusedRun({"run", dir}, "case file " + dir + " is a directory");
}

BOOST_AUTO_TEST_CASE(dev_zero_is_refused_quickly) {
  const auto t0 = std::chrono::steady_clock::now();
  expectRefusedRun({"run", "/dev/zero"}, "case file /dev/zero line 1: not a case file");
  const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - t0;
  BOOST_TEST_MESSAGE("sph run /dev/zero: " << dt.count() << " s");
  BOOST_TEST(dt.count() < 10.0);
}

BOOST_AUTO_TEST_CASE(control_characters_are_escaped) {
  const std::string file = writeFile("control.case", kTiny + "k\x1b[2J = 1\n");
  expectRefusedRun({"run", file}, "line 8: expected 'key = value' (a key is letters, digits, '_' and '-'), found 'k\\x1b[2J = 1'");
  expectRefusedRun({"run", test::caseFile("one_particle"), "--end\x1b[2J_time", "1"}, "unknown key 'end\\x1b[2J_time'");
  expectRefusedRun({"run", test::caseFile("one_particle"), "--name", "a\x07"}, "name = \"a\\x07\"");
}

BOOST_AUTO_TEST_CASE(did_you_mean) {
  const std::string file = writeFile("typo.case", kTiny + "end_tme = 0.1\n");
  expectRefusedRun({"run", file}, "unknown key 'end_tme' (case file " + file +
                                      " line 8); did you mean 'end_time'? ('sph run --help' lists the keys)");
  expectRefusedRun({"run", test::caseFile("one_particle"), "--end_tme", "0.1"},
                   "sph: error: unknown key 'end_tme' (on the command line); did you mean 'end_time'? "
                   "('sph run --help' lists the keys)");
  // The keys come from the App: a key with a flag alias and one of the last declared.
  expectRefusedRun({"run", test::caseFile("one_particle"), "--no_progress"}, "did you mean 'no-progress'?");
  expectRefusedRun({"run", test::caseFile("one_particle"), "--particle-file=x.csv"}, "did you mean 'particle_file'?");
  expectRefusedRun({"run", test::caseFile("one_particle"), "--temperature", "3"},
                   "unknown key 'temperature' (on the command line) ('sph run --help' lists the keys)");
  // A flag before the case file: its value is not taken for the case file.
  expectRefusedRun({"run", "--end_tme", "0.1", test::caseFile("one_particle")}, "did you mean 'end_time'?");
  expectRefusedRun({"run", test::caseFile("one_particle"), "another.case"}, "unexpected argument 'another.case'");
  expectRefusedRun({"run", test::caseFile("one_particle"), "--", "x"}, "unexpected argument '--'");
  expectRefusedRun({"--end_time", "0.1"}, "unknown option '--end_time': sph --help, sph --version or sph run CASE_FILE");
}

BOOST_AUTO_TEST_CASE(missing_subcommand) {
  const std::string dam = test::caseFile("dam_break");
  expectRefusedRun({dam}, "sph: error: missing subcommand: did you mean 'sph run " + dam + "'?");
  expectRefusedRun({dam, "--end_time", "0.1"}, "did you mean 'sph run " + dam + " --end_time 0.1'?");
  expectRefusedRun({"my case.case"}, "did you mean 'sph run \"my case.case\"'?");
  expectRefusedRun({"rn", dam}, "unknown subcommand 'rn': the subcommands are 'run', 'check', 'study' and 'keys'");
  const auto bare = test::runSph({});
  BOOST_TEST(bare.exitCode == 2);
  BOOST_TEST(bare.output.find("Usage: sph run CASE_FILE") != std::string::npos, bare.output);
}

// The whole path, CLI11 included, stays fast on a 10^6-value array (CLI11's
// own reader took 3.4 s for 128k values and 15.6 s for 256k).
BOOST_AUTO_TEST_CASE(long_array_through_the_executable) {
  const std::string file = writeFile("long.case", kTiny + bigArray("domain_min", 1000000));
  const auto t0 = std::chrono::steady_clock::now();
  expectRefusedRun({"run", file}, "domain_min has 1000000 values: it needs 2");
  const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - t0;
  BOOST_TEST_MESSAGE("sph run with a 1e6-value array: " << dt.count() << " s");
  BOOST_TEST(dt.count() < 20.0);
}

BOOST_AUTO_TEST_SUITE_END()
