// The key reference: docs/keys.md is generated from the key table
// (`sph keys`, src/key_reference.cpp) and `sph run --help` is declared from
// it (src/main.cpp). These tests fail when either drifts from the table:
// a key added, renamed, given another range, default or help text.
#include "sph/case_keys.hpp"
#include "sph/methods.hpp"
#include "test_support.hpp"

#include <boost/test/unit_test.hpp>

#include <filesystem>
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
  declared(sph::kernelMethods<2>());
  declared(sph::eosMethods());
  declared(sph::viscosityMethods());
  declared(sph::integratorMethods<2>());
  declared(sph::densityMethods());
  declared(sph::diffusionMethods());
  declared(sph::negativePressureMethods());
  declared(sph::densityReinitMethods());
  declared(sph::gradientCorrectionMethods());
  declared(sph::surfaceTensionMethods());
  declared(sph::shiftingMethods());
  declared(sph::initialFlowMethods());
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
  // The density, surface-tension and shifting families declare theirs too.
  sph::CaseConfig d = sph::test::bareWcsph(2);
  d.given = {"delta", "diffusion", "sigma", "density_reinit_every", "shifting_coefficient", "flow_speed"};
  const std::vector<std::string> densityNotes = sph::unusedKeyNotes(sph::withDefaults(d));
  const std::vector<std::string> densityExpected = {
      "key 'delta' is not used: density is summation; it applies to density continuity",
      "key 'diffusion' is not used: density is summation; it applies to density continuity",
      "key 'density_reinit_every' is not used: density_reinit is none; it applies to density_reinit shepard or mls",
      "key 'sigma' is not used: surface_tension is none; it applies to surface_tension morris, muller or corrected",
      "key 'shifting_coefficient' is not used: shifting is none; it applies to shifting fickian",
      "key 'flow_speed' is not used: initial_flow is none; it applies to initial_flow taylor_green"};
  BOOST_TEST(densityNotes == densityExpected, boost::test_tools::per_element());
}

// No method name is compared as a string outside the registry: no source
// file but methods.hpp and the boundaries' declarations (boundaries/*.hpp)
// holds `<field> == "` or `<field> != "` for a CaseConfig field whose key
// chooses from a list (the field's name is the key in camelCase). The run
// settings regime_check and probe_interpolation are not methods.
BOOST_AUTO_TEST_CASE(no_method_name_is_compared_outside_the_registry) {
  const auto camel = [](const std::string& key) {
    std::string name;
    bool up = false;
    for (char ch : key) {
      if (ch == '_') up = true;
      else name += up ? static_cast<char>(ch - 'a' + 'A') : ch, up = false;
    }
    return name;
  };
  std::vector<std::string> fields;
  for (const sph::KeySpec& k : sph::caseKeys())
    if (k.choices && std::string(k.name) != "regime_check" && std::string(k.name) != "probe_interpolation")
      fields.push_back(camel(k.name));
  BOOST_TEST(fields.size() >= 15u);
  namespace fs = std::filesystem;
  int files = 0;
  for (const char* dir : {"include", "src"})
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(SPH_SOURCE_DIR) / dir)) {
      // The registry: methods.hpp and the boundaries' own declarations.
      if (!entry.is_regular_file() || entry.path().filename() == "methods.hpp" ||
          entry.path().parent_path().filename() == "boundaries")
        continue;
      const std::string text = readText(entry.path().string());
      ++files;
      for (const std::string& f : fields)
        for (const char* op : {" == \"", " != \""}) {
          const std::string needle = "." + f + op;
          BOOST_TEST(text.find(needle) == std::string::npos,
                     entry.path().string() << " compares " << f << " with a name: ask the registry (methods.hpp)");
        }
    }
  BOOST_TEST(files > 50);
}

BOOST_AUTO_TEST_SUITE_END()
