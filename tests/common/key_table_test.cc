#include "common/key_table.h"

#include <gtest/gtest.h>

#include <string>

#include "common/config.h"
#include "common/error.h"

namespace granasym {
namespace {

const KeyTable& TestKeys() {
  static const KeyTable table(
      "test", "a test file",
      {
          {"", "t", KeyType::kTable, "", Range::Any(), "", "required", "a table", ""},
          {"", "stage", KeyType::kTables, "", Range::Any(), "", "none", "stages", ""},
          {"", "p", KeyType::kTable, "", Range::Any(), "", "none", "parameters", ""},
          {"p", "a", KeyType::kTable, "", Range::Any(), "", "none", "parameter a", ""},
          {"t", "modulus", KeyType::kNumber, "MPa", Range::Positive(), "", "500", "a modulus", ""},
          {"t", "count", KeyType::kInteger, "", Range::Closed(1, 10), "", "3", "a count", ""},
          {"t", "flag", KeyType::kBool, "", Range::Any(), "true or false", "false", "a flag", ""},
          {"stage[]", "rate", KeyType::kNumber, "1/s", Range::Positive(), "", "required", "a rate",
           "type = a"},
          {"p.*", "value", KeyType::kNumber, "", Range::Closed(0, 1), "", "none",
           "any parameter's value", ""},
      });
  return table;
}

ConfigTable WithKeys(const std::string& text) {
  const ConfigTable root = ConfigTable::ParseString(text, "test.toml");
  root.UseKeys({&TestKeys()});
  return root;
}

TEST(KeyTable, PatternsReplaceIndicesAndMatchAnyName) {
  EXPECT_EQ(TablePattern("stage[2].stop"), "stage[].stop");
  EXPECT_EQ(TablePattern("run[10].stage[3]"), "run[].stage[]");
  EXPECT_EQ(TablePattern("a[x]"), "a[x]");
  EXPECT_EQ(TestKeys().Find("stage[4]", "rate").size(), 1u);
  EXPECT_EQ(TestKeys().Find("p.lambda", "value").size(), 1u);
  EXPECT_TRUE(TestKeys().Find("p.lambda.x", "value").empty());
  EXPECT_TRUE(TestKeys().Find("t", "rate").empty());
}

TEST(KeyTable, ReadsThroughTheTableAndRecordsWhatWasConsulted) {
  TestKeys().ResetConsulted();
  const ConfigTable root = WithKeys("[t]\nmodulus = 20\n[[stage]]\nrate = 2\n[p.a]\nvalue = 0.5\n");
  const ConfigTable t = root.GetTable("t");
  EXPECT_EQ(t.GetDouble("modulus", 500, Range::Positive()), 20);
  EXPECT_EQ(t.GetInt("count", 3, Range::Closed(1, 10)), 3);
  EXPECT_FALSE(t.GetBool("flag", false));
  EXPECT_EQ(root.GetTableArray("stage")[0].GetDouble("rate", Range::Positive()), 2);
  EXPECT_EQ(root.GetTable("p").GetTable("a").GetDouble("value", Range::Closed(0, 1)), 0.5);
  std::vector<std::string> left = TestKeys().Unconsulted();
  EXPECT_TRUE(left.empty()) << left.front();
}

TEST(KeyTable, AKeyTheTableLacksIsAParserBug) {
  const ConfigTable t = WithKeys("[t]\nmodulus = 20\n").GetTable("t");
  EXPECT_THROW(t.GetDouble("stiffness", 1.0, Range::Positive()), InvariantError);
  EXPECT_THROW(t.Has("other"), InvariantError);
}

TEST(KeyTable, ARangeOrDefaultOtherThanTheTablesIsAParserBug) {
  const ConfigTable t = WithKeys("[t]\nmodulus = 20\n").GetTable("t");
  EXPECT_THROW(t.GetDouble("modulus", Range::NonNegative()), InvariantError);
  EXPECT_THROW(t.GetDouble("modulus", 400, Range::Positive()), InvariantError);
  EXPECT_THROW(t.GetInt("count", 4, Range::Closed(1, 10)), InvariantError);
  EXPECT_THROW(t.GetBool("flag", true), InvariantError);
  try {
    t.GetDouble("modulus", 400, Range::Positive());
  } catch (const InvariantError& error) {
    EXPECT_NE(std::string(error.what()).find("t.modulus"), std::string::npos) << error.what();
  }
}

TEST(KeyTable, UnknownKeysAreRefusedNamingTheValidOnes) {
  const ConfigTable root = WithKeys("[t]\nmodulus = 20\nmodulos = 3\n");
  const ConfigTable t = root.GetTable("t");
  t.GetDouble("modulus", 500, Range::Positive());
  t.GetInt("count", 3, Range::Closed(1, 10));
  try {
    root.CheckNoUnknownKeys();
    FAIL() << "a made-up key was accepted";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("test.toml: key 't.modulos' is not a known key"), std::string::npos)
        << message;
    EXPECT_NE(message.find("count, modulus"), std::string::npos) << message;
  }
}

TEST(KeyTable, RendersEveryKeyAsTextAndMarkdown) {
  const std::string text = TestKeys().Render(KeyFormat::kText);
  const std::string markdown = TestKeys().Render(KeyFormat::kMarkdown);
  EXPECT_NE(text.find("[t]\n  modulus: number (MPa), > 0; default 500\n      a modulus\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("a rate (where type = a)"), std::string::npos) << text;
  EXPECT_NE(markdown.find("## [t]\n\n| key | type | unit | valid | default | meaning |\n"),
            std::string::npos)
      << markdown;
  EXPECT_NE(markdown.find("| `count` | integer | - | in [1, 10] | 3 | a count |"),
            std::string::npos)
      << markdown;
  for (const KeySpec& spec : TestKeys().keys()) {
    EXPECT_NE(text.find("  " + spec.key + ": "), std::string::npos) << spec.key;
    EXPECT_NE(markdown.find("| `" + spec.key + "` |"), std::string::npos) << spec.key;
  }
}

}  // namespace
}  // namespace granasym
