// Reads a .pvd series the way ParaView does: VTK's XML parser for the
// collection, vtkXMLPolyDataReader for every dataset it lists. (ParaView
// ships VTK's own collection reader in its extensions, not in VTK's IOXML, so
// the tests use the parser directly.)
#pragma once

#include <boost/test/unit_test.hpp>

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLPolyDataReader.h>

#include <filesystem>
#include <string>
#include <vector>

namespace sph::test {

struct PvdEntry {
  double time;
  vtkSmartPointer<vtkPolyData> data;
};

// Fails the test if the collection or any dataset in it cannot be read.
inline std::vector<PvdEntry> readPvd(const std::filesystem::path& pvd) {
  vtkNew<vtkXMLDataParser> parser;
  const std::string name = pvd.string();
  parser->SetFileName(name.c_str());
  BOOST_TEST_REQUIRE(parser->Parse() == 1, "cannot parse " << name);
  vtkXMLDataElement* root = parser->GetRootElement();
  BOOST_TEST_REQUIRE(std::string(root->GetName()) == "VTKFile");
  BOOST_TEST_REQUIRE(std::string(root->GetAttribute("type")) == "Collection");
  vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
  BOOST_TEST_REQUIRE(collection != nullptr);
  std::vector<PvdEntry> out;
  for (int k = 0; k < collection->GetNumberOfNestedElements(); ++k) {
    vtkXMLDataElement* ds = collection->GetNestedElement(k);
    const auto file = pvd.parent_path() / ds->GetAttribute("file");
    vtkNew<vtkXMLPolyDataReader> reader;
    BOOST_TEST_REQUIRE(reader->CanReadFile(file.string().c_str()) == 1, "cannot read " << file);
    reader->SetFileName(file.string().c_str());
    reader->Update();
    vtkSmartPointer<vtkPolyData> poly = reader->GetOutput();
    BOOST_TEST_REQUIRE(poly->GetNumberOfPoints() > 0);
    out.push_back({std::stod(ds->GetAttribute("timestep")), poly});
  }
  return out;
}

}  // namespace sph::test
