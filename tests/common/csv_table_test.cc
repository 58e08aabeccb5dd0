#include "common/csv_table.h"

#include <gtest/gtest.h>

#include <string>

#include "common/error.h"
#include "common/quantity_names.h"

namespace granasym {
namespace {

TEST(CsvTextTable, QuotedFieldsKeepCommasQuotesAndLineBreaks) {
  const CsvTextTable table = CsvTextTable::Parse(
      "# a comment before the header\n"
      "case,message, p_kpa\n"
      "r1/ncl,\"still drifting: psi_sigma 1.2 (< 1), slope 0.2\", 20.5\n"
      "\n"
      "r1/oc,\"say \"\"hi\"\"\",7\n"
      "r1/x,\"two\nlines\",  8 \n",
      "states.csv");
  ASSERT_EQ(table.columns, (std::vector<std::string>{"case", "message", "p_kpa"}));
  ASSERT_EQ(table.rows.size(), 3u);
  EXPECT_EQ(table.rows[0][1], "still drifting: psi_sigma 1.2 (< 1), slope 0.2");
  EXPECT_EQ(table.rows[0][2], "20.5");
  EXPECT_EQ(table.rows[1][1], "say \"hi\"");
  EXPECT_EQ(table.rows[2][1], "two\nlines");
  EXPECT_EQ(table.rows[2][2], "8");
  EXPECT_EQ(table.line_numbers, (std::vector<int>{3, 5, 6}));
  EXPECT_EQ(table.comments, (std::vector<std::string>{"a comment before the header"}));
  EXPECT_EQ(table.Column("p_kpa"), 2u);
  EXPECT_EQ(table.Find("ocr"), -1);
}

TEST(CsvTextTable, EmptyFieldsAndATrailingDelimiterCount) {
  const CsvTextTable table = CsvTextTable::Parse("a,b,c\n1,,\n", "t.csv");
  ASSERT_EQ(table.rows.size(), 1u);
  EXPECT_EQ(table.rows[0], (std::vector<std::string>{"1", "", ""}));
}

TEST(CsvTextTable, TabSeparatedHasNoQuoting) {
  const CsvTextTable table = CsvTextTable::Parse(
      "stem\tfigure\ttitle\n"
      "fig16\t16\tpsi_sigma \"vs\" psi_epsilon, all paths\n",
      "index.tsv", CsvTextTable::Format::kTsv);
  ASSERT_EQ(table.rows.size(), 1u);
  EXPECT_EQ(table.rows[0][2], "psi_sigma \"vs\" psi_epsilon, all paths");
}

TEST(CsvTextTable, ErrorsNameTheFileAndTheLine) {
  try {
    CsvTextTable::Parse("a,b\n1,2\n1,2,3\n", "bad.csv");
    FAIL() << "a row with too many fields was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("bad.csv: line 3 has 3 fields"), std::string::npos)
        << error.what();
  }
  try {
    CsvTextTable::Parse("a,b\n1,\"open\n", "open.csv");
    FAIL() << "an unclosed quote was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("open.csv: line 2"), std::string::npos)
        << error.what();
  }
  try {
    CsvTextTable::Parse("a,b\n\"x\"y,2\n", "after.csv");
    FAIL() << "text after a closing quote was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("after.csv: line 2"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(CsvTextTable::Parse("# only a comment\n", "empty.csv"), InputError);
  const CsvTextTable table = CsvTextTable::Parse("a\n1\n", "t.csv");
  try {
    table.Column("b");
    FAIL();
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("missing column 'b' (columns present: a)"),
              std::string::npos);
  }
}

TEST(CsvTable, NumbersMayBeQuotedButTextIsRejected) {
  const CsvTable table = CsvTable::Parse("# gsd\nd_mm, passing\n\"1.5\", 20\n2,100\n", "gsd.csv");
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.rows[0], (std::vector<double>{1.5, 20}));
  EXPECT_EQ(table.line_numbers, (std::vector<int>{3, 4}));
  EXPECT_THROW(CsvTable::Parse("a\nabc\n", "t.csv"), InputError);
  EXPECT_THROW(CsvTable::Parse("a,b\n1\n", "t.csv"), InputError);
  // What WriteCsv writes reads back, a subnormal number included.
  EXPECT_EQ(CsvTable::Parse("a\n1e-310\n", "t.csv").rows[0][0], 1e-310);
}

// One rule for every table: each case breaks it once; the message names the
// file, the line (and the column where one is at fault) and the value.
struct CsvRuleCase {
  const char* name;
  const char* text;
  std::vector<std::string> mentions;
  bool numeric_only = false;  // a text table accepts it (text fields)
};

const std::vector<CsvRuleCase>& CsvRuleCases() {
  static const std::vector<CsvRuleCase> cases = {
      {"duplicate_column", "a,b,a\n1,2,3\n", {"line 1", "'a'", "columns 1 and 3", "unique"}},
      {"duplicate_column_after_comments",
       "# note\n\nx, y ,y\n1,2,3\n",
       {"line 3", "'y'", "columns 2 and 3"}},
      {"unnamed_column", "a,,b\n1,2,3\n", {"line 1", "column 2 has no name"}},
      {"row_with_an_extra_field", "a,b\n1,2\n1,2,3\n", {"line 3", "3 fields", "2 columns"}},
      {"row_with_a_missing_field", "a,b\n1,2\n\n4\n", {"line 4", "1 fields", "2 columns"}},
      {"nan", "a,b\n1,nan\n", {"line 2", "column 'b'", "'nan'", "finite"}, true},
      {"inf", "a,b\n1,2\n-inf,2\n", {"line 3", "column 'a'", "'-inf'"}, true},
      {"overflow", "a,b\n1,1e400\n", {"line 2", "column 'b'", "'1e400'"}, true},
      {"text", "a,b\n1,abc\n", {"line 2", "column 'b'", "'abc'"}, true},
      {"trailing_text", "a,b\n1.5x,2\n", {"line 2", "column 'a'", "'1.5x'"}, true},
      {"empty_field", "a,b\n1,\n", {"line 2", "column 'b'", "''"}, true},
      {"empty_file", "", {"no header row", "empty"}},
      {"comments_only", "# only a comment\n\n", {"no header row"}},
  };
  return cases;
}

TEST(CsvTable, EveryBreakOfTheCommonRuleNamesFileLineAndValue) {
  for (const CsvRuleCase& c : CsvRuleCases()) {
    const std::string origin = std::string("rule_") + c.name + ".csv";
    try {
      CsvTable::Parse(c.text, origin);
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(origin), std::string::npos) << c.name << ": " << message;
      for (const std::string& mention : c.mentions) {
        EXPECT_NE(message.find(mention), std::string::npos)
            << c.name << ": no '" << mention << "' in: " << message;
      }
    }
  }
}

TEST(CsvTextTable, FollowsTheSameRuleForHeadersAndFieldCounts) {
  for (const CsvRuleCase& c : CsvRuleCases()) {
    const std::string origin = std::string("rule_") + c.name + ".csv";
    if (c.numeric_only) {
      EXPECT_NO_THROW(CsvTextTable::Parse(c.text, origin)) << c.name;
      continue;
    }
    try {
      CsvTextTable::Parse(c.text, origin);
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(origin), std::string::npos) << c.name << ": " << message;
      for (const std::string& mention : c.mentions) {
        EXPECT_NE(message.find(mention), std::string::npos)
            << c.name << ": no '" << mention << "' in: " << message;
      }
    }
  }
}

TEST(CsvTable, RequireOnlyColumnsNamesTheUnknownColumnAndListsTheKnownOnes) {
  const CsvTable table = CsvTable::Parse("# gsd\nd_mm,passing,comment\n1,0,7\n", "gsd.csv");
  EXPECT_EQ(table.header_line, 2);
  EXPECT_NO_THROW(table.RequireOnlyColumns({"comment", "passing", "d_mm", "other"}));
  try {
    table.RequireOnlyColumns({"d_mm", "passing"});
    FAIL() << "an unknown column was accepted";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("gsd.csv: line 2: unknown column 'comment' (column 3; known columns: "
                           "d_mm, passing)"),
              std::string::npos)
        << message;
  }
  EXPECT_EQ(table.Find("passing"), 1);
  EXPECT_EQ(table.Find("Passing"), -1);
}

// An element test's CSV before and after issue 33 (common/quantity_names.h).
TEST(CsvTable, AColumnIsFoundByItsNameOrItsFormerName) {
  const CsvTable old_file =
      CsvTable::Parse("time_s,p_kpa,void_ratio\n0,100,0.8\n", "old_result.csv");
  const CsvTable new_file = CsvTable::Parse("time_s,p_kpa,e\n0,100,0.8\n", "result.csv");
  EXPECT_EQ(old_file.Column(quantity::kVoidRatio, quantity::former::kVoidRatio), 2u);
  EXPECT_EQ(new_file.Column(quantity::kVoidRatio, quantity::former::kVoidRatio), 2u);
  // Both present: the current name wins.
  const CsvTable both = CsvTable::Parse("void_ratio,e\n0.7,0.8\n", "both.csv");
  EXPECT_EQ(both.Column(quantity::kVoidRatio, quantity::former::kVoidRatio), 1u);
  // Neither: the message names the current name and lists the columns.
  try {
    CsvTable::Parse("time_s,p_kpa\n0,100\n", "neither.csv")
        .Column(quantity::kVoidRatio, quantity::former::kVoidRatio);
    FAIL() << "found a column that is not there";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("neither.csv: missing column 'e' (columns present: time_s, p_kpa)"),
              std::string::npos)
        << message;
  }
}

}  // namespace
}  // namespace granasym
