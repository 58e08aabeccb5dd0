// The study folder's records: merging refuses shards of different studies,
// naming the field that differs.
#include "study/study_folder.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "common/error.h"
#include "common/text_file.h"

namespace granasym::study {
namespace {

namespace fs = std::filesystem;

TEST(MergeStudies, ShardsOfAnotherStudyAreRefusedNamingTheField) {
  const fs::path root =
      fs::temp_directory_path() / ("granasym_study_folder_" + std::to_string(getpid()));
  fs::remove_all(root);
  const std::string record =
      "programme = \"paper\"\nprogramme_file = \"paper.toml\"\nscale = \"tiny\"\nthreads = 1\n"
      "replicates = 2\ncount = 800\nncl = \"ncl\"\nprogram_version = \"x\"\n";
  fs::create_directories(root / "a");
  fs::create_directories(root / "b");
  WriteTextFileAtomically((root / "a/study.toml").string(), record);
  std::string other = record;
  other.replace(other.find("threads = 1"), 11, "threads = 2");
  WriteTextFileAtomically((root / "b/study.toml").string(), other);
  try {
    MergeStudies({(root / "a").string(), (root / "b").string()}, (root / "m").string());
    ADD_FAILURE() << "merged shards of two studies";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("threads is '1' there and '2' here"),
              std::string::npos)
        << error.what();
  }
  fs::remove_all(root);
}

}  // namespace
}  // namespace granasym::study
