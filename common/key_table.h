// The key tables of the input files: every key a parser reads, with its
// type, unit, valid values, default and meaning, one table per input kind
// (scene, stage, programme, calibration, figures). `granasym keys KIND`
// prints them; the parsers consult them: a ConfigTable parsed with its
// kind's tables (ConfigTable::ParseString/ParseFile) checks on every read
// that the key is in the table, that the range it validates with is the
// table's, and that its default is the table's (an InvariantError
// otherwise: a bug, caught by the tests that parse every key), so the
// printed tables cannot drift from what the parsers accept. A key that no
// reader asked for is refused naming the valid keys of its table.
#pragma once

#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/enum_names.h"

namespace granasym {

enum class KeyType { kNumber, kInteger, kBool, kString, kNumbers, kStrings, kTable, kTables };
enum class KeyFormat { kText, kMarkdown };

}  // namespace granasym

template <>
struct granasym::EnumNames<granasym::KeyFormat> {
  static constexpr EnumEntry<KeyFormat> kEntries[] = {
      {KeyFormat::kText, "text", "aligned plain text for a terminal"},
      {KeyFormat::kMarkdown, "markdown", "Markdown tables, one per TOML table (for the docs)"},
  };
};

namespace granasym {

struct KeySpec {
  // The dotted path of the table that holds the key: "" for the top level,
  // "sample.generate", "stage[].stop" (an array of tables: "[]"), and "*"
  // for any one name ("parameters.*").
  std::string table;
  std::string key;
  KeyType type = KeyType::kNumber;
  std::string unit;      // "" for none (ratios, counts, names)
  Range range;           // numbers: what the parser accepts (Range::Any() for other types)
  std::string valid;     // other values: what is valid, e.g. "strain_path, triaxial or rest"
  std::string fallback;  // the default, as text; "required" or "none" (optional, no default)
  std::string meaning;
  std::string when;  // where the key applies, e.g. "type = triaxial"; "" everywhere
};

// A key of a number type (kNumber, kInteger, kNumbers): its unit and range.
KeySpec NumberKey(std::string table, std::string key, KeyType type, std::string unit, Range range,
                  std::string fallback, std::string meaning, std::string when = "");
// A key of any other type: what is valid, in words.
KeySpec OtherKey(std::string table, std::string key, KeyType type, std::string valid,
                 std::string fallback, std::string meaning, std::string when = "");

class KeyTable {
 public:
  KeyTable(std::string kind, std::string description, std::vector<KeySpec> keys);

  const std::string& kind() const { return kind_; }
  const std::string& description() const { return description_; }
  const std::vector<KeySpec>& keys() const { return keys_; }

  // The specs of `key` in the table at `table_path` (indices as in
  // ConfigTable::KeyName, e.g. "stage[2].stop"); empty when the table lacks it.
  std::vector<const KeySpec*> Find(const std::string& table_path, const std::string& key) const;
  // The keys that a parse consulted since the last ResetConsulted (tests:
  // every key of the table is read by some input).
  void MarkConsulted(const KeySpec* spec) const;
  std::vector<std::string> Unconsulted() const;  // "table.key" of the others
  void ResetConsulted() const;

  std::string Render(KeyFormat format) const;

 private:
  std::string kind_, description_;
  std::vector<KeySpec> keys_;
  mutable std::mutex mutex_;
  mutable std::set<const KeySpec*> consulted_;
};

// "[2, 2e+09]"-style text of a spec's values: its range, or `valid`.
std::string ValidText(const KeySpec& spec);
// "stage[2].stop" -> "stage[].stop".
std::string TablePattern(const std::string& table_path);
// A dotted "table.key" name of a spec ("key" at the top level).
std::string SpecName(const KeySpec& spec);

}  // namespace granasym
