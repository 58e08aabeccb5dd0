// The values a hostile or careless user writes for a number, and the check
// of the outcome that the table-driven tests of every input kind share: a
// value is either valid for its key and accepted, or rejected with a message
// naming the file, the key and the value.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace granasym::testing {

// TOML literal and how messages spell it.
inline const std::vector<std::pair<std::string, std::string>>& HostileNumbers() {
  static const std::vector<std::pair<std::string, std::string>> values = {
      {"nan", "nan"}, {"inf", "inf"},      {"-inf", "-inf"},     {"0", "0"},
      {"-1", "-1"},   {"1e308", "1e+308"}, {"1e-300", "1e-300"},
  };
  return values;
}

// `message` is the InputError's text ("" when the input was accepted).
inline void ExpectOutcome(const std::string& what, bool valid, const std::string& message,
                          const std::string& file, const std::string& key,
                          const std::string& spelling) {
  if (valid) {
    EXPECT_EQ(message, "") << what << " is valid but was rejected";
    return;
  }
  ASSERT_FALSE(message.empty()) << what << " was accepted";
  EXPECT_NE(message.find(file), std::string::npos) << what << ": no file name in: " << message;
  EXPECT_NE(message.find(key), std::string::npos)
      << what << ": the message names another key: " << message;
  EXPECT_NE(message.find(spelling), std::string::npos)
      << what << ": the message lacks the value: " << message;
}

}  // namespace granasym::testing
