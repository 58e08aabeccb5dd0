// Validated access to TOML configuration files (scene, model and calibration
// files). Every value read names its file and key in errors; keys that no
// reader asked for are reported as unknown with the valid keys of their table.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/enum_names.h"

namespace toml {
template <typename, template <typename...> class, template <typename...> class>
class basic_value;
}

namespace granasym {

class KeyTable;
struct KeySpec;

// Magnitudes beyond which no number of a configuration file is a setting
// (every number read is checked against them, whatever its key's range).
inline constexpr double kLargestSetting = 1e100;
inline constexpr double kSmallestSetting = 1e-100;

// An admissible interval for a number, with its own wording for messages.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_inclusive = true;
  bool max_inclusive = true;

  static Range Any() { return {}; }
  static Range Positive() { return {0.0, Range().max, false, true}; }
  static Range NonNegative() { return {0.0, Range().max, true, true}; }
  static Range Closed(double lo, double hi) { return {lo, hi, true, true}; }
  static Range Open(double lo, double hi) { return {lo, hi, false, false}; }
  static Range AtLeast(double lo) { return {lo, Range().max, true, true}; }
  bool Contains(double value) const;
  std::string Describe() const;  // e.g. "> 0", "in [0, 1]"; "" for any number
};

// Ranges shared by the DEM's scenes and the models' test files: stresses up
// to 10 GPa (grains crush long before), strain rates up to 1e6 1/s, and
// logarithmic strains of a stage up to 20 (the cell changes by e^20).
inline constexpr Range kStressKpa = {0.0, 1e7, false, true};
inline constexpr Range kStrainRate = {0.0, 1e6, false, true};
inline constexpr Range kStageStrain = {-20.0, 20.0, true, true};

class ConfigTable {
 public:
  // Parses a TOML file; a syntax error becomes an InputError naming the line.
  static ConfigTable ParseFile(const std::string& path);
  // Parses TOML text; `origin` names it in messages.
  static ConfigTable ParseString(const std::string& text, const std::string& origin);

  ConfigTable(const ConfigTable&);
  ConfigTable& operator=(const ConfigTable&);
  ~ConfigTable();

  bool Has(const std::string& key) const;
  // The keys of this table, sorted (none of them counts as asked for).
  std::vector<std::string> Keys() const;
  // Required values.
  double GetDouble(const std::string& key, Range range = Range::Any()) const;
  int64_t GetInt(const std::string& key, Range range = Range::Any()) const;
  bool GetBool(const std::string& key) const;
  std::string GetString(const std::string& key) const;
  // Optional values with defaults (the default is not range-checked).
  double GetDouble(const std::string& key, double fallback, Range range) const;
  int64_t GetInt(const std::string& key, int64_t fallback, Range range) const;
  bool GetBool(const std::string& key, bool fallback) const;
  std::string GetString(const std::string& key, const std::string& fallback) const;
  // A string that must be one of `allowed`. Prefer GetEnum: enumerations
  // carry their own name table (common/enum_names.h).
  std::string GetChoice(const std::string& key, const std::vector<std::string>& allowed,
                        const std::string& fallback) const;
  // A value of the enumeration E named as in its EnumNames table; an unknown
  // name fails with the file, key, value and the allowed names, e.g.
  //   f.toml: key 'integration.jacobian' = 'exakt' is not valid: expected exact or
  //   finite_difference
  // Required key:
  template <typename E>
  E GetEnum(const std::string& key) const;
  // Optional key with a default:
  template <typename E>
  E GetEnum(const std::string& key, E fallback) const;
  // Optional key where only `allowed` (a subset of the table) is valid here,
  // e.g. the model kinds that calibration can fit.
  template <typename E>
  E GetEnum(const std::string& key, E fallback, const std::vector<E>& allowed) const;
  std::vector<double> GetDoubles(const std::string& key, Range range = Range::Any()) const;
  // An array of strings; a single string counts as an array of one.
  std::vector<std::string> GetStrings(const std::string& key) const;

  ConfigTable GetTable(const std::string& key) const;
  std::vector<ConfigTable> GetTableArray(const std::string& key) const;

  // Throws InputError naming the first key of this table (and its subtables)
  // that no Get/Has call asked for.
  void CheckNoUnknownKeys() const;

  // Makes every later read of this document consult the key tables of its
  // input kind (common/key_table.h): a key read that they lack, or read with
  // another range or default than theirs, is an InvariantError (a parser
  // that drifted from its table). Called by a parser on the table it gets.
  void UseKeys(std::vector<const KeyTable*> tables) const;

  // Full dotted name of a key of this table, e.g. "stage[2].stop.mean_stress_kpa".
  std::string KeyName(const std::string& key) const;
  const std::string& origin() const { return *origin_; }
  // Raises an InputError about `key` of this table with the given explanation.
  [[noreturn]] void Fail(const std::string& key, const std::string& explanation) const;

 private:
  struct Document;
  ConfigTable(std::shared_ptr<Document> document, const void* table, std::string prefix);
  // The key's value (nullptr when absent); with key tables in use, `specs`
  // gets the key's entries (never empty: a key they lack is an InvariantError).
  const void* Find(const std::string& key, std::vector<const KeySpec*>* specs = nullptr) const;
  void CheckRange(const std::string& key, const std::vector<const KeySpec*>& specs,
                  const Range& range) const;
  void CheckDefault(const std::string& key, const std::vector<const KeySpec*>& specs,
                    const std::string& fallback, double number) const;
  void MarkKnown(const std::string& key) const;

  std::shared_ptr<Document> document_;
  const void* table_;  // toml::value of this table, owned by document_
  std::string prefix_;
  std::shared_ptr<const std::string> origin_;
};

template <typename E>
E ConfigTable::GetEnum(const std::string& key) const {
  if (!Has(key)) Fail(key, "is missing: expected " + AllowedNames<E>());
  return GetEnum(key, E{}, EnumValues<E>());
}

template <typename E>
E ConfigTable::GetEnum(const std::string& key, E fallback) const {
  return GetEnum(key, fallback, EnumValues<E>());
}

template <typename E>
E ConfigTable::GetEnum(const std::string& key, E fallback, const std::vector<E>& allowed) const {
  if (!Has(key)) return fallback;
  const std::string name = GetString(key);
  const std::optional<E> value = FromString<E>(name);
  if (value) {
    for (E candidate : allowed) {
      if (candidate == *value) return candidate;
    }
  }
  Fail(key, "= '" + name + "' is not valid: expected " + AllowedNames(allowed));
}

}  // namespace granasym
