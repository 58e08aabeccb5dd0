#include "common/config.h"

#include <gtest/gtest.h>

#include <functional>

#include "common/error.h"

namespace granasym {
namespace {

std::string MessageOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(ConfigTable, ReadsTypedValuesWithDefaults) {
  const ConfigTable root =
      ConfigTable::ParseString("a = 2\nb = 1.5\n[t]\nname = 'x'\nflag = true\n", "test.toml");
  EXPECT_DOUBLE_EQ(root.GetDouble("a", Range::Positive()), 2.0);
  EXPECT_EQ(root.GetInt("a"), 2);
  EXPECT_DOUBLE_EQ(root.GetDouble("b"), 1.5);
  EXPECT_DOUBLE_EQ(root.GetDouble("missing", 7.0, Range::Any()), 7.0);
  const ConfigTable t = root.GetTable("t");
  EXPECT_EQ(t.GetString("name"), "x");
  EXPECT_TRUE(t.GetBool("flag"));
  EXPECT_NO_THROW(root.CheckNoUnknownKeys());
}

TEST(ConfigTable, OutOfRangeNamesFileKeyValueAndRange) {
  const ConfigTable root = ConfigTable::ParseString("[m]\nmodulus = -5\n", "scene.toml");
  const std::string message =
      MessageOf([&] { root.GetTable("m").GetDouble("modulus", Range::Positive()); });
  EXPECT_NE(message.find("scene.toml"), std::string::npos) << message;
  EXPECT_NE(message.find("m.modulus"), std::string::npos) << message;
  EXPECT_NE(message.find("-5"), std::string::npos) << message;
  EXPECT_NE(message.find("> 0"), std::string::npos) << message;
}

TEST(ConfigTable, InfinityAndNanAreNeverValidNumbers) {
  const ConfigTable root =
      ConfigTable::ParseString("a = inf\nb = -inf\nc = nan\nlist = [1.0, inf]\n", "scene.toml");
  for (const char* key : {"a", "b", "c"}) {
    // Even where any number is valid, and where inf satisfies "> 0".
    for (const Range range : {Range::Any(), Range::Positive()}) {
      const std::string message = MessageOf([&] { root.GetDouble(key, range); });
      EXPECT_NE(message.find(std::string("key '") + key + "'"), std::string::npos) << message;
      EXPECT_NE(message.find("is not a finite number"), std::string::npos) << message;
    }
  }
  const std::string message = MessageOf([&] { root.GetDoubles("list", Range::Positive()); });
  EXPECT_NE(message.find("list[1]"), std::string::npos) << message;
  EXPECT_NE(message.find("is not a finite number"), std::string::npos) << message;
}

TEST(ConfigTable, UnknownKeyIsReportedWithTheValidOnes) {
  const ConfigTable root = ConfigTable::ParseString("[m]\nyoung = 5\n", "scene.toml");
  root.GetTable("m").GetDouble("modulus", 1.0, Range::Positive());
  const std::string message = MessageOf([&] { root.CheckNoUnknownKeys(); });
  EXPECT_NE(message.find("m.young"), std::string::npos) << message;
  EXPECT_NE(message.find("modulus"), std::string::npos) << message;
}

TEST(ConfigTable, WrongTypeAndBadChoiceAreRejected) {
  const ConfigTable root = ConfigTable::ParseString("a = 'text'\nmode = 'sideways'\n", "f.toml");
  EXPECT_NE(MessageOf([&] { root.GetDouble("a"); }).find("expected a number"), std::string::npos);
  const std::string message = MessageOf([&] { root.GetChoice("mode", {"up", "down"}, "up"); });
  EXPECT_NE(message.find("'up', 'down'"), std::string::npos) << message;
}

TEST(ConfigTable, SyntaxErrorIsAnInputError) {
  EXPECT_THROW(ConfigTable::ParseString("a = = 1\n", "bad.toml"), InputError);
}

TEST(ConfigTable, TableArraysCarryTheirIndexInKeyNames) {
  const ConfigTable root =
      ConfigTable::ParseString("[[stage]]\nx = 1\n[[stage]]\nx = -1\n", "s.toml");
  const auto stages = root.GetTableArray("stage");
  ASSERT_EQ(stages.size(), 2u);
  const std::string message = MessageOf([&] { stages[1].GetDouble("x", Range::Positive()); });
  EXPECT_NE(message.find("stage[1].x"), std::string::npos) << message;
}

}  // namespace
}  // namespace granasym
