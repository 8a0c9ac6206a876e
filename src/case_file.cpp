// The strict case-file reader (see include/sph/case_file.hpp): one pass over
// the text with a cursor, so its time is linear in the file's length; every
// refusal names the line and, where there is one, the key.
#include "sph/case_file.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <istream>
#include <unordered_map>

namespace sph {
namespace {

bool isControl(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u < 0x20 || u == 0x7f;
}

bool isKeyChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
}

// Characters of a bare value (numbers, true, false): anything printable but
// blanks and the characters that mean something else here.
bool isBareChar(char c) {
  return !isControl(c) && c != ' ' && std::strchr("#,[]\"'=", c) == nullptr;
}

class Parser {
 public:
  explicit Parser(std::string_view text) : t_(text) {}

  std::vector<CaseEntry> entries() {
    std::vector<CaseEntry> out;
    std::unordered_map<std::string, std::size_t> seen;  // key -> line
    if (t_.substr(0, 3) == "\xEF\xBB\xBF") i_ = lineStart_ = 3;  // UTF-8 byte-order mark
    while (!atEnd()) {
      skipSpaces();
      if (atLineEnd()) {  // blank line or comment
        endLine("");
        continue;
      }
      CaseEntry e;
      e.line = line_;
      const std::size_t start = i_;
      while (!atEnd() && isKeyChar(t_[i_])) ++i_;
      e.key = std::string(t_.substr(start, i_ - start));
      skipSpaces();
      if (e.key.empty() || atEnd() || t_[i_] != '=') {
        if (!atEnd() && t_[i_] == '\0') failHere("");
        fail("expected 'key = value' (a key is letters, digits, '_' and '-'), found '" + currentLine() + "'");
      }
      ++i_;
      skipSpaces();
      if (atLineEnd()) fail("key '" + e.key + "' has no value");
      if (t_[i_] == '[')
        readArray(e);
      else
        e.values.push_back(readScalar(e.key));
      const auto [it, isNew] = seen.emplace(e.key, e.line);
      if (!isNew)
        throw CaseFileError(e.line, "key '" + e.key + "' is given twice (lines " + std::to_string(it->second) + " and " +
             std::to_string(e.line) + "): give each key once");
      endLine("after the value of '" + e.key + "'");
      out.push_back(std::move(e));
    }
    return out;
  }

 private:
  bool atEnd() const { return i_ >= t_.size(); }
  bool atNewline() const {
    return !atEnd() && (t_[i_] == '\n' || (t_[i_] == '\r' && i_ + 1 < t_.size() && t_[i_ + 1] == '\n'));
  }
  bool atLineEnd() const { return atEnd() || atNewline() || t_[i_] == '#'; }

  [[noreturn]] void fail(const std::string& what) const { throw CaseFileError(line_, what); }

  // Fails on the character at the cursor: as binary content if it is a
  // control character, else with `what`.
  [[noreturn]] void failHere(const std::string& what) const {
    if (t_[i_] == '\0') fail("not a case file: it holds a NUL byte (binary content)");
    if (isControl(t_[i_]))
      fail("control character " + escapeControl(t_.substr(i_, 1)) + " in '" + currentLine() +
           "': case files are text");
    fail(what);
  }

  // The current line from its start, up to 40 characters, escaped.
  std::string currentLine() const {
    std::string_view rest = t_.substr(lineStart_);
    rest = rest.substr(0, std::min({rest.find('\n'), rest.find("\r\n"), std::size_t{40}}));
    return escapeControl(rest);
  }

  // Up to 20 characters from the cursor, within the line, escaped.
  std::string here() const {
    std::string_view rest = t_.substr(i_, 20);
    return escapeControl(rest.substr(0, rest.find_first_of("\r\n")));
  }

  void skipSpaces() {
    while (!atEnd() && (t_[i_] == ' ' || t_[i_] == '\t')) ++i_;
  }

  void skipComment() {
    if (atEnd() || t_[i_] != '#') return;
    for (; !atEnd() && !atNewline(); ++i_)
      if (isControl(t_[i_]) && t_[i_] != '\t') failHere("");
  }

  void consumeNewline() {
    i_ += t_[i_] == '\r' ? 2 : 1;
    ++line_;
    lineStart_ = i_;
  }

  // Spaces, an optional comment, then the end of the line (or of the text).
  void endLine(const std::string& context) {
    skipSpaces();
    skipComment();
    if (atEnd()) return;
    if (!atNewline())
      failHere("unexpected '" + here() + "' " + context +
               ": quote strings (\"...\") and put lists in [ ]");
    consumeNewline();
  }

  // Blanks, comments and newlines, inside an array.
  void skipBlank() {
    for (;;) {
      skipSpaces();
      skipComment();
      if (!atNewline()) return;
      consumeNewline();
    }
  }

  std::string readScalar(const std::string& key) {
    const char quote = t_[i_];
    if (quote == '"' || quote == '\'') return readString(key, quote);
    const std::size_t start = i_;
    while (!atEnd() && isBareChar(t_[i_])) ++i_;
    if (i_ == start) failHere("expected a value for '" + key + "', found '" + here() + "'");
    return std::string(t_.substr(start, i_ - start));
  }

  // "..." with the escapes \" and \\, or '...' taken as it is.
  std::string readString(const std::string& key, char quote) {
    std::string s;
    ++i_;
    for (;;) {
      if (atEnd() || atNewline())
        fail("unterminated string in the value of '" + key + "': it needs a closing " + quote + " on the same line");
      const char c = t_[i_];
      if (c == quote) {
        ++i_;
        return s;
      }
      if (isControl(c) && c != '\t') failHere("");
      if (c == '\\' && quote == '"') {
        ++i_;
        if (atEnd() || (t_[i_] != '"' && t_[i_] != '\\'))
          fail("unknown escape in the string value of '" + key + "': only \\\" and \\\\ are allowed (or use '...')");
      }
      s += t_[i_++];
    }
  }

  void readArray(CaseEntry& e) {
    e.array = true;
    const std::size_t open = line_;
    auto unterminated = [&] {
      throw CaseFileError(open, "unterminated array: the '[' of '" + e.key + "' has no ']'");
    };
    ++i_;
    for (;;) {
      skipBlank();
      if (atEnd()) unterminated();
      if (t_[i_] == ']') break;
      if (t_[i_] == '[') fail("the array of '" + e.key + "' holds an array: arrays hold numbers or strings");
      e.values.push_back(readScalar(e.key));
      skipBlank();
      if (atEnd()) unterminated();
      if (t_[i_] == ']') break;
      if (t_[i_] != ',')
        failHere("the array of '" + e.key + "' (line " + std::to_string(open) +
                 ") needs ',' between values and ']' at its end, found '" +
                 here() + "'");
      ++i_;
    }
    ++i_;  // the ']'
  }

  std::string_view t_;
  std::size_t i_ = 0;
  std::size_t line_ = 1;
  std::size_t lineStart_ = 0;
};

char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

std::string lowerCase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), lower);
  return s;
}

}  // namespace

std::vector<CaseEntry> parseCaseText(std::string_view text) { return Parser(text).entries(); }

std::vector<CaseEntry> readCaseFile(std::istream& in, std::size_t maxBytes) {
  std::string text;
  std::vector<char> buf(std::size_t{1} << 16);
  while (in.read(buf.data(), static_cast<std::streamsize>(buf.size())) || in.gcount() > 0) {
    const auto n = static_cast<std::size_t>(in.gcount());
    if (const void* nul = std::memchr(buf.data(), 0, n)) {
      const auto at = static_cast<std::size_t>(static_cast<const char*>(nul) - buf.data());
      const auto line = 1 + std::count(text.begin(), text.end(), '\n') + std::count(buf.data(), buf.data() + at, '\n');
      throw CaseFileError(static_cast<std::size_t>(line), "not a case file: it holds a NUL byte (binary content)");
    }
    if (text.size() + n > maxBytes)
      throw CaseFileError(0, "not a case file: it is larger than " +
                                 (maxBytes >= (1u << 20) ? std::to_string(maxBytes >> 20) + " MB"
                                                         : std::to_string(maxBytes) + " bytes"));
    text.append(buf.data(), n);
  }
  if (in.bad()) throw CaseFileError(0, "cannot be read");
  return parseCaseText(text);
}

std::string escapeControl(std::string_view s) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    if (!isControl(c)) {
      out += c;
      continue;
    }
    const auto u = static_cast<unsigned char>(c);
    out += "\\x";
    out += hex[u >> 4];
    out += hex[u & 15];
  }
  return out;
}

std::size_t editDistance(std::string_view a, std::string_view b) {
  // Rows i-2, i-1 and i of the (|a|+1) x (|b|+1) table.
  std::vector<std::size_t> before(b.size() + 1), prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        cur[j] = std::min(cur[j], before[j - 2] + 1);
    }
    std::swap(before, prev);
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::optional<std::string> closestKey(const std::string& key, const std::vector<std::string>& known) {
  const std::string k = lowerCase(key);
  const std::size_t limit = std::max<std::size_t>(2, k.size() / 3);
  std::optional<std::string> best;
  std::size_t bestDistance = limit + 1;
  for (const auto& candidate : known) {
    const std::size_t gap = candidate.size() > k.size() ? candidate.size() - k.size() : k.size() - candidate.size();
    if (gap >= bestDistance) continue;  // the distance is at least the length difference
    const std::size_t d = editDistance(k, lowerCase(candidate));
    if (d < bestDistance && d < k.size()) {
      best = candidate;
      bestDistance = d;
    }
  }
  return best;
}

std::string unknownKeyMessage(const std::string& key, const std::string& where,
                              const std::vector<std::string>& known) {
  std::string msg = "unknown key '" + escapeControl(key) + "' (" + where + ")";
  if (const auto guess = closestKey(key, known)) msg += "; did you mean '" + *guess + "'?";
  return msg + " ('sph run --help' lists the keys)";
}

std::string defaultRunName(const std::string& caseFile) {
  std::string name = std::filesystem::path(caseFile).stem().string();
  for (char& c : name)
    if (!isKeyChar(c) && c != '.') c = '_';
  return name.empty() ? "sph" : name;
}

}  // namespace sph
