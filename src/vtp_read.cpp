// readVtp: particles from a .vtp file, in any layout VTK and ParaView write
// (ascii, inline base64 "binary", appended raw or base64; uncompressed or
// compressed with zlib, LZ4 or LZMA; UInt32 or UInt64 headers; either byte
// order), such that no file can crash or hang sph.
//
// VTK's vtkXMLPolyDataReader decodes the values. But it trusts the file it
// reads: a damaged block header or an absurd NumberOfPoints /
// NumberOfComponents makes it divide by zero, read out of bounds, allocate
// gigabytes or loop for minutes (found by feeding it broken files). So,
// before VTK sees the file, checkLayout() reads the XML itself (a plain scan
// of the tags before <AppendedData>, or of the whole file when the data are
// inline) and checks the structure (one PolyData piece with Points) and every
// DataArray: a known type, 1 to kMaxComponents components, and exactly the
// values that NumberOfPoints (cells, tuples) times the components need:
// ascii data by counting their words; binary data by their block header
// (decoded from base64 where they are text), which must lie inside the file
// or the element and whose (compressed) blocks must too. The last cell
// offset, by which VTK sizes the connectivity (an unchecked value that
// aborts VTK when damaged), must fit that array. Only then does VTK read the
// file, with its log output captured (its first error becomes our message)
// and only the point arrays sph uses; last, the values are checked: finite
// positions and velocities, masses > 0, unique ids, TimeValue finite and >= 0.
#include "sph/io/number_format.hpp"
#include "sph/io/vtp_io.hpp"

#include <vtkDataArray.h>
#include <vtkDataArraySelection.h>
#include <vtkBase64Utilities.h>
#include <vtkFieldData.h>
#include <vtkLZ4DataCompressor.h>
#include <vtkLZMADataCompressor.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkVariant.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkZLibDataCompressor.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace sph {
namespace {

constexpr std::uint64_t kMaxHeaderBytes = 4u << 20;    // read first; sph's own headers are ~5 kB
constexpr std::uint64_t kMaxCount = 1000000000;        // points, cells or tuples (= kMaxParticles)
constexpr std::uint64_t kMaxComponents = 64;

// A problem with the file; readVtp() prefixes the path.
struct Problem : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Text from the file, made safe for a one-line message.
std::string printable(const std::string& s) {
  std::string out;
  for (char c : s.substr(0, 40)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  return s.size() > 40 ? out + "..." : out;
}

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

// ---- The XML header, as a tree of elements ----

struct Element {
  std::string name;
  std::map<std::string, std::string> attributes;
  int parent = -1;
  std::vector<int> children;
  std::size_t textBegin = 0, textEnd = 0;  // its text before the first child or its end tag, trimmed

  std::optional<std::string> attribute(const std::string& key) const {
    const auto it = attributes.find(key);
    if (it == attributes.end()) return std::nullopt;
    return trimmed(it->second);
  }
};

struct Header {
  std::vector<Element> elements;  // [0] is the root
  bool hasAppendedData = false;
  std::string appendedEncoding;
  std::uint64_t appendedStart = 0;  // file offset of the byte after the '_' that starts the data
};

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
bool isNameChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == ':' || c == '-' || c == '.';
}

// The tags before "<AppendedData" (where VTK's parser stops, too) and that
// tag itself. Text between tags, comments, <?...?> and <!...> are skipped.
Header parseHeader(const std::string& s) {
  Header h;
  const std::size_t stop = s.find("<AppendedData");  // npos: the whole text is XML
  std::vector<int> open;
  std::size_t i = 0;
  auto fail = [&](const std::string& what) {
    throw Problem("its XML header is malformed at byte " + std::to_string(std::min(i, s.size())) + ": " + what);
  };
  auto skipTo = [&](const char* end, std::size_t from) {
    const std::size_t e = s.find(end, from);
    if (e == std::string::npos || (stop != std::string::npos && e > stop)) fail("unterminated <! or <?");
    return e + std::char_traits<char>::length(end);
  };
  while ((i = s.find('<', i)) != std::string::npos) {
    if (s.compare(i, 4, "<!--") == 0) { i = skipTo("-->", i + 4); continue; }
    if (s.compare(i, 2, "<?") == 0) { i = skipTo("?>", i + 2); continue; }
    if (s.compare(i, 2, "<!") == 0) { i = skipTo(">", i + 2); continue; }
    std::size_t j = i + 1;
    const bool closing = j < s.size() && s[j] == '/';
    if (closing) ++j;
    const std::size_t nameStart = j;
    while (j < s.size() && isNameChar(s[j])) ++j;
    Element e;
    e.name = s.substr(nameStart, j - nameStart);
    if (e.name.empty()) fail("a '<' that starts no tag");
    bool selfClosing = false;
    for (;;) {
      while (j < s.size() && isSpace(s[j])) ++j;
      if (j >= s.size()) fail("the tag <" + printable(e.name) + " is not closed");
      if (s[j] == '>') { ++j; break; }
      if (!closing && s[j] == '/' && j + 1 < s.size() && s[j + 1] == '>') { selfClosing = true; j += 2; break; }
      std::size_t k = j;
      while (k < s.size() && isNameChar(s[k])) ++k;
      if (closing || k == j) fail("unexpected character in the tag <" + printable(e.name) + ">");
      const std::string key = s.substr(j, k - j);
      while (k < s.size() && isSpace(s[k])) ++k;
      if (k >= s.size() || s[k] != '=') fail("attribute " + printable(key) + " has no value");
      ++k;
      while (k < s.size() && isSpace(s[k])) ++k;
      if (k >= s.size() || (s[k] != '"' && s[k] != '\'')) fail("attribute " + printable(key) + " is not quoted");
      const std::size_t close = s.find(s[k], k + 1);
      if (close == std::string::npos) fail("attribute " + printable(key) + " is not closed");
      if (!e.attributes.emplace(key, s.substr(k + 1, close - k - 1)).second)
        fail("attribute " + printable(key) + " appears twice");
      j = close + 1;
    }
    // A tag that swallows "<AppendedData" is read differently by VTK: refuse.
    if (stop != std::string::npos && i < stop && j > stop) fail("<AppendedData inside another tag");
    if (closing) {
      if (open.empty() || h.elements[static_cast<std::size_t>(open.back())].name != e.name)
        fail("</" + printable(e.name) + "> closes no open element");
      open.pop_back();
      i = j;
      continue;
    }
    if (open.empty() && !h.elements.empty()) fail("a second root element <" + printable(e.name) + ">");
    if (open.size() > 32) fail("elements nested too deep");
    e.parent = open.empty() ? -1 : open.back();
    const int index = static_cast<int>(h.elements.size());
    if (e.parent >= 0) h.elements[static_cast<std::size_t>(e.parent)].children.push_back(index);
    h.elements.push_back(std::move(e));
    if (i == stop) {
      // The raw data start after the tag, white space and one '_'.
      while (j < s.size() && isSpace(s[j])) ++j;
      if (j >= s.size() || s[j] != '_') fail("the appended data do not start with '_'");
      h.hasAppendedData = true;
      h.appendedEncoding = h.elements.back().attribute("encoding").value_or("");
      h.appendedStart = j + 1;
      return h;
    }
    if (!selfClosing) {
      open.push_back(index);
      Element& added = h.elements.back();
      added.textEnd = std::min(s.find('<', j), s.size());
      added.textBegin = std::min(s.find_first_not_of(" \t\r\n", j), added.textEnd);
      while (added.textEnd > added.textBegin && isSpace(s[added.textEnd - 1])) --added.textEnd;
    }
    i = j;
  }
  if (!open.empty())
    throw Problem("its XML header ends before <" + printable(h.elements[static_cast<std::size_t>(open.back())].name) +
                  "> is closed: the file is truncated or damaged");
  return h;
}

// ---- Checking the header against the file ----

std::uint64_t parseCount(const std::optional<std::string>& value, const std::string& key, std::uint64_t max) {
  const std::string v = value.value_or("");
  if (v.empty() || v.find_first_not_of("0123456789") != std::string::npos)
    throw Problem(key + " = \"" + printable(v) + "\" is not a whole number >= 0");
  std::uint64_t n = 0;
  for (char c : v) {
    n = n * 10 + static_cast<std::uint64_t>(c - '0');
    if (n > max)
      throw Problem(key + " = " + printable(v) + " is out of range: at most " + std::to_string(max) +
                    " are allowed");
  }
  return n;
}

// Bytes per value of a VTK XML type name; 0 if not a numeric type.
std::uint64_t typeSize(const std::string& type) {
  static const std::map<std::string, std::uint64_t> sizes{
      {"Int8", 1},  {"UInt8", 1},  {"Int16", 2},   {"UInt16", 2},  {"Int32", 4},
      {"UInt32", 4}, {"Int64", 8}, {"UInt64", 8}, {"Float32", 4}, {"Float64", 8}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

bool isFloatType(const std::string& type) { return type == "Float32" || type == "Float64"; }

struct File {
  std::ifstream in;
  std::uint64_t size = 0;
  bool bigEndian = false;
  std::uint64_t wordBytes = 4;  // header_type UInt32 or UInt64
  std::string compressor;       // "" for none

  std::vector<unsigned char> bytes(std::uint64_t pos, std::uint64_t count) {
    std::vector<unsigned char> raw(static_cast<std::size_t>(count));
    in.clear();
    in.seekg(static_cast<std::streamoff>(pos));
    in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(raw.size()));
    if (!in) throw Problem("cannot be read at byte " + std::to_string(pos));
    return raw;
  }
  // An unsigned integer of `n` bytes in the file's byte order.
  std::uint64_t decode(const unsigned char* p, std::uint64_t n) const {
    std::uint64_t v = 0;
    for (std::uint64_t b = 0; b < n; ++b) v |= static_cast<std::uint64_t>(p[b]) << (8 * (bigEndian ? n - 1 - b : b));
    return v;
  }
};

// Stored binary data as VTK lays them out: raw bytes in the file from `at`,
// or base64 text from `at` (appended with encoding = "base64", or inline
// format = "binary"), read up to `end` (the file's end, or the end of an
// inline element's text). Offsets below count decoded bytes.
struct Stream {
  std::uint64_t at = 0, end = 0;
  bool base64 = false;
  std::string what;  // "array \"velocity\"", for messages

  // Decoded bytes the stream can hold at most.
  std::uint64_t room() const { return base64 ? (end - at) / 4 * 3 : end - at; }
  Problem truncated(const File& f) const {
    return Problem(what + " runs past the end of " + (end < f.size ? "its element" : "the file (" + std::to_string(f.size) + " bytes)") +
                   ": the file is truncated or damaged");
  }
  // Decoded bytes [from, from + count); base64 is decoded by VTK in whole
  // groups of 4 characters (3 bytes).
  std::vector<unsigned char> read(File& f, std::uint64_t from, std::uint64_t count) const {
    if (count > room() || from > room() - count) throw truncated(f);
    if (count == 0) return {};
    if (!base64) return f.bytes(at + from, count);
    const std::uint64_t first = from / 3, last = (from + count + 2) / 3;
    const auto text = f.bytes(at + 4 * first, 4 * (last - first));
    std::vector<unsigned char> out(static_cast<std::size_t>(3 * (last - first)));
    if (vtkBase64Utilities::DecodeSafely(text.data(), text.size(), out.data(), out.size()) < from + count - 3 * first)
      throw Problem(what + " is not valid base64 text (a damaged file?)");
    out.erase(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(from - 3 * first));
    out.resize(static_cast<std::size_t>(count));
    return out;
  }
  std::vector<std::uint64_t> words(File& f, std::uint64_t from, std::uint64_t count) const {
    if (count > room() / f.wordBytes) throw truncated(f);
    const auto raw = read(f, from, count * f.wordBytes);
    std::vector<std::uint64_t> out(static_cast<std::size_t>(count));
    for (std::size_t w = 0; w < out.size(); ++w) out[w] = f.decode(raw.data() + w * f.wordBytes, f.wordBytes);
    return out;
  }
};

// Where an array's data lie: `bytes` of data, from `dataFrom` in `data`;
// when compressed, blocks of `blockSize` bytes (the last one `lastSize`)
// stored in `compressed[i]` bytes each.
struct Stored {
  Stream data;
  std::uint64_t dataFrom = 0, bytes = 0, blockSize = 0, lastSize = 0;
  std::vector<std::uint64_t> compressed;
};

// The block header at the start of `s`, after checking that it and the
// (compressed) blocks lie inside the stream. Uncompressed: one word (the
// size) and the data, in one stream. Compressed: the words (blocks, block
// size, last block size, each block's compressed size), then the blocks;
// base64 encodes the two as separate streams.
Stored stored(File& f, const Stream& s) {
  const std::uint64_t w = f.wordBytes;
  Stored st;
  st.data = s;
  if (f.compressor.empty()) {
    st.bytes = s.words(f, 0, 1)[0];
    st.dataFrom = w;
    if (st.bytes > s.room() - w) throw s.truncated(f);
    return st;
  }
  const auto head = s.words(f, 0, 3);
  const std::uint64_t blocks = head[0];
  st.blockSize = head[1];
  if (blocks > s.room() / w - 3) throw s.truncated(f);
  st.compressed = s.words(f, 3 * w, blocks);
  st.dataFrom = (3 + blocks) * w;
  if (s.base64) {
    st.data.at += (st.dataFrom + 2) / 3 * 4;
    st.dataFrom = 0;
    if (st.data.at > st.data.end) throw s.truncated(f);
  }
  std::uint64_t left = st.data.room() - st.dataFrom;
  for (std::uint64_t size : st.compressed) {
    if (size > left) throw s.truncated(f);
    left -= size;
  }
  if (blocks == 0) return st;
  if (st.blockSize == 0 || head[2] > st.blockSize)
    throw Problem(s.what + " has a damaged compression header (block size " + std::to_string(st.blockSize) +
                  ", last block " + std::to_string(head[2]) + ")");
  st.lastSize = head[2] > 0 ? head[2] : st.blockSize;
  if (blocks - 1 > (std::numeric_limits<std::uint64_t>::max() - st.lastSize) / st.blockSize)
    throw Problem(s.what + " has a damaged compression header (" + std::to_string(blocks) + " blocks)");
  st.bytes = (blocks - 1) * st.blockSize + st.lastSize;
  return st;
}

// The last value of an array of unsigned integers of `size` bytes (as
// stored; a signed negative value reads as a huge one).
std::uint64_t lastValue(File& f, const Stored& s, std::uint64_t size) {
  const std::string& what = s.data.what;
  if (s.bytes < size) throw Problem(what + " is empty");
  if (f.compressor.empty()) return f.decode(s.data.read(f, s.dataFrom + s.bytes - size, size).data(), size);
  if (s.blockSize % size != 0)
    throw Problem(what + " has a damaged compression header (block size " + std::to_string(s.blockSize) + ")");
  const std::size_t last = s.compressed.size() - 1;
  std::uint64_t at = s.dataFrom;
  for (std::size_t b = 0; b < last; ++b) at += s.compressed[b];
  const auto packed = s.data.read(f, at, s.compressed[last]);
  std::vector<unsigned char> block(static_cast<std::size_t>(s.lastSize));
  vtkSmartPointer<vtkDataCompressor> c;
  if (f.compressor == "vtkZLibDataCompressor") c = vtkSmartPointer<vtkZLibDataCompressor>::New();
  else if (f.compressor == "vtkLZ4DataCompressor") c = vtkSmartPointer<vtkLZ4DataCompressor>::New();
  else c = vtkSmartPointer<vtkLZMADataCompressor>::New();
  if (c->Uncompress(packed.data(), packed.size(), block.data(), block.size()) != block.size())
    throw Problem(what + ": its data cannot be uncompressed (a damaged file?)");
  return f.decode(block.data() + block.size() - size, size);
}

// ASCII data (format = "ascii"): the values are the words of the element's
// text, which VTK parses itself; here they are counted, and the last one
// read when it is a cell offset.
std::uint64_t countWords(const std::string& text, std::size_t begin, std::size_t end) {
  std::uint64_t n = 0;
  for (std::size_t i = begin; i < end; ++i)
    if (!isSpace(text[i]) && (i == begin || isSpace(text[i - 1]))) ++n;
  return n;
}
std::uint64_t lastWord(const std::string& text, std::size_t begin, std::size_t end, const std::string& what) {
  std::size_t from = end;
  while (from > begin && !isSpace(text[from - 1])) --from;
  if (from == end) throw Problem(what + " is empty");
  return parseCount(text.substr(from, end - from), what + ": its last value", std::numeric_limits<std::uint64_t>::max() / 10);
}

struct Layout {
  std::uint64_t points = 0;
  bool velocity = false, mass = false, id = false, time = false;
  // The arrays a resume reads besides (the state an integrator carries).
  bool acceleration = false, density = false, densityRate = false, xsph = false, kind = false, step = false;
  bool colour = false, velocityPrevious = false, densityPrevious = false, listBuildPosition = false;
};

const Element* onlyChild(const Header& h, const Element& parent, const std::string& name, bool required,
                         const std::string& where) {
  const Element* found = nullptr;
  for (int c : parent.children) {
    const Element& e = h.elements[static_cast<std::size_t>(c)];
    if (e.name != name) continue;
    if (found) throw Problem(where + " has more than one <" + name + "> (sph reads files with one)");
    found = &e;
  }
  if (!found && required) throw Problem(where + " has no <" + name + "> element");
  return found;
}

// Everything that can be checked before VTK reads the file.
// allowEmpty: a piece of a .pvtp may hold no particles (a rank with none).
Layout checkLayout(const std::string& path, bool allowEmpty) {
  File f;
  std::error_code ec;
  f.size = std::filesystem::file_size(path, ec);
  if (ec) throw Problem("cannot be read: " + ec.message());
  if (f.size == 0) throw Problem("is empty");
  f.in.open(path, std::ios::binary);
  if (!f.in) throw Problem("cannot be opened");
  // The XML: up to <AppendedData>, else (data inline) the whole file.
  std::string text(static_cast<std::size_t>(std::min(f.size, kMaxHeaderBytes)), '\0');
  f.in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (!f.in) throw Problem("cannot be read");
  if (text.size() < f.size && text.find("<AppendedData") == std::string::npos) {
    text.resize(static_cast<std::size_t>(f.size));
    f.in.read(text.data() + kMaxHeaderBytes, static_cast<std::streamsize>(f.size - kMaxHeaderBytes));
    if (!f.in) throw Problem("cannot be read");
  }

  const Header h = parseHeader(text);
  if (h.elements.empty() || h.elements[0].name != "VTKFile")
    throw Problem("is not a VTK XML file (it has no <VTKFile> element)");
  const Element& root = h.elements[0];
  const std::string type = root.attribute("type").value_or("");
  if (type != "PolyData")
    throw Problem("is a VTK file of type \"" + printable(type) + "\": sph reads PolyData (.vtp) files");
  const std::string order = root.attribute("byte_order").value_or("LittleEndian");
  if (order != "LittleEndian" && order != "BigEndian")
    throw Problem("byte_order = \"" + printable(order) + "\": it must be LittleEndian or BigEndian");
  f.bigEndian = order == "BigEndian";
  const std::string headerType = root.attribute("header_type").value_or("UInt32");
  if (headerType != "UInt32" && headerType != "UInt64")
    throw Problem("header_type = \"" + printable(headerType) + "\": it must be UInt32 or UInt64");
  f.wordBytes = headerType == "UInt64" ? 8 : 4;
  const std::string compressor = root.attribute("compressor").value_or("");
  if (!compressor.empty() && compressor != "vtkZLibDataCompressor" && compressor != "vtkLZ4DataCompressor" &&
      compressor != "vtkLZMADataCompressor")
    throw Problem("compressor = \"" + printable(compressor) +
                  "\": it must be vtkZLibDataCompressor, vtkLZ4DataCompressor, vtkLZMADataCompressor or none");
  f.compressor = compressor;

  const Element& poly = *onlyChild(h, root, "PolyData", true, "<VTKFile>");
  const Element& piece = *onlyChild(h, poly, "Piece", true, "<PolyData>");
  Layout L;
  L.points = parseCount(piece.attribute("NumberOfPoints"), "NumberOfPoints", kMaxCount);
  if (L.points == 0 && !allowEmpty) throw Problem("holds no particles (NumberOfPoints = 0)");
  const Element* points = onlyChild(h, piece, "Points", false, "<Piece>");
  if (!points) throw Problem("has no <Points> element: it holds no particle positions");
  if (points->children.size() != 1 || h.elements[static_cast<std::size_t>(points->children[0])].name != "DataArray")
    throw Problem("its <Points> element must hold exactly one DataArray");
  std::map<std::string, std::uint64_t> cells;
  std::uint64_t allCells = 0;
  for (const char* kind : {"Verts", "Lines", "Strips", "Polys"}) {
    const std::string key = std::string("NumberOf") + kind;
    cells[kind] = piece.attribute(key) ? parseCount(piece.attribute(key), key, kMaxCount) : 0;
    allCells += cells[kind];
  }

  struct CellArrays {
    std::function<std::uint64_t()> lastOffset;
    std::optional<std::uint64_t> connectivity;  // values
  };
  std::map<std::string, CellArrays> cellArrays;

  // Every DataArray: type, components, where its data are, and their size.
  for (const Element& e : h.elements) {
    if (e.name == "Array") throw Problem("holds an <Array> element (string data), which sph does not read");
    if (e.name != "DataArray") continue;
    const std::string name = e.attribute("Name").value_or("");
    const std::string what = "array \"" + printable(name) + "\"";
    const std::string arrayType = e.attribute("type").value_or("");
    const std::uint64_t bytes = typeSize(arrayType);
    if (bytes == 0)
      throw Problem(what + " has type \"" + printable(arrayType) +
                    "\": it must be Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32 or Float64");
    const std::uint64_t components =
        e.attribute("NumberOfComponents") ? parseCount(e.attribute("NumberOfComponents"), what + ": NumberOfComponents", kMaxComponents) : 1;
    if (components == 0) throw Problem(what + ": NumberOfComponents = 0: it must be 1 to " + std::to_string(kMaxComponents));
    // How many values are stored, and for binary data where.
    const std::string format = e.attribute("format").value_or("");
    std::optional<Stored> data;
    std::uint64_t values = 0;
    if (format == "ascii") {
      values = countWords(text, e.textBegin, e.textEnd);
    } else if (format == "binary") {
      data = stored(f, Stream{e.textBegin, e.textEnd, true, what});
    } else if (format == "appended") {
      if (!h.hasAppendedData) throw Problem(what + " has format = appended, but the file has no <AppendedData>");
      if (h.appendedEncoding != "raw" && h.appendedEncoding != "base64")
        throw Problem("its <AppendedData> has encoding = \"" + printable(h.appendedEncoding) + "\": it must be raw or base64");
      const std::uint64_t offset = parseCount(e.attribute("offset"), what + ": offset", f.size);
      const Stream s{h.appendedStart + offset, f.size, h.appendedEncoding == "base64", what};
      if (s.at > s.end) throw s.truncated(f);
      data = stored(f, s);
    } else {
      throw Problem(what + " has format = \"" + printable(format) + "\": it must be ascii, binary or appended");
    }
    if (data) {
      if (data->bytes % bytes != 0) throw Problem(what + " holds " + std::to_string(data->bytes) + " bytes, not whole values");
      values = data->bytes / bytes;
    }

    // What the counts in the header say the array must hold.
    const std::string parent = e.parent >= 0 ? h.elements[static_cast<std::size_t>(e.parent)].name : "";
    std::optional<std::uint64_t> tuples;
    std::string because;
    if (parent == "Points" || parent == "PointData") {
      tuples = L.points;
      because = "NumberOfPoints = " + std::to_string(L.points);
    } else if (parent == "CellData") {
      tuples = allCells;
      because = "the number of cells, " + std::to_string(allCells) + ",";
    } else if (parent == "FieldData") {
      tuples = parseCount(e.attribute("NumberOfTuples"), what + ": NumberOfTuples", kMaxCount);
      because = "NumberOfTuples = " + std::to_string(*tuples);
    } else if (cells.count(parent) && name == "offsets") {
      tuples = cells[parent];
      because = "NumberOf" + parent + " = " + std::to_string(*tuples);
    }
    if (tuples && values != *tuples * components)
      throw Problem(what + " holds " + std::to_string(values) + " values, but " + because + " with " +
                    std::to_string(components) + " components needs " + std::to_string(*tuples * components) +
                    " (a damaged file?)");

    // The arrays sph uses.
    auto require = [&](bool ok, const std::string& allowed) {
      if (!ok)
        throw Problem(what + " has type " + arrayType + " and " + std::to_string(components) +
                      " component(s): it must have " + allowed);
    };
    if (parent == "Points") require(isFloatType(arrayType) && components == 3, "type Float32 or Float64 and 3 components");
    if (parent == "PointData") {
      const std::pair<const char*, bool*> known[] = {
          {"velocity", &L.velocity},       {"mass", &L.mass},        {"id", &L.id},
          {"acceleration", &L.acceleration}, {"density", &L.density}, {"density_rate", &L.densityRate},
          {"xsph_velocity", &L.xsph},      {"kind", &L.kind},       {"colour", &L.colour},
          {"velocity_previous", &L.velocityPrevious}, {"density_previous", &L.densityPrevious},
          {"list_build_position", &L.listBuildPosition}};
      for (const auto& [known_name, seen] : known) {
        if (name != known_name) continue;
        if (*seen) throw Problem("has two point arrays named \"" + name + "\"");
        *seen = true;
      }
      if (name == "velocity" || name == "acceleration" || name == "xsph_velocity" || name == "velocity_previous" ||
          name == "list_build_position")
        require(isFloatType(arrayType) && components == 3, "type Float32 or Float64 and 3 components");
      if (name == "mass" || name == "density" || name == "density_rate" || name == "colour" ||
          name == "density_previous")
        require(isFloatType(arrayType) && components == 1, "type Float32 or Float64 and 1 component");
      if (name == "id" || name == "kind") require(!isFloatType(arrayType) && components == 1, "an integer type and 1 component");
    }
    if (parent == "FieldData" && name == "TimeValue") {
      require(components == 1 && *tuples >= 1, "1 component and at least 1 tuple");
      L.time = true;
    }
    if (parent == "FieldData" && name == "step") {
      require(!isFloatType(arrayType) && components == 1 && *tuples >= 1, "an integer type, 1 component, 1 tuple");
      L.step = true;
    }
    if (cells.count(parent) && (name == "offsets" || name == "connectivity")) {
      require(!isFloatType(arrayType) && components == 1, "an integer type and 1 component");
      auto& c = cellArrays[parent];
      if (name != "offsets") c.connectivity = values;
      else if (data) c.lastOffset = [&f, stored = *data, bytes] { return lastValue(f, stored, bytes); };
      else c.lastOffset = [&text, &e, what] { return lastWord(text, e.textBegin, e.textEnd, what); };
    }
  }

  // VTK sizes a cell connectivity array by the last cell offset, as stored:
  // that must not exceed what the connectivity array holds.
  for (const auto& [kind, count] : cells) {
    const CellArrays& c = cellArrays[kind];
    if (count == 0 || !c.lastOffset || !c.connectivity) continue;  // VTK reports missing arrays
    const std::string what = "the cell offsets of <" + kind + ">";
    const std::uint64_t last = c.lastOffset();
    if (last > *c.connectivity)
      throw Problem(what + " end at " + std::to_string(last) + ", but its connectivity holds " +
                    std::to_string(*c.connectivity) + " values (a damaged file?)");
  }
  return L;
}

// ---- Reading with VTK, its messages captured ----

// Swallows VTK's messages and keeps the first error.
class CapturingOutputWindow : public vtkOutputWindow {
 public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow)
  void DisplayText(const char*) override {}
  void DisplayErrorText(const char* text) override {
    if (firstError.empty() && text) firstError = text;
  }
  void DisplayWarningText(const char*) override {}
  void DisplayGenericWarningText(const char*) override {}
  void DisplayDebugText(const char*) override {}
  std::string firstError;
};
vtkStandardNewMacro(CapturingOutputWindow);

// While alive, VTK prints nothing (neither its output window nor vtkLogger).
class QuietVtk {
 public:
  QuietVtk() : previous_(vtkOutputWindow::GetInstance()), verbosity_(vtkLogger::GetCurrentVerbosityCutoff()) {
    vtkOutputWindow::SetInstance(window_);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~QuietVtk() {
    vtkOutputWindow::SetInstance(previous_);
    vtkLogger::SetStderrVerbosity(verbosity_);
  }
  QuietVtk(const QuietVtk&) = delete;
  QuietVtk& operator=(const QuietVtk&) = delete;

  // Throws the first error VTK reported, if any, as one line.
  void check() const {
    std::string text = window_->firstError;
    if (text.empty()) return;
    // "ERROR: In file, line N\nClass (0x...): message\n\n": keep the message.
    if (text.rfind("ERROR: In ", 0) == 0 && text.find('\n') != std::string::npos) text = text.substr(text.find('\n') + 1);
    text = text.substr(0, text.find('\n'));
    if (const auto colon = text.find("): "); colon != std::string::npos) text = text.substr(colon + 3);
    std::string line;
    for (char c : text.substr(0, 200)) line += (c >= 0x20 && c < 0x7f) ? c : ' ';
    throw Problem("VTK cannot read it: " + line);
  }

 private:
  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkNew<CapturingOutputWindow> window_;
  vtkLogger::Verbosity verbosity_;
};

VtpParticles readChecked(const std::string& path, bool allowEmpty = false) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Problem("does not exist or is not a file");
  QuietVtk quiet;
  const Layout L = checkLayout(path, allowEmpty);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  quiet.check();
  vtkDataArraySelection* arrays = reader->GetPointDataArraySelection();
  arrays->DisableAllArrays();
  for (const char* name : {"velocity", "mass", "id", "acceleration", "density", "density_rate", "xsph_velocity", "kind",
                           "colour", "velocity_previous", "density_previous", "list_build_position"})
    arrays->EnableArray(name);
  reader->GetCellDataArraySelection()->DisableAllArrays();
  reader->Update();
  quiet.check();

  vtkPolyData* poly = reader->GetOutput();
  const vtkIdType n = poly && poly->GetPoints() ? poly->GetNumberOfPoints() : 0;
  if (static_cast<std::uint64_t>(n) != L.points)
    throw Problem("VTK read " + std::to_string(n) + " points from it, but NumberOfPoints = " + std::to_string(L.points));
  const auto count = static_cast<std::size_t>(n);
  vtkPointData* pd = poly->GetPointData();
  auto pointArray = [&](const char* name, int components) {
    vtkDataArray* a = pd->GetArray(name);
    if (!a || a->GetNumberOfTuples() != n || a->GetNumberOfComponents() != components)
      throw Problem("VTK did not read its point array \"" + std::string(name) + "\" in full");
    return a;
  };
  auto finite = [](const std::array<Real, 3>& v) {
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
  };

  VtpParticles out;
  out.x.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    poly->GetPoint(static_cast<vtkIdType>(i), out.x[i].data());
    if (!finite(out.x[i])) throw Problem("particle " + std::to_string(i) + " has a position that is not finite");
  }
  if (L.velocity) {
    vtkDataArray* v = pointArray("velocity", 3);
    out.hasVelocity = true;
    out.v.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      v->GetTuple(static_cast<vtkIdType>(i), out.v[i].data());
      if (!finite(out.v[i])) throw Problem("particle " + std::to_string(i) + " has a velocity that is not finite");
    }
  }
  if (L.mass) {
    vtkDataArray* m = pointArray("mass", 1);
    out.m.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      out.m[i] = m->GetTuple1(static_cast<vtkIdType>(i));
      if (!(std::isfinite(out.m[i]) && out.m[i] > 0))
        throw Problem("particle " + std::to_string(i) + " has mass " + significant(out.m[i]) +
                      ": masses must be finite and > 0");
    }
  }
  if (L.id) {
    vtkDataArray* id = pointArray("id", 1);
    out.id.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      bool valid = false;
      out.id[i] = id->GetVariantValue(static_cast<vtkIdType>(i)).ToTypeInt64(&valid);
      if (!valid) throw Problem("particle " + std::to_string(i) + " has an id that is not a 64-bit integer");
    }
    std::vector<std::int64_t> sorted = out.id;
    std::sort(sorted.begin(), sorted.end());
    if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
      throw Problem("id " + std::to_string(*twice) + " appears more than once: ids must be unique");
  }
  auto readVectors = [&](bool present, const char* name, std::vector<std::array<Real, 3>>& to) {
    if (!present) return;
    vtkDataArray* a = pointArray(name, 3);
    to.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      a->GetTuple(static_cast<vtkIdType>(i), to[i].data());
      if (!finite(to[i])) throw Problem("particle " + std::to_string(i) + " has " + name + " that is not finite");
    }
  };
  auto readScalars = [&](bool present, const char* name, std::vector<Real>& to) {
    if (!present) return;
    vtkDataArray* a = pointArray(name, 1);
    to.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      to[i] = a->GetTuple1(static_cast<vtkIdType>(i));
      if (!std::isfinite(to[i])) throw Problem("particle " + std::to_string(i) + " has " + name + " that is not finite");
    }
  };
  readVectors(L.acceleration, "acceleration", out.a);
  readVectors(L.xsph, "xsph_velocity", out.vXsph);
  readScalars(L.density, "density", out.rho);
  readScalars(L.densityRate, "density_rate", out.drho);
  readScalars(L.colour, "colour", out.colour);
  readVectors(L.velocityPrevious, "velocity_previous", out.vPrev);
  readScalars(L.densityPrevious, "density_previous", out.rhoPrev);
  readVectors(L.listBuildPosition, "list_build_position", out.xList);
  if (L.kind) {
    vtkDataArray* k = pointArray("kind", 1);
    out.kind.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const double value = k->GetTuple1(static_cast<vtkIdType>(i));
      if (value != 0 && value != 1) throw Problem("particle " + std::to_string(i) + " has kind " + significant(value) + ": it must be 0 (fluid) or 1 (wall)");
      out.kind[i] = static_cast<std::uint8_t>(value);
    }
  }
  if (L.step) {
    vtkDataArray* st = poly->GetFieldData()->GetArray("step");
    if (!st || st->GetNumberOfTuples() < 1) throw Problem("VTK did not read its step");
    const double value = st->GetTuple1(0);
    if (!(value >= 0 && value <= 1e15)) throw Problem("step = " + significant(value) + ": it must be >= 0");
    out.step = static_cast<long>(value);
  }
  if (L.time) {
    vtkDataArray* t = poly->GetFieldData()->GetArray("TimeValue");
    if (!t || t->GetNumberOfTuples() < 1) throw Problem("VTK did not read its TimeValue");
    out.time = t->GetTuple1(0);
    if (!(std::isfinite(out.time) && out.time >= 0))
      throw Problem("TimeValue = " + significant(out.time) + ": it must be finite and >= 0");
  }
  return out;
}

// ---- A parallel snapshot (.pvtp): its pieces, appended ----

// The pieces' particles in the order the summary lists them (the ranks'
// order), each piece read and checked as a .vtp (it may be empty). The
// pieces must agree: the same arrays, TimeValue and step; ids unique across
// all of them. VTK's own reader would append them too, but reads a missing
// or damaged piece as no points with only a log message.
VtpParticles readPvtpChecked(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Problem("does not exist or is not a file");
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) throw Problem("cannot be read: " + ec.message());
  if (size > kMaxHeaderBytes) throw Problem("is larger than a .pvtp summary can be (" + std::to_string(size) + " bytes)");
  std::ifstream in(path, std::ios::binary);
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (!in) throw Problem("cannot be read");
  const Header h = parseHeader(text);
  if (h.elements.empty() || h.elements[0].name != "VTKFile")
    throw Problem("is not a VTK XML file (it has no <VTKFile> element)");
  const std::string type = h.elements[0].attribute("type").value_or("");
  if (type != "PPolyData")
    throw Problem("is a VTK file of type \"" + printable(type) + "\": a .pvtp must be PPolyData");
  const Element& poly = *onlyChild(h, h.elements[0], "PPolyData", true, "<VTKFile>");
  std::vector<std::string> sources;
  for (int c : poly.children) {
    const Element& e = h.elements[static_cast<std::size_t>(c)];
    if (e.name != "Piece") continue;
    const std::string source = e.attribute("Source").value_or("");
    if (source.empty()) throw Problem("piece " + std::to_string(sources.size()) + " has no Source file");
    sources.push_back(source);
  }
  if (sources.empty()) throw Problem("lists no <Piece>");

  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  VtpParticles all;
  std::string first;  // the first piece with particles: the others must match it
  for (const std::string& source : sources) {
    VtpParticles p;
    const std::filesystem::path file = folder / source;  // an absolute Source stays as it is
    try {
      p = readChecked(file.string(), /*allowEmpty=*/true);
    } catch (const Problem& e) {
      throw Problem("its piece " + file.string() + ": " + e.what());
    }
    if (p.x.empty()) continue;
    const std::string piece = "its piece " + file.string();
    if (first.empty()) {
      first = file.string();
      all.time = p.time;
      all.step = p.step;
      all.hasVelocity = p.hasVelocity;
    } else if (p.time != all.time || p.step != all.step) {
      throw Problem(piece + " is of time " + significant(p.time) + ", step " + std::to_string(p.step) + ", but " +
                    first + " of time " + significant(all.time) + ", step " + std::to_string(all.step));
    }
    const std::size_t before = all.x.size();
    auto append = [&](auto& to, const auto& from, const char* name) {
      if (before > 0 && to.empty() != from.empty())
        throw Problem(piece + (from.empty() ? " lacks" : " has") + " the array \"" + name + "\", but " + first +
                      (from.empty() ? " has it" : " does not"));
      to.insert(to.end(), from.begin(), from.end());
    };
    append(all.x, p.x, "Points");
    append(all.v, p.v, "velocity");
    append(all.m, p.m, "mass");
    append(all.id, p.id, "id");
    append(all.a, p.a, "acceleration");
    append(all.vXsph, p.vXsph, "xsph_velocity");
    append(all.rho, p.rho, "density");
    append(all.drho, p.drho, "density_rate");
    // A piece without walls may lack "kind" (a rank's particles allocate it
    // only when they include walls): its particles are fluid (kind 0).
    if (!all.kind.empty() || !p.kind.empty()) {
      all.kind.resize(before, 0);
      if (p.kind.empty()) p.kind.assign(p.x.size(), 0);
    }
    append(all.kind, p.kind, "kind");
    append(all.colour, p.colour, "colour");
    append(all.vPrev, p.vPrev, "velocity_previous");
    append(all.rhoPrev, p.rhoPrev, "density_previous");
    append(all.xList, p.xList, "list_build_position");
  }
  if (all.x.empty()) throw Problem("holds no particles (all its pieces are empty)");
  std::vector<std::int64_t> sorted = all.id;
  std::sort(sorted.begin(), sorted.end());
  if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
    throw Problem("id " + std::to_string(*twice) + " appears in more than one of its pieces: ids must be unique");
  return all;
}

}  // namespace

VtpParticles readVtp(const std::string& path) {
  try {
    if (std::filesystem::path(path).extension() == ".pvtp") return readPvtpChecked(path);
    return readChecked(path);
  } catch (const Problem& e) {
    throw std::runtime_error(path + ": " + e.what());
  } catch (const std::bad_alloc&) {
    throw std::runtime_error(path + ": not enough memory to read it");
  } catch (const std::exception& e) {  // anything else VTK or the library throws
    throw std::runtime_error(path + " cannot be read: " + e.what());
  }
}

}  // namespace sph
