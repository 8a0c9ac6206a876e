// The key reference: docs/keys.md is generated from the key table
// (`sph keys`, src/key_reference.cpp) and `sph run --help` is declared from
// it (src/main.cpp). These tests fail when either drifts from the table:
// a key added, renamed, given another range, default or help text.
#include "sph/case_keys.hpp"
#include "sph/methods.hpp"
#include "test_support.hpp"

#include <boost/test/unit_test.hpp>

#include <fstream>
#include <map>
#include <sstream>

BOOST_AUTO_TEST_SUITE(key_reference)

namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The first line where a and b differ, for the failure message.
std::string firstDifference(const std::string& a, const std::string& b) {
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool ga = static_cast<bool>(std::getline(sa, la)), gb = static_cast<bool>(std::getline(sb, lb));
    if (!ga && !gb) return "none";
    if (la != lb || ga != gb)
      return "line " + std::to_string(line) + ":\n  docs/keys.md: " + (ga ? la : "(end)") + "\n  sph keys:     " +
             (gb ? lb : "(end)");
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(docs_keys_md_is_the_table) {
  const std::string docs = readText(std::string(SPH_SOURCE_DIR) + "/docs/keys.md");
  const std::string table = sph::keyReferenceMarkdown();
  BOOST_TEST(!docs.empty(), "docs/keys.md is missing or empty");
  BOOST_TEST((docs == table), "docs/keys.md drifted from the key table; regenerate it with "
                              "'build/sph keys > docs/keys.md'. First difference at "
                                  << firstDifference(docs, table));
  // Every key has its row (what the generator must do, checked apart from it).
  for (const sph::KeySpec& k : sph::caseKeys())
    BOOST_TEST(docs.find("| `" + std::string(k.name) + "` |") != std::string::npos, "docs/keys.md lacks " << k.name);
}

BOOST_AUTO_TEST_CASE(sph_keys_prints_the_reference) {
  const auto r = sph::test::runSph({"keys"});
  BOOST_TEST(r.exitCode == 0);
  BOOST_TEST((r.output == sph::keyReferenceMarkdown()));
}

BOOST_AUTO_TEST_CASE(run_help_lists_every_key_with_its_help) {
  const auto r = sph::test::runSph({"run", "--help"});
  BOOST_TEST(r.exitCode == 0);
  for (const sph::KeySpec& k : sph::caseKeys()) {
    BOOST_TEST(r.output.find("--" + std::string(k.name)) != std::string::npos, "sph run --help lacks --" << k.name);
    // The first words of the help text (CLI11 wraps long lines).
    const std::string help = std::string(k.help).substr(0, 20);
    BOOST_TEST(r.output.find(help) != std::string::npos, "sph run --help lacks the help of " << k.name);
  }
}

// Each key is declared once: in the key table or by one method of the
// registry (methods.hpp), whose keys the table splices in after the key that
// chooses the method; a method reads the keys it declares, and the
// unused-key notes of those keys come from the same declaration.
BOOST_AUTO_TEST_CASE(every_key_is_declared_once_by_the_table_or_a_method) {
  std::map<std::string, int> seen;
  for (const sph::KeySpec& k : sph::caseKeys()) ++seen[k.name];
  for (const auto& [name, n] : seen) BOOST_TEST(n == 1, name << " is declared " << n << " times");
  const auto declared = [](const auto& table) {
    for (const auto& method : table)
      for (const sph::KeySpec& k : method.params) {
        BOOST_TEST(sph::findKey(k.name) != nullptr, k.name << " (" << method.name << ") is not in the key table");
        BOOST_TEST(sph::readsKey(method, k.name), method.name << " declares " << k.name << " but does not read it");
      }
  };
  declared(sph::eosMethods());
  declared(sph::viscosityMethods());
  // The notes name the chosen method and the methods that read the key.
  sph::CaseConfig c = sph::test::bareWcsph(2);
  c.viscosity = "morris";
  c.eos = "tait";
  c.c0 = 10;
  c.given = {"alpha", "polytropic_index", "nu", "c0"};
  const std::vector<std::string> notes = sph::unusedKeyNotes(sph::withDefaults(c));
  const std::vector<std::string> expected = {
      "key 'polytropic_index' is not used: eos is tait; it applies to eos polytropic",
      "key 'alpha' is not used: viscosity is morris; it applies to viscosity monaghan"};
  BOOST_TEST(notes == expected, boost::test_tools::per_element());
}

BOOST_AUTO_TEST_SUITE_END()
