// What a case is (case.toml): one writer, one reader, and the checked set of
// the figures a case serves.
#include "study/case_record.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "common/text_file.h"

namespace granasym::study {
namespace {
namespace fs = std::filesystem;

std::string Message(const std::string& text) {
  try {
    FigureSet::Parse(text, "p.toml", "run[2].figures");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(FigureSet, ReadsFiguresSectionsAndTheRateStudy) {
  const FigureSet set = FigureSet::Parse(" 8,9 , 16, Sec. 5.2,rate ", "p.toml", "figures");
  EXPECT_EQ(set.entries(), (std::vector<std::string>{"8", "9", "16", "Sec. 5.2", "rate"}));
  EXPECT_EQ(set.Text(), "8, 9, 16, Sec. 5.2, rate");
  EXPECT_EQ(set.Figures(), (std::vector<int>{8, 9, 16}));
  EXPECT_TRUE(set.HasFigure(16));
  EXPECT_FALSE(set.HasFigure(5));  // "Sec. 5.2" is a section, not figure 5
  EXPECT_TRUE(set.HasSection("5.2"));
  EXPECT_FALSE(set.HasSection("5"));
  EXPECT_TRUE(set.ServesRateStudy());
  EXPECT_TRUE(set.Contains("Sec. 5.2"));
  EXPECT_TRUE(FigureSet::Parse("", "p.toml", "figures").empty());
  EXPECT_TRUE(FigureSet::Parse("  ", "p.toml", "figures").empty());
  EXPECT_FALSE(FigureSet::Parse("10", "p.toml", "figures").ServesRateStudy());
}

TEST(FigureSet, RejectsWhatThePaperDoesNotHaveNamingTheFileKeyAndValue) {
  for (const char* bad : {"23", "0", "08", "Fig. 10", "10b", "Sec. 7", "Sec.5.2", "rates", "-1"}) {
    const std::string message = Message(std::string("9, ") + bad);
    EXPECT_NE(message.find("p.toml: key 'run[2].figures'"), std::string::npos) << message;
    EXPECT_NE(message.find(std::string("'") + bad + "' is not valid"), std::string::npos)
        << message;
    EXPECT_NE(message.find("figure numbers 1-22"), std::string::npos) << message;
  }
  EXPECT_NE(Message("9, 10, 9").find("names '9' twice"), std::string::npos);
  EXPECT_NE(Message("9,,10").find("has an empty entry"), std::string::npos);
}

CaseRecord Example() {
  CaseRecord c;
  c.id = "r2/nc100_psi90";
  c.name = "nc100_psi90";
  c.replicate = 2;
  c.key = "abc123";
  c.parent = "r2/ncl";
  c.parent_stage = "p100";
  c.run = "nc{p}_psi{psi}";
  c.figures = FigureSet::Parse("10, 16, Sec. 5.2", "p.toml", "figures");
  c.programme = "paper";
  c.scale = "small";
  c.threads = 2;
  c.program_version = "0.1.0 (abc)";
  c.variables = {{"p", "100"}, {"psi", "90"}};
  return c;
}

TEST(CaseRecord, ReadsBackWhatItWrites) {
  const fs::path dir = fs::path(::testing::TempDir()) / "case_record_round_trip";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const CaseRecord c = Example();
  c.Write(dir.string());
  const CaseRecord back = CaseRecord::Read(dir.string());
  EXPECT_EQ(back.directory, dir.string());
  EXPECT_EQ(back.Text(), c.Text());
  EXPECT_EQ(back.id, c.id);
  EXPECT_EQ(back.parent_name(), "ncl");
  EXPECT_EQ(back.parent_stage, "p100");
  EXPECT_EQ(back.replicate, 2);
  EXPECT_EQ(back.threads, 2);
  EXPECT_EQ(back.figures, c.figures);
  EXPECT_EQ(back.variables, c.variables);
  // The file's text is what earlier versions wrote: study folders stay readable.
  EXPECT_NE(c.Text().find("figures = \"10, 16, Sec. 5.2\"\n"), std::string::npos) << c.Text();
  CaseRecord sample = c;
  sample.parent.clear();
  EXPECT_EQ(sample.parent_name(), "");
}

TEST(CaseRecord, ABadFileIsAnInputErrorNamingItAndTheKey) {
  const fs::path dir = fs::path(::testing::TempDir()) / "case_record_bad";
  fs::remove_all(dir);
  fs::create_directories(dir);
  EXPECT_THROW(CaseRecord::Read(dir.string()), InputError);  // no case.toml
  std::string text = Example().Text();
  text.replace(text.find("10, 16"), 6, "10, 99");
  WriteTextFileAtomically((dir / "case.toml").string(), text);
  try {
    CaseRecord::Read(dir.string());
    FAIL() << "an unknown figure was accepted";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("case.toml: key 'figures'"), std::string::npos) << message;
    EXPECT_NE(message.find("'99' is not valid"), std::string::npos) << message;
  }
  // Variables are text, as the writer quotes them.
  WriteTextFileAtomically((dir / "case.toml").string(), Example().Text() + "colour = 3\n");
  EXPECT_THROW(CaseRecord::Read(dir.string()), InputError);
  WriteTextFileAtomically((dir / "case.toml").string(),
                          "seed = 3\n" + Example().Text());  // an unknown key at the top
  try {
    CaseRecord::Read(dir.string());
    FAIL() << "an unknown key was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("seed"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace granasym::study
