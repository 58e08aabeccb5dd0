#include "common/hdf5_file.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "common/error.h"

namespace granasym {
namespace {

std::string TempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("granasym_" + name)).string();
}

TEST(Hdf5File, RoundTripsDatasetsStringsAndAttributes) {
  const std::string path = TempPath("roundtrip.h5");
  {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    file.WriteDoubles("series/p", {1.0, 2.5}, "kPa");
    file.WriteMatrix("state/x", {1, 2, 3, 4, 5, 6}, 2, 3, "m");
    file.WriteInts("state/id", {7, 8});
    file.WriteString("scene", "a = 1\n");
    file.SetAttribute("series", "rows", int64_t{2});
    file.SetAttribute("series", "note", "hello");
    file.SetAttribute("series/p", "scale", 0.5);
    EXPECT_FALSE(std::filesystem::exists(path));  // still under the temporary name
    file.Commit();
  }
  ASSERT_TRUE(std::filesystem::exists(path));
  const Hdf5File file = Hdf5File::OpenRead(path);
  EXPECT_EQ(file.ReadDoubles("series/p"), (std::vector<double>{1.0, 2.5}));
  EXPECT_EQ(file.ReadStringAttribute("series/p", "units"), "kPa");
  size_t rows = 0, cols = 0;
  EXPECT_EQ(file.ReadMatrix("state/x", &rows, &cols).size(), 6u);
  EXPECT_EQ(rows, 2u);
  EXPECT_EQ(cols, 3u);
  EXPECT_EQ(file.ReadInts("state/id"), (std::vector<int64_t>{7, 8}));
  EXPECT_EQ(file.ReadString("scene"), "a = 1\n");
  EXPECT_EQ(file.ReadIntAttribute("series", "rows"), 2);
  EXPECT_EQ(file.ReadStringAttribute("series", "note"), "hello");
  EXPECT_DOUBLE_EQ(file.ReadDoubleAttribute("series/p", "scale"), 0.5);
  EXPECT_TRUE(file.Exists("series/p"));
  EXPECT_FALSE(file.Exists("nothing/here"));
  EXPECT_EQ(file.List("series"), (std::vector<std::string>{"p"}));
  std::remove(path.c_str());
}

TEST(Hdf5File, UncommittedFileLeavesNothingBehind) {
  const std::string path = TempPath("uncommitted.h5");
  {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    file.WriteDoubles("x", {1.0});
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(Hdf5File, MissingFileIsAnInputError) {
  EXPECT_THROW(Hdf5File::OpenRead(TempPath("does_not_exist.h5")), InputError);
}

}  // namespace
}  // namespace granasym
