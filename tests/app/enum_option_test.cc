#include "app/enum_option.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace granasym {
namespace {
enum class Drive : unsigned char { kRate, kStressPoint };
}  // namespace

template <>
struct EnumNames<Drive> {
  static constexpr EnumEntry<Drive> kEntries[] = {
      {Drive::kRate, "rate_integration", "the rate form"},
      {Drive::kStressPoint, "stress_point"},
  };
};

namespace {

// Parses `args` (without the program name); returns the CLI11 error text or "".
std::string Parse(CLI::App& app, std::vector<std::string> args) {
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& error) {
    return error.what();
  }
  return "";
}

TEST(EnumOption, ParsesEveryTableName) {
  for (const auto& entry : EnumEntries<Drive>()) {
    CLI::App app;
    Drive drive = entry.value == Drive::kRate ? Drive::kStressPoint : Drive::kRate;
    AddEnumOption(&app, "--drive", &drive, "how to drive");
    EXPECT_EQ(Parse(app, {"--drive", entry.name}), "") << entry.name;
    EXPECT_EQ(drive, entry.value) << entry.name;
  }
}

TEST(EnumOption, KeepsTheDefaultWhenAbsent) {
  CLI::App app;
  Drive drive = Drive::kStressPoint;
  AddEnumOption(&app, "--drive", &drive, "how to drive");
  EXPECT_EQ(Parse(app, {}), "");
  EXPECT_EQ(drive, Drive::kStressPoint);
}

TEST(EnumOption, RejectsUnknownNamesAndIntegersNamingTheAllowedNames) {
  for (const char* bad : {"euler", "1", "Rate_Integration"}) {
    CLI::App app;
    Drive drive = Drive::kRate;
    AddEnumOption(&app, "--drive", &drive, "how to drive");
    const std::string message = Parse(app, {"--drive", bad});
    EXPECT_NE(message.find(std::string("'") + bad + "'"), std::string::npos) << message;
    EXPECT_NE(message.find("rate_integration or stress_point"), std::string::npos) << message;
    EXPECT_EQ(drive, Drive::kRate);
  }
}

TEST(EnumOption, HelpShowsNamesDefaultAndDescriptions) {
  CLI::App app;
  Drive drive = Drive::kStressPoint;
  AddEnumOption(&app, "--drive", &drive, "how to drive");
  const std::string help = app.help();
  EXPECT_NE(help.find("rate_integration|stress_point"), std::string::npos) << help;
  EXPECT_NE(help.find("rate_integration: the rate form"), std::string::npos) << help;
  EXPECT_NE(help.find("stress_point"), std::string::npos) << help;
}

}  // namespace
}  // namespace granasym
