// Broken particle files are refused, never crash or hang sph, and failed
// writes leave no temporaries.
//
// Each broken file is made here from a good .vtp written by `sph run` itself
// (or rewritten by VTK in another layout: ascii, inline or appended base64):
// truncated, bytes flipped in the header and in the appended data, header
// values replaced (NumberOfPoints 99999999, NumberOfComponents 2^64-1, ...),
// values made bad through VTK (mass -1, TimeValue nan, repeated ids, ...),
// plus files that are empty, not XML, or a directory, and 200 random
// single-byte damages and truncations (fixed seed). `sph run` on each, under
// `timeout`, must exit with status 2 and print exactly one line, starting
// `sph: error: particle_file <path>`, and write nothing; a random damage that
// leaves the file valid may instead run (status 0). Never a signal, never a
// timeout, never a VTK log line.
#include "cli_support.hpp"

#include "sph/io/atomic_file.hpp"
#include "sph/io/vtp_io.hpp"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <functional>
#include <iterator>
#include <limits>
#include <random>

using namespace sph;

namespace {

// `sph run` with a time limit: a hang ends as status 124, a crash as a signal
// (reported as 1000 + signal), so neither can pass for 0 or 2.
test::Result runLimited(const std::vector<std::string>& args) {
  std::string cmd = std::string("timeout -k 5 20 '") + SPH_EXECUTABLE + "'";
  for (const auto& a : args) cmd += " '" + a + "'";
  cmd += " 2>&1";
  test::Result r{-1, ""};
  FILE* pipe = ::popen(cmd.c_str(), "r");
  BOOST_REQUIRE(pipe != nullptr);
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe)) r.output += buf.data();
  const int status = ::pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
  return r;
}

// Runs sph on one particle file: a fast case (4 particles, 2 steps).
test::Result runOn(const std::string& particleFile, const std::filesystem::path& out) {
  return runLimited({"run", test::caseFile("four_particles"), "--output", out.string(), "--end_time", "0.0002",
                     "--particle_file", particleFile});
}

bool hasVtkLog(const std::string& output) {
  return output.find('\x1b') != std::string::npos || output.find("ERR|") != std::string::npos ||
         output.find("WARN|") != std::string::npos || output.find("vtkXML") != std::string::npos;
}

// Refused as the house rule says: status 2, one line naming the file (and
// `expected`), no VTK log lines, nothing written.
void expectRefused(const std::string& file, const std::string& expected) {
  const auto out = test::scratchDir("bad_files_run") / "out";
  const auto r = runOn(file, out);
  BOOST_TEST_CONTEXT(file) {
    BOOST_TEST(r.exitCode == 2, r.output);
    BOOST_TEST(r.output.rfind("sph: error: particle_file " + file, 0) == 0, r.output);
    BOOST_TEST(r.output.find(expected) != std::string::npos, "expected '" << expected << "' in: " << r.output);
    BOOST_TEST(std::count(r.output.begin(), r.output.end(), '\n') == 1, r.output);
    BOOST_TEST(!hasVtkLog(r.output), r.output);
    BOOST_TEST(!std::filesystem::exists(out));
  }
}

std::string readBytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::filesystem::path folder() {
  static const auto dir = test::scratchDir("bad_files");
  return dir;
}

std::string writeBytes(const std::string& name, const std::string& bytes) {
  const auto p = folder() / name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p.string();
}

// A good snapshot written by `sph run` (4 particles, t = 0), read once.
const std::string& goodVtp() {
  static const std::string bytes = [] {
    const auto dir = test::scratchDir("bad_files_good");
    const auto r = runLimited({"run", test::caseFile("four_particles"), "--output", dir.string(), "--end_time", "0.0002"});
    BOOST_TEST_REQUIRE(r.exitCode == 0, r.output);
    return readBytes(dir / "four_particles_00000.vtp");
  }();
  return bytes;
}

std::string replaced(const std::string& from, const std::string& to) {
  std::string s = goodVtp();
  const auto at = s.find(from);
  BOOST_TEST_REQUIRE(at != std::string::npos, "the good file has no " << from);
  return s.replace(at, from.size(), to);
}

// Where the appended data start (the byte after '_'), and where the data of
// the first DataArray named `name` start (its block header).
std::size_t appendedStart(const std::string& s = goodVtp()) { return s.find('_', s.find("<AppendedData")) + 1; }
std::size_t dataOf(const std::string& name, const std::string& s = goodVtp()) {
  const auto tag = s.find("Name=\"" + name + "\"");
  const auto offset = s.find("offset=\"", tag) + 8;
  return appendedStart(s) + std::stoul(s.substr(offset));
}

// The good file read by VTK, changed by `edit`, written as sph writes or
// as `layout` sets the writer up.
std::string rewritten(const std::string& name, const std::function<void(vtkPolyData*)>& edit,
                      const std::function<void(vtkXMLPolyDataWriter*)>& layout = {}) {
  const std::string good = writeBytes("good_for_" + name, goodVtp());
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(good.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  BOOST_TEST_REQUIRE(poly->GetNumberOfPoints() == 4);
  edit(poly);
  const std::string path = (folder() / name).string();
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(poly);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  if (layout) layout(writer);
  BOOST_TEST_REQUIRE(writer->Write() == 1);
  return path;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(bad_files)

BOOST_AUTO_TEST_CASE(the_good_file_and_its_rewrite_run) {
  // The controls: without damage the same runs succeed.
  for (const std::string& file : {writeBytes("good.vtp", goodVtp()), rewritten("same.vtp", [](vtkPolyData*) {})}) {
    const auto out = test::scratchDir("bad_files_good_run") / "out";
    const auto r = runOn(file, out);
    BOOST_TEST(r.exitCode == 0, r.output);
    BOOST_TEST(!hasVtkLog(r.output), r.output);
    BOOST_TEST(std::filesystem::exists(out / "four_particles.pvd"));
  }
}

namespace {
void uncompressed(vtkXMLPolyDataWriter* w) { w->SetCompressorTypeToNone(); }
void lz4(vtkXMLPolyDataWriter* w) { w->SetCompressorTypeToLZ4(); }
void ascii(vtkXMLPolyDataWriter* w) { w->SetDataModeToAscii(); }
void inlineZlib(vtkXMLPolyDataWriter* w) { w->SetDataModeToBinary(); }
void inlineRaw(vtkXMLPolyDataWriter* w) {
  w->SetDataModeToBinary();
  w->SetCompressorTypeToNone();
}
void base64(vtkXMLPolyDataWriter* w) {
  w->EncodeAppendedDataOn();
  w->SetCompressorTypeToNone();
}
void base64Lz4(vtkXMLPolyDataWriter* w) {
  w->EncodeAppendedDataOn();
  w->SetCompressorTypeToLZ4();
}
}  // namespace

BOOST_AUTO_TEST_CASE(other_layouts_vtk_writes_run) {
  const auto nothing = [](vtkPolyData*) {};
  const std::vector<std::pair<std::string, std::function<void(vtkXMLPolyDataWriter*)>>> layouts{
      {"raw_u64_big.vtp",
       [](vtkXMLPolyDataWriter* w) {
         w->SetCompressorTypeToNone();
         w->SetHeaderTypeToUInt64();
         w->SetByteOrderToBigEndian();
       }},
      {"lz4.vtp", lz4},
      {"ascii_layout.vtp", ascii},
      {"inline_zlib.vtp", inlineZlib},
      {"inline_raw_u64.vtp",
       [](vtkXMLPolyDataWriter* w) {
         inlineRaw(w);
         w->SetHeaderTypeToUInt64();
       }},
      {"base64_layout.vtp", base64},
      {"base64_lz4.vtp", base64Lz4},
      {"lzma.vtp", [](vtkXMLPolyDataWriter* w) { w->SetCompressorTypeToLZMA(); }},
      {"zlib_u64_big.vtp", [](vtkXMLPolyDataWriter* w) {
         w->SetHeaderTypeToUInt64();
         w->SetByteOrderToBigEndian();
       }}};
  for (const auto& [name, layout] : layouts) {
    const auto out = test::scratchDir("bad_files_layout") / "out";
    const auto r = runOn(rewritten(name, nothing, layout), out);
    BOOST_TEST(r.exitCode == 0, name << ": " << r.output);
    BOOST_TEST(!hasVtkLog(r.output), r.output);
    BOOST_TEST(std::filesystem::exists(out / "four_particles.pvd"), name);
  }
}

BOOST_AUTO_TEST_CASE(files_that_are_not_vtp) {
  expectRefused(writeBytes("empty.vtp", ""), "is empty");
  expectRefused(writeBytes("text.vtp", "not xml at all\n"), "not a VTK XML file");
  std::mt19937 rng(7);
  std::string noise(3000, '\0');
  for (char& c : noise) c = static_cast<char>(rng() & 0xff);
  expectRefused(writeBytes("noise.vtp", noise), "");
  std::filesystem::create_directories(folder() / "folder.vtp");
  expectRefused((folder() / "folder.vtp").string(), "not a file");
  expectRefused(writeBytes("grid.vtp", replaced("type=\"PolyData\"", "type=\"UnstructuredGrid\"")), "PolyData");
}

BOOST_AUTO_TEST_CASE(truncated_files) {
  const std::string& g = goodVtp();
  const std::size_t data = appendedStart();
  const std::size_t header = g.find("<AppendedData");
  for (std::size_t at : {std::size_t{1}, std::size_t{100}, header / 2, header, data - 1, data, data + 20,
                         dataOf("Points") + 10, g.rfind("</AppendedData>") - 4}) {
    const std::string file = writeBytes("cut_" + std::to_string(at) + ".vtp", g.substr(0, at));
    expectRefused(file, at > data ? "truncated" : "");
  }
}

BOOST_AUTO_TEST_CASE(flipped_bytes) {
  auto flipped = [](std::size_t at, int bits = 0xff) {
    std::string s = goodVtp();
    s[at] = static_cast<char>(s[at] ^ bits);
    return s;
  };
  const std::string& g = goodVtp();
  expectRefused(writeBytes("flip_points_tag.vtp", flipped(g.find("<Points>"))), "malformed");
  expectRefused(writeBytes("flip_attribute.vtp", flipped(g.find("NumberOfPoints"), 0x20)), "NumberOfPoints");
  expectRefused(writeBytes("flip_underscore.vtp", flipped(appendedStart() - 1)), "'_'");
  // The Points block header (UInt32 words: blocks, block size, last block,
  // compressed size) and its zlib data.
  const std::size_t points = dataOf("Points");
  expectRefused(writeBytes("flip_blocks.vtp", flipped(points + 3)), "Points");
  std::string zeroBlock = g;
  zeroBlock.replace(points + 4, 4, std::string(4, '\0'));
  expectRefused(writeBytes("zero_block_size.vtp", zeroBlock), "compression header");
  expectRefused(writeBytes("flip_compressed_size.vtp", flipped(points + 15)), "Points");
  expectRefused(writeBytes("flip_zlib_data.vtp", flipped(points + 16 + 5)), "VTK cannot read it");
}

// VTK sizes the connectivity by the last cell offset, a data value: a
// damaged one made VTK abort (uncompressed and LZ4 data have no checksum).
BOOST_AUTO_TEST_CASE(damaged_cell_offset) {
  // sph writes the vertex offsets as Int32; VTK's 64-bit vtkIdType (Int64)
  // is in files of other programs and of sph before 2026-12-07.
  for (const std::size_t width : {4u, 8u}) {
    const auto storage = [width](vtkPolyData* poly) {
      if (width == 8) poly->GetVerts()->ConvertTo64BitStorage();
      else poly->GetVerts()->ConvertTo32BitStorage();
    };
    const std::string raw = readBytes(rewritten("raw.vtp", storage, uncompressed));
    BOOST_TEST_REQUIRE(raw.find(std::string("type=\"Int") + (width == 4 ? "32" : "64") + "\" Name=\"offsets\"") !=
                       std::string::npos);
    std::string s = raw;
    const std::size_t last = dataOf("offsets", raw) + 4 + 3 * width;  // UInt32 size, then 4 offsets
    BOOST_TEST_REQUIRE(raw.compare(last, width, std::string("\x04\0\0\0\0\0\0\0", width)) == 0);
    s[last + width - 1] = 0x7f;
    expectRefused(writeBytes("huge_offset.vtp", s), "cell offsets of <Verts>");
  }
}

BOOST_AUTO_TEST_CASE(header_values_out_of_range) {
  const std::string n = "NumberOfPoints=\"4\"";
  expectRefused(writeBytes("points_99999999.vtp", replaced(n, "NumberOfPoints=\"99999999\"")), "NumberOfPoints = 99999999");
  expectRefused(writeBytes("points_0.vtp", replaced(n, "NumberOfPoints=\"0\"")), "NumberOfPoints = 0");
  expectRefused(writeBytes("points_minus_4.vtp", replaced(n, "NumberOfPoints=\"-4\"")), "NumberOfPoints");
  expectRefused(writeBytes("points_huge.vtp", replaced(n, "NumberOfPoints=\"18446744073709551615\"")), "NumberOfPoints");
  const std::string velocity = "Name=\"velocity\" NumberOfComponents=\"3\"";
  expectRefused(writeBytes("components_huge.vtp",
                           replaced(velocity, "Name=\"velocity\" NumberOfComponents=\"18446744073709551615\"")),
                "NumberOfComponents");
  expectRefused(writeBytes("components_2.vtp", replaced(velocity, "Name=\"velocity\" NumberOfComponents=\"2\"")), "velocity");
  const std::string points = "Name=\"Points\" NumberOfComponents=\"3\"";
  expectRefused(writeBytes("points_components.vtp",
                           replaced(points, "Name=\"Points\" NumberOfComponents=\"18446744073709551615\"")),
                "NumberOfComponents");
  expectRefused(writeBytes("float77.vtp", replaced("type=\"Float64\" Name=\"Points\"", "type=\"Float77\" Name=\"Points\"")),
                "Float77");
  expectRefused(writeBytes("ascii.vtp", replaced("NumberOfComponents=\"3\" format=\"appended\"",
                                                 "NumberOfComponents=\"3\" format=\"ascii\"")),
                "holds 0 values");
  expectRefused(writeBytes("format.vtp", replaced("NumberOfComponents=\"3\" format=\"appended\"",
                                                  "NumberOfComponents=\"3\" format=\"hex\"")),
                "it must be ascii, binary or appended");
  expectRefused(writeBytes("base64.vtp", replaced("encoding=\"raw\"", "encoding=\"base64\"")), "base64");
  expectRefused(writeBytes("encoding.vtp", replaced("encoding=\"raw\"", "encoding=\"hex\"")), "raw or base64");
  expectRefused(writeBytes("far_offset.vtp", [] {
                  std::string s = goodVtp();
                  const auto at = s.find("offset=\"", s.find("Name=\"Points\"")) + 8;
                  return s.replace(at, s.find('"', at) - at, "999999999");
                }()),
                "Points");
  expectRefused(writeBytes("compressor.vtp", replaced("vtkZLibDataCompressor", "vtkFooCompressor")), "compressor");
  expectRefused(writeBytes("header_type.vtp", replaced("header_type=\"UInt32\"", "header_type=\"UInt16\"")), "header_type");
}

// The text layouts: ascii values are counted, base64 block headers decoded
// and checked against the element or the file, as raw ones are.
BOOST_AUTO_TEST_CASE(damaged_text_layouts) {
  const std::string text = readBytes(rewritten("ascii_for_damage.vtp", [](vtkPolyData*) {}, ascii));
  auto edited = [](std::string s, const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    BOOST_TEST_REQUIRE(at != std::string::npos, "no " << from);
    return s.replace(at, from.size(), to);
  };
  // One value fewer in the points, a huge NumberOfPoints, a last cell offset
  // past the connectivity, a word that is not a number where VTK reads it.
  const auto points = text.find('>', text.find("Name=\"Points\"")) + 1;
  const auto firstValue = text.find_first_not_of(" \n", points);
  std::string oneShort = text;
  oneShort.erase(firstValue, text.find(' ', firstValue) - firstValue);
  expectRefused(writeBytes("ascii_one_short.vtp", oneShort), "holds 11 values");
  expectRefused(writeBytes("ascii_huge_count.vtp", edited(text, "NumberOfPoints=\"4\"", "NumberOfPoints=\"99999999\"")),
                "NumberOfPoints");
  const auto offsets = text.find('>', text.find("Name=\"offsets\"")) + 1;
  std::string hugeOffset = text;
  hugeOffset.insert(text.find('<', offsets), " 99999999999 ");
  expectRefused(writeBytes("ascii_huge_offset.vtp", edited(hugeOffset, "NumberOfVerts=\"4\"", "NumberOfVerts=\"5\"")),
                "cell offsets of <Verts>");
  std::string word = text;
  word.replace(firstValue, 1, "x");
  expectRefused(writeBytes("ascii_word.vtp", word), "particle_file");

  // Inline base64: the Points text cut short, its size word made huge.
  const std::string inl = readBytes(rewritten("inline_for_damage.vtp", [](vtkPolyData*) {}, inlineRaw));
  const auto pointsText = inl.find_first_not_of(" \n", inl.find('>', inl.find("Name=\"Points\"")) + 1);
  std::string cut = inl;
  cut.erase(pointsText + 40, inl.find('<', pointsText) - pointsText - 40);
  expectRefused(writeBytes("inline_cut.vtp", cut), "runs past the end of its element");
  std::string hugeSize = inl;
  hugeSize.replace(pointsText, 8, "/////w==");  // size word 0x00ffffff
  expectRefused(writeBytes("inline_huge_size.vtp", hugeSize), "Points");
  std::string notBase64 = inl;
  notBase64[pointsText + 2] = '*';  // in the size word, which sph decodes (VTK decodes the values)
  expectRefused(writeBytes("inline_not_base64.vtp", notBase64), "not valid base64");

  // Appended base64, cut inside the data.
  const std::string b64 = readBytes(rewritten("base64_for_damage.vtp", [](vtkPolyData*) {}, base64Lz4));
  expectRefused(writeBytes("base64_cut.vtp", b64.substr(0, b64.size() - 200)), "truncated");
}

BOOST_AUTO_TEST_CASE(structure) {
  expectRefused(writeBytes("two_pieces.vtp", replaced("</Piece>", "</Piece>\n<Piece NumberOfPoints=\"0\"/>")), "<Piece>");
  const std::string& g = goodVtp();
  const auto from = g.find("<Points>"), to = g.find("</Points>") + 9;
  expectRefused(writeBytes("no_points.vtp", std::string(g).erase(from, to - from)), "no <Points>");
  expectRefused(rewritten("empty_polydata.vtp", [](vtkPolyData* p) { p->Initialize(); }), "NumberOfPoints = 0");
}

BOOST_AUTO_TEST_CASE(bad_values) {
  auto setMass = [](double m) {
    return [m](vtkPolyData* p) { p->GetPointData()->GetArray("mass")->SetTuple1(1, m); };
  };
  expectRefused(rewritten("mass_negative.vtp", setMass(-1)), "mass -1");
  expectRefused(rewritten("mass_zero.vtp", setMass(0)), "mass 0");
  expectRefused(rewritten("mass_nan.vtp", setMass(std::numeric_limits<double>::quiet_NaN())), "mass nan");
  auto setTime = [](double t) {
    return [t](vtkPolyData* p) { p->GetFieldData()->GetArray("TimeValue")->SetTuple1(0, t); };
  };
  expectRefused(rewritten("time_nan.vtp", setTime(std::numeric_limits<double>::quiet_NaN())), "TimeValue = nan");
  expectRefused(rewritten("time_negative.vtp", setTime(-1)), "TimeValue = -1");
  expectRefused(rewritten("ids_twice.vtp",
                          [](vtkPolyData* p) {
                            vtkDataArray* id = p->GetPointData()->GetArray("id");
                            id->SetTuple1(2, id->GetTuple1(0));
                          }),
                "appears more than once");
  expectRefused(rewritten("position_nan.vtp",
                          [](vtkPolyData* p) { p->GetPoints()->SetPoint(3, std::nan(""), 0.5, 0); }),
                "position");
  expectRefused(rewritten("velocity_inf.vtp",
                          [](vtkPolyData* p) {
                            p->GetPointData()->GetArray("velocity")->SetComponent(0, 1, std::numeric_limits<double>::infinity());
                          }),
                "velocity");
  expectRefused(rewritten("z_in_2d.vtp", [](vtkPolyData* p) { p->GetPoints()->SetPoint(0, 0.5, 0.5, 0.25); }),
                "dimension = 2");
}

BOOST_AUTO_TEST_CASE(csv_columns_that_would_be_lost) {
  expectRefused(writeBytes("vy_only.csv", "x,y,vy\n0.5,0.5,1\n"), "column vx is missing");
  expectRefused(writeBytes("x_twice.csv", "x,x,y\n0.5,0.5,0.5\n"), "column x appears twice");
  expectRefused(writeBytes("z_in_2d.csv", "x,y,z\n0.5,0.5,0.5\n"), "header column 3 is 'z'");
  expectRefused(writeBytes("mass.csv", "x,y,mass\n0.5,0.5,1\n"), "header column 3 is 'mass'");
  expectRefused(writeBytes("wide_row.csv", "# comment\nx,y\n0.5,0.5\n0.5,0.5,7\n"), "line 4: 3 values");
  expectRefused(writeBytes("no_rows.csv", "x,y\n"), "no particles");
}

namespace {

// Random damage to `good`, `times` times: one byte (at or after `from`) set
// to another value, or, one time in four, the file cut. Never a crash, a hang
// or a VTK log line; a refusal is one line and writes nothing. With
// `allRefusalsNameTheFile` every status-2 line must name the file, and only
// 0 and 2 are allowed; else (data without checksums, whose damage can pass
// as other finite values) also the run's own checks may stop it (status 2
// with another message, or 3: blew up).
void damageRandomly(const std::string& good, std::size_t from, int times, unsigned seed, bool allRefusalsNameTheFile) {
  std::mt19937 rng(seed);
  int refused = 0, ran = 0;
  for (int k = 0; k < times; ++k) {
    std::string s = good;
    std::string what;
    if (rng() % 4 == 0) {
      s.resize(from + rng() % (s.size() - from));
      what = "cut at " + std::to_string(s.size());
    } else {
      const std::size_t at = from + rng() % (s.size() - from);
      s[at] = static_cast<char>(s[at] ^ static_cast<char>(1 + rng() % 255));
      what = "byte " + std::to_string(at) + " changed";
    }
    const std::string file = writeBytes("random.vtp", s);
    const auto out = test::scratchDir("bad_files_random") / "out";
    const auto r = runOn(file, out);
    BOOST_TEST_CONTEXT("seed " << seed << ", " << what) {
      const bool allowed = r.exitCode == 0 || r.exitCode == 2 || (!allRefusalsNameTheFile && r.exitCode == 3);
      BOOST_TEST(allowed, "exit " << r.exitCode << ": " << r.output);
      BOOST_TEST(!hasVtkLog(r.output), r.output);
      if (r.exitCode == 2) {
        ++refused;
        BOOST_TEST(r.output.rfind(allRefusalsNameTheFile ? "sph: error: particle_file " + file : "sph: error: ", 0) == 0,
                   r.output);
        BOOST_TEST(std::count(r.output.begin(), r.output.end(), '\n') == 1, r.output);
        BOOST_TEST(!std::filesystem::exists(out));
      } else if (r.exitCode == 0) {
        ++ran;
        BOOST_TEST(std::filesystem::exists(out / "four_particles.pvd"));
      }
    }
  }
  BOOST_TEST_MESSAGE("random damage (seed " << seed << "): " << refused << " refused, " << ran << " harmless and ran");
  BOOST_TEST(refused > 0);
}

}  // namespace

BOOST_AUTO_TEST_CASE(random_damage_never_crashes) { damageRandomly(goodVtp(), 0, 200, 20240601, true); }

BOOST_AUTO_TEST_CASE(random_damage_to_unchecked_data_never_crashes) {
  for (const auto& [name, layout] : {std::pair<std::string, std::function<void(vtkXMLPolyDataWriter*)>>{"raw.vtp", uncompressed},
                                     {"lz4.vtp", lz4}}) {
    const std::string good = readBytes(rewritten(name, [](vtkPolyData*) {}, layout));
    damageRandomly(good, appendedStart(good), 60, 17, false);
  }
}

// Text layouts: damage anywhere (header or data) in ascii, inline base64
// and appended base64 files.
BOOST_AUTO_TEST_CASE(random_damage_to_text_layouts_never_crashes) {
  for (const auto& [name, layout] : {std::pair<std::string, std::function<void(vtkXMLPolyDataWriter*)>>{"ascii.vtp", ascii},
                                     {"inline.vtp", inlineZlib},
                                     {"inline_raw.vtp", inlineRaw},
                                     {"base64.vtp", base64}}) {
    const std::string good = readBytes(rewritten("random_" + name, [](vtkPolyData*) {}, layout));
    damageRandomly(good, 0, 40, 23, false);
  }
}

// ---- Temporaries ----

BOOST_AUTO_TEST_CASE(a_failed_write_leaves_no_temporary) {
  const auto dir = test::scratchDir("bad_files_tmp");
  // The temporary cannot be written: a full disk (/dev/full behind it).
  const auto full = dir / "energy.csv";
  std::filesystem::create_symlink("/dev/full", temporaryName(full.string()));
  BOOST_CHECK_THROW(writeFileAtomically(full.string(), std::string(100000, 'x')), std::runtime_error);
  BOOST_TEST(!std::filesystem::exists(std::filesystem::symlink_status(temporaryName(full.string()))));
  BOOST_TEST(!std::filesystem::exists(full));
  // The rename fails: the target is a folder.
  const auto folderTarget = dir / "taken.csv";
  std::filesystem::create_directory(folderTarget);
  BOOST_CHECK_THROW(writeFileAtomically(folderTarget.string(), "x"), std::runtime_error);
  BOOST_TEST(!std::filesystem::exists(temporaryName(folderTarget.string())));
  // The folder does not exist.
  BOOST_CHECK_THROW(writeFileAtomically((dir / "none" / "a.csv").string(), "x"), std::runtime_error);
  BOOST_TEST(!std::filesystem::exists(dir / "none"));

}

namespace {
Particles<2> oneParticle() {
  Particles<2> P;
  P.x = {Vec<2>(0.5, 0.5)};
  P.v = {Vec<2>::Zero()};
  P.m = {1.0};
  P.id = {0};
  P.resize(1);
  return P;
}
}  // namespace

BOOST_AUTO_TEST_CASE(a_failed_vtp_rename_leaves_no_temporary) {
  const auto dir = test::scratchDir("bad_files_vtp_tmp");
  const auto target = dir / "s_00001.vtp";
  std::filesystem::create_directory(target);  // the rename over it fails
  BOOST_CHECK_THROW(writeVtp<2>(target.string(), oneParticle(), SnapshotInfo{}), std::runtime_error);
  BOOST_TEST(!std::filesystem::exists(temporaryName(target.string())));
}

// On a full disk vtkXMLWriter::Write() still returns 1 (only GetErrorCode()
// says ENOSPC): writeVtp checks both, so a damaged temporary is never
// renamed over a snapshot.
BOOST_AUTO_TEST_CASE(a_vtp_on_a_full_disk_is_an_error) {
  const auto dir = test::scratchDir("bad_files_vtp_full");
  const auto target = dir / "s_00000.vtp";
  std::filesystem::create_symlink("/dev/full", temporaryName(target.string()));
  const bool warnings = vtkObject::GetGlobalWarningDisplay();
  vtkObject::GlobalWarningDisplayOff();  // VTK's own complaints are expected here
  BOOST_CHECK_THROW(writeVtp<2>(target.string(), oneParticle(), SnapshotInfo{}), std::runtime_error);
  vtkObject::SetGlobalWarningDisplay(warnings);
  BOOST_TEST(!std::filesystem::exists(std::filesystem::symlink_status(temporaryName(target.string()))));
  BOOST_TEST(!std::filesystem::exists(std::filesystem::symlink_status(target)));
}

BOOST_AUTO_TEST_CASE(stale_temporaries_are_removed) {
  const auto dir = test::scratchDir("bad_files_stale");
  const std::vector<std::string> stale{"run_00003.vtp.tmp", "run.pvd.tmp", "energy.csv.tmp", "summary.json.tmp"};
  const std::vector<std::string> kept{"run_00003.vtp", "notes.tmp", "data.txt.tmp", ".vtp.tmp", "run.vtp.tmp.old"};
  for (const auto& name : stale) std::ofstream(dir / name) << "half";
  for (const auto& name : kept) std::ofstream(dir / name) << "keep";
  std::filesystem::create_directory(dir / "sub.vtp.tmp");  // a folder: not ours
  std::filesystem::create_directory(dir / "sub");
  std::ofstream(dir / "sub" / "deep.vtp.tmp") << "not in dir itself";

  BOOST_TEST(removeStaleTemporaries(dir) == stale.size());
  for (const auto& name : stale) BOOST_TEST(!std::filesystem::exists(dir / name), name);
  for (const auto& name : kept) BOOST_TEST(std::filesystem::exists(dir / name), name);
  BOOST_TEST(std::filesystem::is_directory(dir / "sub.vtp.tmp"));
  BOOST_TEST(std::filesystem::exists(dir / "sub" / "deep.vtp.tmp"));
  BOOST_TEST(removeStaleTemporaries(dir) == 0u);
  BOOST_TEST(removeStaleTemporaries(dir / "does_not_exist") == 0u);
}

BOOST_AUTO_TEST_SUITE_END()
