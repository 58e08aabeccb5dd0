// Test helper: an enumeration's name table spells exactly the given names.
// The expected list is written out in the test on purpose, so that renaming a
// value (which files, HDF5 attributes and scripts depend on) fails a test.
#pragma once

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/enum_names.h"

namespace granasym {

// Every (value, name) pair round-trips through ToString and FromString, and
// the table holds exactly these pairs in this order.
template <typename E>
void ExpectSpellings(const std::vector<std::pair<E, std::string>>& expected) {
  std::vector<E> values;
  for (const auto& [value, name] : expected) {
    EXPECT_EQ(ToString(value), name);
    const std::optional<E> parsed = FromString<E>(name);
    ASSERT_TRUE(parsed.has_value()) << name;
    EXPECT_EQ(*parsed, value) << name;
    values.push_back(value);
  }
  EXPECT_EQ(EnumValues<E>(), values) << "the table of " << AllowedNames<E>();
}

}  // namespace granasym
