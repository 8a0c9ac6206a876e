// Case files: a strict reader of the TOML subset the cases use, without CLI11.
// CLI11's own reader accepts too much (a key given twice, binary files) and too
// little (byte-order marks, CRLF), and is quadratic in the length of an array;
// src/main.cpp hands CLI11 what this reader returns. Also here, because they
// are plain string work worth unit-testing: the "did you mean" suggestion for
// unknown keys, the escaping of control characters in messages, and the run
// name a case file gets by default.
//
// The subset: `key = value` lines, blank lines and `#` comments (also after a
// value). A key is letters, digits, '_' and '-'. A value is a bare word (a
// number, true, false), a string "..." (escapes \" and \\) or '...' (no
// escapes), or an array [a, b, ...] of those, which may span lines. An UTF-8
// byte-order mark and CRLF line ends are accepted.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

// One `key = value` of a case file: a scalar has one value, an array any
// number; strings are unquoted and unescaped.
struct CaseEntry {
  std::size_t line = 0;  // 1-based line of the key
  std::string key;
  std::vector<std::string> values;
  bool array = false;
};

// A case file that cannot be read. line() is the 1-based line the problem is
// on, or 0 when it is about the whole file; what() does not name the file.
class CaseFileError : public std::runtime_error {
 public:
  CaseFileError(std::size_t line, const std::string& what) : std::runtime_error(what), line_(line) {}
  std::size_t line() const { return line_; }

 private:
  std::size_t line_;
};

// Case files are small; anything larger is not one (and /dev/zero ends).
constexpr std::size_t kMaxCaseFileBytes = std::size_t{64} << 20;

// The entries of a case file's text, in file order, in one pass (linear in
// the text's length). Throws CaseFileError on anything outside the subset,
// on a key given twice (naming both lines) and on NUL or control bytes.
std::vector<CaseEntry> parseCaseText(std::string_view text);

// Reads at most maxBytes from `in` (stopping at the first NUL byte) and
// parses it. Throws CaseFileError for binary content, a larger input or a
// read error.
std::vector<CaseEntry> readCaseFile(std::istream& in, std::size_t maxBytes = kMaxCaseFileBytes);

// `s` with ASCII control characters (and DEL) written as \xHH, so that a
// message never sends raw control bytes to a terminal and stays one line.
std::string escapeControl(std::string_view s);

// Damerau-Levenshtein distance (optimal string alignment: insertions,
// deletions, substitutions and swaps of adjacent characters each cost 1).
std::size_t editDistance(std::string_view a, std::string_view b);

// The known key closest to `key` (ASCII case ignored) if it is close enough
// to be a typo: distance <= max(2, length / 3) and less than the length of
// `key`. Ties go to the first in `known`.
std::optional<std::string> closestKey(const std::string& key, const std::vector<std::string>& known);

// "unknown key 'KEY' (WHERE); did you mean 'K'? ('sph run --help' lists the
// keys)", without the suggestion when no key is close.
std::string unknownKeyMessage(const std::string& key, const std::string& where,
                              const std::vector<std::string>& known);

// The run name of a case file when --name is not given: the file name
// without its extension, with characters other than letters, digits, '_',
// '-' and '.' replaced by '_' ("my case.case" -> "my_case").
std::string defaultRunName(const std::string& caseFile);

}  // namespace sph
