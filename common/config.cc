#include "common/config.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <sstream>
#include <toml.hpp>

#include "common/error.h"
#include "common/key_table.h"

namespace granasym {

struct ConfigTable::Document {
  toml::value root;
  // Keys that a reader asked for, per table prefix.
  std::map<std::string, std::set<std::string>> known;
  // The key tables of the input kind (UseKeys); empty: none consulted.
  std::vector<const KeyTable*> key_tables;
};

namespace {
const toml::value& AsValue(const void* p) { return *static_cast<const toml::value*>(p); }

std::string FormatNumber(double value) {
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

// "a number > 0", or "a number" where any finite number is valid.
std::string ExpectedNumber(const Range& range) {
  const std::string bounds = range.Describe();
  return bounds.empty() ? "a number" : "a number " + bounds;
}

std::string TypeName(const toml::value& value) {
  std::ostringstream out;
  out << value.type();
  return out.str();
}
}  // namespace

bool Range::Contains(double value) const {
  if (std::isnan(value)) return false;
  const bool above = min_inclusive ? value >= min : value > min;
  const bool below = max_inclusive ? value <= max : value < max;
  return above && below;
}

std::string Range::Describe() const {
  const bool has_min = std::isfinite(min);
  const bool has_max = std::isfinite(max);
  if (has_min && has_max) {
    return std::string("in ") + (min_inclusive ? "[" : "(") + FormatNumber(min) + ", " +
           FormatNumber(max) + (max_inclusive ? "]" : ")");
  }
  if (has_min) return (min_inclusive ? ">= " : "> ") + FormatNumber(min);
  if (has_max) return (max_inclusive ? "<= " : "< ") + FormatNumber(max);
  return "";
}

ConfigTable::ConfigTable(std::shared_ptr<Document> document, const void* table, std::string prefix)
    : document_(std::move(document)), table_(table), prefix_(std::move(prefix)) {}

ConfigTable::ConfigTable(const ConfigTable&) = default;
ConfigTable& ConfigTable::operator=(const ConfigTable&) = default;
ConfigTable::~ConfigTable() = default;

ConfigTable ConfigTable::ParseFile(const std::string& path) {
  auto document = std::make_shared<Document>();
  try {
    document->root = toml::parse(path);
  } catch (const std::exception& error) {
    throw InputError("cannot read TOML file '" + path + "': " + error.what());
  }
  ConfigTable table(document, &document->root, "");
  table.origin_ = std::make_shared<const std::string>(path);
  return table;
}

ConfigTable ConfigTable::ParseString(const std::string& text, const std::string& origin) {
  auto document = std::make_shared<Document>();
  std::istringstream stream(text);
  try {
    document->root = toml::parse(stream, origin);
  } catch (const std::exception& error) {
    throw InputError("cannot parse TOML '" + origin + "': " + error.what());
  }
  ConfigTable table(document, &document->root, "");
  table.origin_ = std::make_shared<const std::string>(origin);
  return table;
}

std::string ConfigTable::KeyName(const std::string& key) const {
  if (key.empty()) return prefix_;  // the table itself
  return prefix_.empty() ? key : prefix_ + "." + key;
}

void ConfigTable::Fail(const std::string& key, const std::string& explanation) const {
  throw InputError(*origin_ + ": key '" + KeyName(key) + "' " + explanation);
}

void ConfigTable::MarkKnown(const std::string& key) const { document_->known[prefix_].insert(key); }

void ConfigTable::UseKeys(std::vector<const KeyTable*> tables) const {
  document_->key_tables = std::move(tables);
}

const void* ConfigTable::Find(const std::string& key, std::vector<const KeySpec*>* specs) const {
  MarkKnown(key);
  if (!document_->key_tables.empty()) {
    std::vector<const KeySpec*> found;
    std::string kinds;
    for (const KeyTable* table : document_->key_tables) {
      for (const KeySpec* spec : table->Find(prefix_, key)) {
        table->MarkConsulted(spec);
        found.push_back(spec);
      }
      kinds += (kinds.empty() ? "" : ", ") + table->kind();
    }
    GRANASYM_CHECK(!found.empty())
        << *origin_ << ": the parser reads key '" << KeyName(key) << "', which the key tables ("
        << kinds << ") lack: add it to its table (`granasym keys` prints them)";
    if (specs) *specs = std::move(found);
  }
  const toml::value& table = AsValue(table_);
  if (!table.is_table()) return nullptr;
  const auto& entries = table.as_table();
  const auto found = entries.find(key);
  return found == entries.end() ? nullptr : &found->second;
}

bool ConfigTable::Has(const std::string& key) const { return Find(key) != nullptr; }

void ConfigTable::CheckRange(const std::string& key, const std::vector<const KeySpec*>& specs,
                             const Range& range) const {
  // A read without a range only fetches the value for a message (e.g. the
  // other contact law's constant, refused with its own explanation).
  if (specs.empty() || range.Describe().empty()) return;
  std::string listed;
  for (const KeySpec* spec : specs) {
    if (spec->range.Describe() == range.Describe()) return;
    listed += (listed.empty() ? "'" : ", '") + spec->range.Describe() + "'";
  }
  GRANASYM_CHECK(false) << *origin_ << ": the parser checks key '" << KeyName(key)
                        << "' against the range '" << range.Describe()
                        << "', its key table against " << listed;
}

void ConfigTable::CheckDefault(const std::string& key, const std::vector<const KeySpec*>& specs,
                               const std::string& fallback, double number) const {
  bool any_stated = false;
  std::string listed;
  for (const KeySpec* spec : specs) {
    char* end = nullptr;
    const double stated = std::strtod(spec->fallback.c_str(), &end);
    const bool numeric = end && *end == '\0' && end != spec->fallback.c_str();
    if (numeric && std::isfinite(number)) {
      any_stated = true;
      if (std::abs(stated - number) <= 1e-9 * std::max(std::abs(stated), std::abs(number))) return;
    } else if (!numeric && (spec->fallback == "true" || spec->fallback == "false")) {
      any_stated = true;
      if (spec->fallback == fallback) return;
    } else {
      return;  // a default in words (e.g. "by path kind"): nothing to compare
    }
    listed += (listed.empty() ? "'" : ", '") + spec->fallback + "'";
  }
  GRANASYM_CHECK(!any_stated) << *origin_ << ": the parser's default of key '" << KeyName(key)
                              << "' is " << fallback << ", its key table's " << listed;
}

std::vector<std::string> ConfigTable::Keys() const {
  std::vector<std::string> keys;
  const toml::value& table = AsValue(table_);
  if (!table.is_table()) return keys;
  for (const auto& entry : table.as_table()) keys.push_back(entry.first);
  std::sort(keys.begin(), keys.end());
  return keys;
}

namespace {
// A number of the file; inf and nan (valid TOML) are never valid settings,
// whatever range the key has.
double NumberOf(const ConfigTable& table, const std::string& key, const toml::value& value,
                const Range& range) {
  double number = 0;
  if (value.is_floating()) {
    number = value.as_floating();
  } else if (value.is_integer()) {
    number = static_cast<double>(value.as_integer());
  } else {
    table.Fail(key, "has type " + TypeName(value) + ": expected a number");
  }
  if (!std::isfinite(number)) {
    table.Fail(key, "= " + FormatNumber(number) + " is not a finite number: expected " +
                        ExpectedNumber(range));
  }
  // No setting of granasym (in its units: mm, kPa, MPa, s, degrees, ratios)
  // is meaningful beyond these magnitudes; keys with a physical scale have
  // narrower ranges of their own.
  if (std::abs(number) > kLargestSetting || (number != 0 && std::abs(number) < kSmallestSetting)) {
    table.Fail(key, "= " + FormatNumber(number) + " is beyond any meaningful setting (magnitudes " +
                        FormatNumber(kSmallestSetting) + " to " + FormatNumber(kLargestSetting) +
                        "): expected " + ExpectedNumber(range));
  }
  return number;
}
}  // namespace

double ConfigTable::GetDouble(const std::string& key, Range range) const {
  std::vector<const KeySpec*> specs;
  const void* found = Find(key, &specs);
  CheckRange(key, specs, range);
  if (!found) Fail(key, "is missing: expected " + ExpectedNumber(range));
  const double value = NumberOf(*this, key, AsValue(found), range);
  if (!range.Contains(value)) {
    Fail(key, "= " + FormatNumber(value) + " is out of range: must be " + range.Describe());
  }
  return value;
}

double ConfigTable::GetDouble(const std::string& key, double fallback, Range range) const {
  std::vector<const KeySpec*> specs;
  const bool has = Find(key, &specs) != nullptr;
  CheckDefault(key, specs, FormatNumber(fallback), fallback);
  return has ? GetDouble(key, range) : fallback;
}

int64_t ConfigTable::GetInt(const std::string& key, Range range) const {
  std::vector<const KeySpec*> specs;
  const void* found = Find(key, &specs);
  CheckRange(key, specs, range);
  if (!found) {
    Fail(key, "is missing: expected an integer" +
                  (range.Describe().empty() ? "" : " " + range.Describe()));
  }
  const toml::value& value = AsValue(found);
  if (value.is_floating()) {
    Fail(key, "= " + FormatNumber(value.as_floating()) +
                  " is written as a floating-point number: expected an integer without a "
                  "decimal point or exponent (e.g. 1000, not 1e3 or 1000.0)" +
                  (range.Describe().empty() ? "" : ", " + range.Describe()));
  }
  if (!value.is_integer()) Fail(key, "has type " + TypeName(value) + ": expected an integer");
  const int64_t number = value.as_integer();
  if (!range.Contains(static_cast<double>(number))) {
    Fail(key, "= " + std::to_string(number) + " is out of range: must be " + range.Describe());
  }
  return number;
}

int64_t ConfigTable::GetInt(const std::string& key, int64_t fallback, Range range) const {
  std::vector<const KeySpec*> specs;
  const bool has = Find(key, &specs) != nullptr;
  CheckDefault(key, specs, std::to_string(fallback), static_cast<double>(fallback));
  return has ? GetInt(key, range) : fallback;
}

bool ConfigTable::GetBool(const std::string& key) const {
  const void* found = Find(key);
  if (!found) Fail(key, "is missing: expected true or false");
  const toml::value& value = AsValue(found);
  if (!value.is_boolean()) Fail(key, "has type " + TypeName(value) + ": expected true or false");
  return value.as_boolean();
}

bool ConfigTable::GetBool(const std::string& key, bool fallback) const {
  std::vector<const KeySpec*> specs;
  const bool has = Find(key, &specs) != nullptr;
  CheckDefault(key, specs, fallback ? "true" : "false", std::numeric_limits<double>::quiet_NaN());
  return has ? GetBool(key) : fallback;
}

std::string ConfigTable::GetString(const std::string& key) const {
  const void* found = Find(key);
  if (!found) Fail(key, "is missing: expected a string");
  const toml::value& value = AsValue(found);
  if (!value.is_string()) Fail(key, "has type " + TypeName(value) + ": expected a string");
  return value.as_string().str;
}

std::string ConfigTable::GetString(const std::string& key, const std::string& fallback) const {
  return Has(key) ? GetString(key) : fallback;
}

std::string ConfigTable::GetChoice(const std::string& key, const std::vector<std::string>& allowed,
                                   const std::string& fallback) const {
  const std::string value = GetString(key, fallback);
  for (const std::string& choice : allowed) {
    if (value == choice) return value;
  }
  std::string list;
  for (const std::string& choice : allowed)
    list += (list.empty() ? "" : ", ") + ("'" + choice + "'");
  Fail(key, "= '" + value + "' is not valid: expected one of " + list);
}

std::vector<double> ConfigTable::GetDoubles(const std::string& key, Range range) const {
  std::vector<const KeySpec*> specs;
  const void* found = Find(key, &specs);
  CheckRange(key, specs, range);
  if (!found) Fail(key, "is missing: expected an array of numbers");
  const toml::value& value = AsValue(found);
  if (!value.is_array())
    Fail(key, "has type " + TypeName(value) + ": expected an array of numbers");
  std::vector<double> numbers;
  for (size_t i = 0; i < value.as_array().size(); ++i) {
    const toml::value& item = value.as_array()[i];
    const std::string item_key = key + "[" + std::to_string(i) + "]";
    const double number = NumberOf(*this, item_key, item, range);
    if (!range.Contains(number)) {
      Fail(item_key, "= " + FormatNumber(number) + " is out of range: must be " + range.Describe());
    }
    numbers.push_back(number);
  }
  return numbers;
}

std::vector<std::string> ConfigTable::GetStrings(const std::string& key) const {
  const void* found = Find(key);
  if (!found) Fail(key, "is missing: expected a string or an array of strings");
  const toml::value& value = AsValue(found);
  if (value.is_string()) return {value.as_string().str};
  if (!value.is_array()) {
    Fail(key, "has type " + TypeName(value) + ": expected a string or an array of strings");
  }
  std::vector<std::string> strings;
  for (size_t i = 0; i < value.as_array().size(); ++i) {
    const toml::value& item = value.as_array()[i];
    if (!item.is_string()) {
      Fail(key + "[" + std::to_string(i) + "]",
           "has type " + TypeName(item) + ": expected a string");
    }
    strings.push_back(item.as_string().str);
  }
  return strings;
}

ConfigTable ConfigTable::GetTable(const std::string& key) const {
  const void* found = Find(key);
  if (!found) Fail(key, "is missing: expected a table");
  if (!AsValue(found).is_table()) {
    Fail(key, "has type " + TypeName(AsValue(found)) + ": expected a table");
  }
  ConfigTable child(document_, found, KeyName(key));
  child.origin_ = origin_;
  return child;
}

std::vector<ConfigTable> ConfigTable::GetTableArray(const std::string& key) const {
  const void* found = Find(key);
  std::vector<ConfigTable> tables;
  if (!found) return tables;
  const toml::value& value = AsValue(found);
  if (!value.is_array()) Fail(key, "has type " + TypeName(value) + ": expected an array of tables");
  for (size_t i = 0; i < value.as_array().size(); ++i) {
    const toml::value& item = value.as_array()[i];
    const std::string name = key + "[" + std::to_string(i) + "]";
    if (!item.is_table()) Fail(name, "has type " + TypeName(item) + ": expected a table");
    ConfigTable child(document_, &item, KeyName(name));
    child.origin_ = origin_;
    tables.push_back(child);
  }
  return tables;
}

void ConfigTable::CheckNoUnknownKeys() const {
  const toml::value& table = AsValue(table_);
  if (!table.is_table()) return;
  const std::set<std::string>& known = document_->known[prefix_];
  for (const auto& [key, value] : table.as_table()) {
    if (!known.count(key)) {
      std::string valid;
      for (const std::string& name : known) valid += (valid.empty() ? "" : ", ") + name;
      Fail(key, "is not a known key" + (valid.empty() ? std::string(" (this table takes no keys)")
                                                      : " (valid keys here: " + valid + ")"));
    }
    if (value.is_table()) {
      ConfigTable child(document_, &value, KeyName(key));
      child.origin_ = origin_;
      child.CheckNoUnknownKeys();
    } else if (value.is_array()) {
      for (size_t i = 0; i < value.as_array().size(); ++i) {
        const toml::value& item = value.as_array()[i];
        if (!item.is_table()) continue;
        ConfigTable child(document_, &item, KeyName(key + "[" + std::to_string(i) + "]"));
        child.origin_ = origin_;
        child.CheckNoUnknownKeys();
      }
    }
  }
}

}  // namespace granasym
