// The programme and [figures] key tables against their parsers: every key of
// the tables is read by the shipped programmes (and a [figures] table with
// every key), and a made-up key is refused naming it and the valid keys.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/error.h"
#include "common/key_table.h"
#include "study/figure_settings.h"
#include "study/programme.h"

namespace granasym::study {
namespace {

TEST(ProgrammeKeys, TheShippedProgrammesReadEveryKeyOfTheTable) {
  ProgrammeKeys().ResetConsulted();
  for (const auto& entry : std::filesystem::directory_iterator(GRANASYM_PROGRAMMES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    const Programme programme = Programme::Load(entry.path().string(), Scale::kTiny);
    EXPECT_FALSE(programme.cases.empty()) << entry.path();
  }
  const std::vector<std::string> unread = ProgrammeKeys().Unconsulted();
  EXPECT_TRUE(unread.empty()) << "never read: " << unread.front();
}

TEST(ProgrammeKeys, AMadeUpKeyIsRefusedNamingItAndTheValidKeys) {
  const std::string text =
      "[study]\nname = \"p\"\nnmae = \"q\"\n[scale.tiny]\ncount = 10\n[[run]]\nname = \"a\"\n"
      "from = \"sample\"\n[[run.stage]]\npsi_epsilon_deg = 0.0\nstretching_rate = 1.0\n"
      "[run.stage.stop]\nsteps = 5\n";
  try {
    Programme::Parse(text, "made_up.toml", ".", Scale::kTiny);
    FAIL() << "a made-up key was accepted";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("made_up.toml: key 'study.nmae' is not known here: valid keys are "
                           "description, name, ncl"),
              std::string::npos)
        << message;
  }
}

TEST(FigureKeys, EveryKeyIsReadAndAMadeUpKeyIsRefused) {
  FigureKeys().ResetConsulted();
  const FigureSettings s = FigureSettings::FromConfig(
      ConfigTable::ParseString("[figures]\nlevels = [0.5, 0.55]\nfig18_level = 0.52\n"
                               "cases = [\"nc*\"]\nexclude_cases = [\"*_psi150\"]\n"
                               "only = [\"10\"]\nmodels = []\nreplicates = true\n",
                               "f.toml")
          .GetTable("figures"));
  EXPECT_EQ(s.levels.size(), 2u);
  EXPECT_TRUE(s.replicates);
  const std::vector<std::string> unread = FigureKeys().Unconsulted();
  EXPECT_TRUE(unread.empty()) << "never read: " << unread.front();
  try {
    FigureSettings::FromConfig(
        ConfigTable::ParseString("[figures]\nlevel = [0.5]\n", "f.toml").GetTable("figures"));
    FAIL() << "a made-up key was accepted";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("key 'figures.level' is not a known key (valid keys here: cases, "
                           "exclude_cases, fig18_level, levels, models, only, replicates)"),
              std::string::npos)
        << message;
  }
}

}  // namespace
}  // namespace granasym::study
