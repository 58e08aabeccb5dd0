#include "common/csv_table.h"

#include <gtest/gtest.h>

#include <string>

#include "common/error.h"

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
}

}  // namespace
}  // namespace granasym
