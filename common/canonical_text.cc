#include "common/canonical_text.h"

#include <fmt/format.h>

#include "common/error.h"

namespace granasym {

void CanonicalText::Put(const std::string& key, std::string value) {
  const bool inserted = lines_.emplace(key, std::move(value)).second;
  GRANASYM_CHECK(inserted) << "canonical key '" << key << "' given twice";
}

void CanonicalText::Add(const std::string& key, double value) {
  Put(key, fmt::format("{:.17g}", value));
}

void CanonicalText::Add(const std::string& key, int64_t value) {
  Put(key, fmt::format("{}", value));
}

void CanonicalText::Add(const std::string& key, bool value) { Put(key, value ? "true" : "false"); }

void CanonicalText::Add(const std::string& key, const std::string& value) {
  std::string quoted = "\"";
  for (char c : value) {
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  Put(key, quoted + "\"");
}

std::string CanonicalText::Text() const {
  std::string text;
  for (const auto& [key, value] : lines_) text += key + " = " + value + "\n";
  return text;
}

}  // namespace granasym
