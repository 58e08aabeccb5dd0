#include "common/key_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <map>

#include "common/error.h"

namespace granasym {

KeySpec NumberKey(std::string table, std::string key, KeyType type, std::string unit, Range range,
                  std::string fallback, std::string meaning, std::string when) {
  return {std::move(table),    std::move(key),     type,           std::move(unit), range, "",
          std::move(fallback), std::move(meaning), std::move(when)};
}

KeySpec OtherKey(std::string table, std::string key, KeyType type, std::string valid,
                 std::string fallback, std::string meaning, std::string when) {
  return {
      std::move(table),    std::move(key),     type,           "", Range::Any(), std::move(valid),
      std::move(fallback), std::move(meaning), std::move(when)};
}
namespace {

const char* TypeText(KeyType type) {
  switch (type) {
    case KeyType::kNumber:
      return "number";
    case KeyType::kInteger:
      return "integer";
    case KeyType::kBool:
      return "boolean";
    case KeyType::kString:
      return "string";
    case KeyType::kNumbers:
      return "array of numbers";
    case KeyType::kStrings:
      return "string or array of strings";
    case KeyType::kTable:
      return "table";
    case KeyType::kTables:
      return "array of tables";
  }
  return "value";
}

// Whether `pattern` (with "*" for any one name) matches `table`, both
// dotted paths in their "[]" form.
bool Matches(const std::string& pattern, const std::string& table) {
  if (pattern == table) return true;
  if (pattern.find('*') == std::string::npos) return false;
  size_t p = 0, t = 0;
  while (p < pattern.size() && t < table.size()) {
    if (pattern[p] == '*') {
      while (t < table.size() && table[t] != '.') ++t;
      ++p;
      continue;
    }
    if (pattern[p] != table[t]) return false;
    ++p, ++t;
  }
  return p == pattern.size() && t == table.size();
}

std::string MarkdownCell(std::string text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

// The table's name as a TOML header: "[sample.generate]", "[[stage]]",
// "[stage.stop]" (a table of each [[stage]]).
std::string Header(const std::string& table) {
  if (table.empty()) return "(top level)";
  const bool array = table.size() > 2 && table.compare(table.size() - 2, 2, "[]") == 0;
  std::string name;
  for (size_t k = 0; k < table.size(); ++k) {
    if (table.compare(k, 2, "[]") == 0) {
      ++k;
      continue;
    }
    name += table[k];
  }
  return array ? "[[" + name + "]]" : "[" + name + "]";
}

std::string Meaning(const KeySpec& spec) {
  return spec.when.empty() ? spec.meaning : spec.meaning + " (where " + spec.when + ")";
}

}  // namespace

KeyTable::KeyTable(std::string kind, std::string description, std::vector<KeySpec> keys)
    : kind_(std::move(kind)), description_(std::move(description)), keys_(std::move(keys)) {
  for (const KeySpec& spec : keys_) {
    GRANASYM_CHECK(!spec.key.empty() && !spec.meaning.empty() && !spec.fallback.empty())
        << kind_ << " key table: '" << SpecName(spec) << "' lacks its name, meaning or default";
  }
}

std::vector<const KeySpec*> KeyTable::Find(const std::string& table_path,
                                           const std::string& key) const {
  const std::string pattern = TablePattern(table_path);
  std::vector<const KeySpec*> found;
  for (const KeySpec& spec : keys_) {
    if (spec.key == key && Matches(spec.table, pattern)) found.push_back(&spec);
  }
  return found;
}

void KeyTable::MarkConsulted(const KeySpec* spec) const {
  std::lock_guard<std::mutex> lock(mutex_);
  consulted_.insert(spec);
}

std::vector<std::string> KeyTable::Unconsulted() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::string> names;
  for (const KeySpec& spec : keys_) {
    if (!consulted_.count(&spec)) {
      names.push_back(SpecName(spec) + (spec.when.empty() ? "" : " (" + spec.when + ")"));
    }
  }
  return names;
}

void KeyTable::ResetConsulted() const {
  std::lock_guard<std::mutex> lock(mutex_);
  consulted_.clear();
}

std::string KeyTable::Render(KeyFormat format) const {
  // The tables in the order of their first key.
  std::vector<std::string> tables;
  std::map<std::string, std::vector<const KeySpec*>> by_table;
  for (const KeySpec& spec : keys_) {
    if (!by_table.count(spec.table)) tables.push_back(spec.table);
    by_table[spec.table].push_back(&spec);
  }
  std::string out;
  if (format == KeyFormat::kMarkdown) {
    out += fmt::format("# Keys: {}\n\n{}\n", kind_, description_);
    for (const std::string& table : tables) {
      out += fmt::format("\n## {}\n\n", Header(table));
      out += "| key | type | unit | valid | default | meaning |\n";
      out += "|---|---|---|---|---|---|\n";
      for (const KeySpec* spec : by_table[table]) {
        out += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", spec->key, TypeText(spec->type),
                           spec->unit.empty() ? "-" : MarkdownCell(spec->unit),
                           MarkdownCell(ValidText(*spec)), MarkdownCell(spec->fallback),
                           MarkdownCell(Meaning(*spec)));
      }
    }
    return out;
  }
  out += fmt::format("{} keys: {}\n", kind_, description_);
  for (const std::string& table : tables) {
    out += fmt::format("\n{}\n", Header(table));
    for (const KeySpec* spec : by_table[table]) {
      std::string line = "  " + spec->key + ": " + TypeText(spec->type);
      if (!spec->unit.empty()) line += " (" + spec->unit + ")";
      const std::string valid = ValidText(*spec);
      if (!valid.empty()) line += ", " + valid;
      line += "; default " + spec->fallback;
      out += line + "\n      " + Meaning(*spec) + "\n";
    }
  }
  return out;
}

std::string ValidText(const KeySpec& spec) {
  if (spec.type == KeyType::kNumber || spec.type == KeyType::kInteger ||
      spec.type == KeyType::kNumbers) {
    const std::string range = spec.range.Describe();
    if (!spec.valid.empty()) return range.empty() ? spec.valid : range + ", " + spec.valid;
    return range;
  }
  return spec.valid;
}

std::string TablePattern(const std::string& table_path) {
  std::string pattern;
  for (size_t k = 0; k < table_path.size(); ++k) {
    if (table_path[k] == '[') {
      size_t end = k + 1;
      while (end < table_path.size() && std::isdigit(static_cast<unsigned char>(table_path[end])))
        ++end;
      if (end < table_path.size() && table_path[end] == ']' && end > k + 1) {
        pattern += "[]";
        k = end;
        continue;
      }
    }
    pattern += table_path[k];
  }
  return pattern;
}

std::string SpecName(const KeySpec& spec) {
  return spec.table.empty() ? spec.key : spec.table + "." + spec.key;
}

}  // namespace granasym
