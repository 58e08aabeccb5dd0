#include "common/text_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <filesystem>

#include "common/error.h"
#include "tests/common/file_size_limit.h"

namespace granasym {
namespace {

std::string TempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("granasym_" + name)).string();
}

TEST(WriteTextFileAtomically, ReplacesTheFileAndLeavesNoTemporary) {
  const std::string path = TempPath("text_replace.txt");
  WriteTextFileAtomically(path, "old\n");
  WriteTextFileAtomically(path, "new\n");
  EXPECT_EQ(ReadTextFile(path), "new\n");
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(WriteTextFileAtomically, AFullDiskIsAFileErrorThatKeepsTheOldFile) {
  const std::string path = TempPath("text_full.txt");
  WriteTextFileAtomically(path, "the good file\n");
  const std::string big(256 * 1024, 'x');
  const testing::LimitedWrite write =
      testing::WriteWithFileSizeLimit(16 * 1024, [&] { WriteTextFileAtomically(path, big); });
  ASSERT_EQ(write.outcome, testing::LimitedWrite::kFileError) << write.message;
  EXPECT_NE(write.message.find("cannot write '" + path + "': File too large"), std::string::npos)
      << write.message;
  EXPECT_NE(write.message.find("is not replaced"), std::string::npos) << write.message;
  EXPECT_EQ(ReadTextFile(path), "the good file\n");
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

// A device is written in place, never replaced by a renamed file. The test
// makes its own full device (the same numbers as /dev/full, 1:7) where it may
// (root), so that a regression cannot replace the system's.
TEST(WriteTextFileAtomically, WritesADeviceInPlaceAndReportsAFullOne) {
  std::string full = TempPath("full_device");
  std::filesystem::remove(full);
  if (mknod(full.c_str(), S_IFCHR | 0666, makedev(1, 7)) != 0) full = "/dev/full";
  try {
    WriteTextFileAtomically(full, "text\n");
    FAIL() << "writing to " << full << " succeeded";
  } catch (const FileError& error) {
    EXPECT_NE(
        std::string(error.what()).find("cannot write '" + full + "': No space left on device"),
        std::string::npos)
        << error.what();
  }
  EXPECT_TRUE(std::filesystem::is_character_file(full));
  EXPECT_FALSE(std::filesystem::exists(full + ".tmp"));
  WriteTextFileAtomically("/dev/null", "text\n");
  EXPECT_TRUE(std::filesystem::is_character_file("/dev/null"));
  if (full != "/dev/full") std::filesystem::remove(full);
}

TEST(WriteTextFileAtomically, NeverReplacesAFolder) {
  const std::string folder = TempPath("text_folder");
  std::filesystem::create_directories(folder);
  EXPECT_THROW(WriteTextFileAtomically(folder, "text\n"), FileError);
  EXPECT_TRUE(std::filesystem::is_directory(folder));
}

}  // namespace
}  // namespace granasym
