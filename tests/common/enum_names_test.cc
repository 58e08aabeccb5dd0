#include "common/enum_names.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "common/config.h"
#include "common/error.h"
#include "tests/common/enum_spellings.h"

namespace granasym {
namespace {
enum class Shape { kSphere, kCube, kRodWithCaps };
enum class Lonely { kOnly };
}  // namespace

template <>
struct EnumNames<Shape> {
  static constexpr EnumEntry<Shape> kEntries[] = {
      {Shape::kSphere, "sphere", "a ball"},
      {Shape::kCube, "cube"},
      {Shape::kRodWithCaps, "rod_with_caps", "a spherocylinder"},
  };
};
template <>
struct EnumNames<Lonely> {
  static constexpr EnumEntry<Lonely> kEntries[] = {{Lonely::kOnly, "only"}};
};

namespace {

// The table is usable at compile time.
static_assert(std::string_view(ToString(Shape::kCube)) == "cube");
static_assert(FromString<Shape>("rod_with_caps") == Shape::kRodWithCaps);
static_assert(!FromString<Shape>("cylinder").has_value());

std::string MessageOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(EnumNames, EveryNameRoundTrips) {
  ExpectSpellings<Shape>(
      {{Shape::kSphere, "sphere"}, {Shape::kCube, "cube"}, {Shape::kRodWithCaps, "rod_with_caps"}});
  ExpectSpellings<Lonely>({{Lonely::kOnly, "only"}});
}

TEST(EnumNames, UnknownNamesAreNotParsedAndLeaveTheValueAlone) {
  EXPECT_FALSE(FromString<Shape>("Sphere").has_value());  // case-sensitive
  EXPECT_FALSE(FromString<Shape>("").has_value());
  EXPECT_FALSE(FromString<Shape>("sphere ").has_value());
  Shape shape = Shape::kCube;
  EXPECT_FALSE(FromString("cylinder", &shape));
  EXPECT_EQ(shape, Shape::kCube);
  EXPECT_TRUE(FromString(std::string("sphere"), &shape));
  EXPECT_EQ(shape, Shape::kSphere);
}

TEST(EnumNames, ValuesOutsideTheTableAreUnknown) {
  EXPECT_STREQ(ToString(static_cast<Shape>(17)), "unknown");
  EXPECT_STREQ(EnumDescription(static_cast<Shape>(17)), "");
}

TEST(EnumNames, DescriptionsAreOptional) {
  EXPECT_STREQ(EnumDescription(Shape::kSphere), "a ball");
  EXPECT_STREQ(EnumDescription(Shape::kCube), "");
}

TEST(EnumNames, ValuesComeInTableOrder) {
  EXPECT_EQ(EnumValues<Shape>(),
            (std::vector<Shape>{Shape::kSphere, Shape::kCube, Shape::kRodWithCaps}));
}

TEST(EnumNames, AllowedNamesReadAsAList) {
  EXPECT_EQ(AllowedNames<Shape>(), "sphere, cube or rod_with_caps");
  EXPECT_EQ(AllowedNames<Lonely>(), "only");
  EXPECT_EQ(AllowedNames(std::vector<Shape>{Shape::kCube, Shape::kSphere}), "cube or sphere");
  EXPECT_EQ(AllowedNames(std::vector<Shape>{}), "");
}

TEST(ConfigTableGetEnum, ReadsANameAndFallsBackToTheDefault) {
  const ConfigTable root = ConfigTable::ParseString("[grain]\nshape = 'cube'\n", "s.toml");
  const ConfigTable grain = root.GetTable("grain");
  EXPECT_EQ(grain.GetEnum("shape", Shape::kSphere), Shape::kCube);
  EXPECT_EQ(grain.GetEnum<Shape>("shape"), Shape::kCube);
  EXPECT_EQ(grain.GetEnum("other_shape", Shape::kRodWithCaps), Shape::kRodWithCaps);
  EXPECT_NO_THROW(root.CheckNoUnknownKeys());  // GetEnum marks its key as known
}

TEST(ConfigTableGetEnum, UnknownNameNamesFileKeyValueAndAllowedNames) {
  const ConfigTable grain =
      ConfigTable::ParseString("[grain]\nshape = 'cylinder'\n", "scene.toml").GetTable("grain");
  for (const std::string& message : {MessageOf([&] { grain.GetEnum("shape", Shape::kSphere); }),
                                     MessageOf([&] { grain.GetEnum<Shape>("shape"); })}) {
    EXPECT_NE(message.find("scene.toml"), std::string::npos) << message;
    EXPECT_NE(message.find("grain.shape"), std::string::npos) << message;
    EXPECT_NE(message.find("'cylinder'"), std::string::npos) << message;
    EXPECT_NE(message.find("sphere, cube or rod_with_caps"), std::string::npos) << message;
  }
}

TEST(ConfigTableGetEnum, MissingRequiredKeyNamesTheAllowedNames) {
  const ConfigTable root = ConfigTable::ParseString("", "scene.toml");
  const std::string message = MessageOf([&] { root.GetEnum<Shape>("shape"); });
  EXPECT_NE(message.find("scene.toml"), std::string::npos) << message;
  EXPECT_NE(message.find("'shape' is missing"), std::string::npos) << message;
  EXPECT_NE(message.find("sphere, cube or rod_with_caps"), std::string::npos) << message;
}

TEST(ConfigTableGetEnum, WrongTypeIsRejected) {
  const ConfigTable root = ConfigTable::ParseString("shape = 3\n", "scene.toml");
  const std::string message = MessageOf([&] { root.GetEnum("shape", Shape::kSphere); });
  EXPECT_NE(message.find("expected a string"), std::string::npos) << message;
}

TEST(ConfigTableGetEnum, ASubsetRejectsTheOtherNamesListingOnlyTheSubset) {
  const std::vector<Shape> round = {Shape::kSphere, Shape::kRodWithCaps};
  const ConfigTable root = ConfigTable::ParseString("a = 'rod_with_caps'\nb = 'cube'\n", "f.toml");
  EXPECT_EQ(root.GetEnum("a", Shape::kSphere, round), Shape::kRodWithCaps);
  EXPECT_EQ(root.GetEnum("missing", Shape::kSphere, round), Shape::kSphere);
  const std::string message = MessageOf([&] { root.GetEnum("b", Shape::kSphere, round); });
  EXPECT_NE(message.find("key 'b' = 'cube' is not valid"), std::string::npos) << message;
  EXPECT_NE(message.find("expected sphere or rod_with_caps"), std::string::npos) << message;
}

}  // namespace
}  // namespace granasym
