// The seed scheme stays bit for bit what it was: the seven seed cases are run
// by the real executable and every snapshot they write (positions,
// velocities, accelerations, densities, pressures, masses, ids, sorted by id;
// not the time stamps, which are formatting, not arithmetic) is hashed; the hashes must equal those recorded in
// tests/reference/seed_bitwise_digests.csv, which were written by this same
// test (SPH_PRINT_DIGESTS=1) from the program just before the core was
// reshaped into the generic pass machinery. This is a regression guard, not
// a physics reference: it proves the reshaping changed no arithmetic.
#include "pvd_reader.hpp"
#include "cli_support.hpp"

#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <map>
#include <numeric>

using namespace sph;

namespace {

// FNV-1a, 64 bit, over raw bytes.
struct Fnv1a {
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t k = 0; k < n; ++k) h = (h ^ b[k]) * 1099511628211ull;
  }
  void add(double x) { add(&x, sizeof x); }
};

std::uint64_t seriesDigest(const std::filesystem::path& pvd) {
  Fnv1a f;
  for (const auto& e : test::readPvd(pvd)) {
    vtkPolyData* poly = e.data;
    vtkPointData* pd = poly->GetPointData();
    const vtkIdType n = poly->GetNumberOfPoints();
    std::vector<vtkIdType> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    vtkDataArray* id = pd->GetArray("id");
    std::sort(order.begin(), order.end(),
              [&](vtkIdType a, vtkIdType b) { return id->GetTuple1(a) < id->GetTuple1(b); });
    for (vtkIdType i : order) {
      double x[3];
      poly->GetPoint(i, x);
      for (double c : x) f.add(c);
      for (const char* vec : {"velocity", "acceleration"})
        for (int c = 0; c < 3; ++c) f.add(pd->GetArray(vec)->GetComponent(i, c));
      for (const char* s : {"density", "pressure", "mass", "id"}) f.add(pd->GetArray(s)->GetTuple1(i));
    }
  }
  return f.h;
}

std::map<std::string, std::string> recordedDigests() {
  std::ifstream in(test::referenceFile("seed_bitwise_digests.csv"));
  BOOST_TEST_REQUIRE(in.good(), "cannot read seed_bitwise_digests.csv");
  std::map<std::string, std::string> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("case,", 0) == 0) continue;
    const auto comma = line.find(',');
    out[line.substr(0, comma)] = line.substr(comma + 1);
  }
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(seed_bitwise)

BOOST_AUTO_TEST_CASE(seven_seed_cases_are_bit_identical) {
  const bool print = std::getenv("SPH_PRINT_DIGESTS") != nullptr;
  const auto recorded = print ? std::map<std::string, std::string>{} : recordedDigests();
  const auto dir = test::scratchDir("seed_bitwise");
  for (const char* name : {"one_particle", "two_particles", "three_particles", "four_particles",
                           "block_drop", "droplet", "dam_break_seed"}) {
    // Two threads and one: the gather-form loops must not depend on them.
    for (const char* threads : {"2", "1"}) {
      const auto out = dir / (std::string(name) + "_" + threads);
      const auto r = test::runSph({"run", test::caseFile(name), "--output", out.string(), "--threads", threads});
      BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
      std::ostringstream digest;
      digest << std::hex << std::setw(16) << std::setfill('0') << seriesDigest(out / (std::string(name) + ".pvd"));
      if (print) {
        std::cout << name << "," << digest.str() << "\n";
        break;
      }
      BOOST_TEST(digest.str() == recorded.at(name), name << " with " << threads << " thread(s)");
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
