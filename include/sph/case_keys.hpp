// The table of case keys: one row per key of a case file (each also a flag
// of `sph run`), with its topic, the CaseConfig field it sets, its unit, help
// text, allowed range and, for choices, the method table it picks from.
// src/main.cpp declares the CLI11 options from it, --help prints it grouped
// by topic, and validateCase() checks the ranges it states. CLI11-free.
//
// Units in 2D are per unit depth: a 2D density is kg/m^2, a 2D pressure N/m.
#pragma once

#include "sph/case_config.hpp"

#include <limits>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace sph {

enum class KeyGroup { kScene, kPhysics, kNumerics, kOutput };

const char* groupName(KeyGroup g);

// Allowed values of a number (and of each number of a list): lo ... hi, each
// end open or closed; an infinite end is no bound.
struct KeyRange {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  bool loOpen = false, hiOpen = false;
  bool integer = false;
  std::string text() const;  // "> 0", "0 to 1", "1 to 1024", ...
  bool contains(double x) const;
};

// Ranges by their ends (case_keys.cpp and the method parameters of
// methods.hpp): open and closed ends, integers.
namespace key_range {
constexpr double kInf = std::numeric_limits<double>::infinity();
inline KeyRange above(double lo, double hi = kInf) { return {lo, hi, true, false, false}; }
inline KeyRange within(double lo, double hi) { return {lo, hi, false, false, false}; }
inline KeyRange count(double lo, double hi) { return {lo, hi, false, false, true}; }
// Coordinates and lengths: large enough for any scene, small enough that
// every product the program forms stays finite.
inline KeyRange coordinate() { return within(-1e9, 1e9); }
}  // namespace key_range

// A key an optional term declares (terms/optional_terms.hpp): its value is
// in CaseConfig::termKeys under the key's name, `initial` when not set.
template <class T>
struct TermKey {
  const char* name;
  T initial;
};

using KeyField = std::variant<Real CaseConfig::*, long CaseConfig::*, int CaseConfig::*, bool CaseConfig::*,
                              std::string CaseConfig::*, std::vector<Real> CaseConfig::*,
                              std::vector<long> CaseConfig::*, TermKey<Real>, TermKey<long>>;

// The value a key field holds in c (a CaseConfig member, or a term's key),
// and a reference to it to set (a term's key is then stored in c.termKeys).
template <class T>
const T& keyValue(const CaseConfig& c, T CaseConfig::*member) {
  return c.*member;
}
template <class T>
T& keyRef(CaseConfig& c, T CaseConfig::*member) {
  return c.*member;
}
inline const std::map<std::string, Real>& termKeyMap(const CaseConfig& c, Real) { return c.termKeys.reals; }
inline const std::map<std::string, long>& termKeyMap(const CaseConfig& c, long) { return c.termKeys.counts; }
inline std::map<std::string, Real>& termKeyMap(CaseConfig& c, Real) { return c.termKeys.reals; }
inline std::map<std::string, long>& termKeyMap(CaseConfig& c, long) { return c.termKeys.counts; }
template <class T>
T keyValue(const CaseConfig& c, TermKey<T> key) {
  const auto& map = termKeyMap(c, T{});
  const auto at = map.find(key.name);
  return at == map.end() ? key.initial : at->second;
}
template <class T>
T& keyRef(CaseConfig& c, TermKey<T> key) {
  return termKeyMap(c, T{}).try_emplace(key.name, key.initial).first->second;
}

struct KeySpec {
  const char* name;           // the key, and the flag --name
  KeyGroup group;
  KeyField field;
  const char* unit;           // "" when none
  const char* help;
  KeyRange range;             // numbers only
  const char* defaultText;    // the default when it is not the field's initial value, else nullptr
  std::vector<std::string> (*choices)();  // allowed names, nullptr for free text
};

const std::vector<KeySpec>& caseKeys();
const KeySpec* findKey(const std::string& name);

// A row of the key table for a key an optional term declares (its value
// in CaseConfig::termKeys), and the value of such a key in c.
template <class T>
KeySpec termKey(const char* name, KeyGroup group, const char* unit, const char* help, KeyRange range, T initial) {
  return {name, group, TermKey<T>{name, initial}, unit, help, range, nullptr, nullptr};
}
Real termReal(const CaseConfig& c, const std::string& name);
long termCount(const CaseConfig& c, const std::string& name);

// The help line of a key: "help [unit; range; default]" and its choices.
std::string keyHelp(const KeySpec& k);

// Throws CaseError if a given value is outside its key's range or choices.
void checkKeyRanges(const CaseConfig& c);

// The value of key k in c as case-file text ("0.01", "[0, 0]", "\"tait\""),
// "" for an empty list or text (nothing given).
std::string keyValueText(const CaseConfig& c, const KeySpec& k);

// Keys that say how to run, not what (resume, overwrite, catalyst,
// catalyst_every): not part of a resolved case, and a resume may give them.
bool isRunOnlyKey(const KeySpec& k);

// Run-only keys a case file may not hold (catalyst, catalyst_every): an
// in-situ pipeline is how one run is looked at, not part of the case, so a
// case file and its resolved run.case repeat the run without ParaView.
bool isCommandLineOnlyKey(const std::string& name);

// Keys a resumed run may set anew (end_time, output_every, output_interval,
// threads, progress): the rest would change the run it continues.
bool isResumeKey(const std::string& name);
std::string resumeKeysText();  // "end_time, output_every, ... and progress", for messages

// A case file holding every key with its value in c, by topic.
std::string resolvedCaseText(const ResolvedCase& c);

// The key reference, docs/keys.md (src/key_reference.cpp): every key as
// Markdown tables by topic, with unit, default, allowed values and help.
std::string keyReferenceMarkdown();

}  // namespace sph
