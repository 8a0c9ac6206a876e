// A snapshot read with VTK's own reader into a map by particle id, and the
// largest differences between two such snapshots (position, velocity,
// density, mass, kind): for tests that compare two runs particle by particle
// whatever order each keeps its particles in.
#pragma once

#include <boost/test/unit_test.hpp>

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>

namespace sph::test {

struct Particle {
  std::array<double, 3> x, v;
  double rho, m;
  int kind;
};

// A snapshot read with VTK's own reader, by particle id.
inline std::map<std::int64_t, Particle> load(const std::filesystem::path& file) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file.string().c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  vtkPointData* pd = poly->GetPointData();
  std::map<std::int64_t, Particle> out;
  BOOST_TEST_REQUIRE(poly->GetNumberOfPoints() > 0, file);
  for (const char* name : {"id", "velocity", "density", "mass", "kind"})
    BOOST_TEST_REQUIRE(pd->GetArray(name) != nullptr, file << " has no " << name);
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
    Particle p{};
    poly->GetPoint(i, p.x.data());
    pd->GetArray("velocity")->GetTuple(i, p.v.data());
    p.rho = pd->GetArray("density")->GetTuple1(i);
    p.m = pd->GetArray("mass")->GetTuple1(i);
    p.kind = static_cast<int>(pd->GetArray("kind")->GetTuple1(i));
    out[static_cast<std::int64_t>(pd->GetArray("id")->GetTuple1(i))] = p;
  }
  return out;
}

struct Difference {
  double x = 0, v = 0, rho = 0, m = 0;
  int kinds = 0;  // particles whose kind differs
};

inline Difference compare(const std::map<std::int64_t, Particle>& a, const std::map<std::int64_t, Particle>& b) {
  BOOST_TEST_REQUIRE(a.size() == b.size());
  Difference d;
  for (const auto& [id, p] : a) {
    const auto it = b.find(id);
    BOOST_TEST_REQUIRE((it != b.end()), "id " << id << " missing");
    const Particle& q = it->second;
    for (int k = 0; k < 3; ++k) {
      d.x = std::max(d.x, std::abs(p.x[k] - q.x[k]));
      d.v = std::max(d.v, std::abs(p.v[k] - q.v[k]));
    }
    d.rho = std::max(d.rho, std::abs(p.rho - q.rho));
    d.m = std::max(d.m, std::abs(p.m - q.m));
    d.kinds += p.kind != q.kind;
  }
  BOOST_TEST_MESSAGE("max |dx| " << d.x << " m, |dv| " << d.v << " m/s, |drho| " << d.rho << ", |dm| " << d.m
                                 << ", kinds differing " << d.kinds);
  return d;
}

}  // namespace sph::test
