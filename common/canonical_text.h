// The canonical text of a parsed, defaulted configuration: one `key = value`
// line per setting, keys sorted, numbers with 17 significant digits, so that
// two inputs that mean the same run (whitespace, comments, key order, values
// left to their defaults or given explicitly) have the same text and hash.
// Result files carry its hash in /provenance; a study cache keys on it.
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace granasym {

class CanonicalText {
 public:
  // `key` is a dotted path, e.g. "stage[1].stop.mean_stress_kpa". A key
  // given twice is a programming error.
  void Add(const std::string& key, double value);
  void Add(const std::string& key, int64_t value);
  void Add(const std::string& key, int value) { Add(key, static_cast<int64_t>(value)); }
  void Add(const std::string& key, bool value);
  void Add(const std::string& key, const std::string& value);
  void Add(const std::string& key, const char* value) { Add(key, std::string(value)); }

  // All lines in key order, each ending in '\n'.
  std::string Text() const;

 private:
  void Put(const std::string& key, std::string value);
  std::map<std::string, std::string> lines_;
};

}  // namespace granasym
