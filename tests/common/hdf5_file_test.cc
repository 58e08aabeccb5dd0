#include "common/hdf5_file.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "common/error.h"
#include "tests/common/file_size_limit.h"
#include "tests/common/hdf5_tamper.h"

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
  EXPECT_FALSE(file.Exists("series/p/below_a_dataset"));
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

// The filters of a dataset (its layout in *layout).
std::vector<H5Z_filter_t> Filters(const std::string& path, const std::string& name,
                                  H5D_layout_t* layout, std::vector<hsize_t>* chunk = nullptr) {
  testing::PrepareHdf5();
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t dataset = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  const hid_t dcpl = H5Dget_create_plist(dataset);
  *layout = H5Pget_layout(dcpl);
  if (chunk && *layout == H5D_CHUNKED) {
    chunk->assign(2, 0);
    chunk->resize(static_cast<size_t>(H5Pget_chunk(dcpl, 2, chunk->data())));
  }
  std::vector<H5Z_filter_t> filters;
  for (int k = 0; k < H5Pget_nfilters(dcpl); ++k) {
    unsigned flags = 0, config = 0;
    size_t count = 0;
    char filter_name[64];
    filters.push_back(H5Pget_filter2(dcpl, k, &flags, &count, nullptr, sizeof(filter_name),
                                     filter_name, &config));
  }
  H5Pclose(dcpl);
  H5Dclose(dataset);
  H5Fclose(file);
  return filters;
}

TEST(Hdf5File, EveryNumericDatasetCarriesAFletcher32Checksum) {
  const std::string path = TempPath("checksums.h5");
  {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    file.WriteDoubles("x", {1.0, 2.0});
    file.WriteMatrix("m", {1, 2, 3, 4, 5, 6}, 3, 2);
    file.WriteInts("i", {3, 4, 5});
    file.WriteDoubles("empty", {});
    file.WriteMatrix("no_rows", {}, 0, 4);
    file.Commit();
  }
  for (const char* name : {"x", "m", "i"}) {
    H5D_layout_t layout;
    EXPECT_EQ(Filters(path, name, &layout), std::vector<H5Z_filter_t>{H5Z_FILTER_FLETCHER32})
        << name;
    EXPECT_EQ(layout, H5D_CHUNKED) << name;
  }
  // An empty dataset has no data to check (and a chunk cannot be empty).
  H5D_layout_t layout;
  EXPECT_TRUE(Filters(path, "empty", &layout).empty());
  const Hdf5File file = Hdf5File::OpenRead(path);
  EXPECT_TRUE(file.ReadDoubles("empty").empty());
  size_t rows = 1, cols = 0;
  EXPECT_TRUE(file.ReadMatrix("no_rows", &rows, &cols).empty());
  EXPECT_EQ(rows, 0u);
  EXPECT_EQ(cols, 4u);
  EXPECT_EQ(file.ReadInts("i"), (std::vector<int64_t>{3, 4, 5}));
}

TEST(Hdf5File, LargeDatasetsAreSplitIntoEvenChunksOfAtMostOneMebibyte) {
  const std::string path = TempPath("chunks.h5");
  std::vector<double> rows(300000 * 4);
  for (size_t k = 0; k < rows.size(); ++k) rows[k] = 0.5 * static_cast<double>(k);
  {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    file.WriteMatrix("rows", rows, 300000, 4);
    file.Commit();
  }
  H5D_layout_t layout;
  std::vector<hsize_t> chunk;
  Filters(path, "rows", &layout, &chunk);
  ASSERT_EQ(chunk.size(), 2u);
  EXPECT_EQ(chunk[1], 4u);
  EXPECT_LE(chunk[0] * 4 * sizeof(double), size_t{1} << 20);
  EXPECT_EQ(chunk[0], 30000u);  // ten chunks of 960 kB, none partial
  size_t n = 0, cols = 0;
  EXPECT_EQ(Hdf5File::OpenRead(path).ReadMatrix("rows", &n, &cols), rows);
}

// Flips the lowest bit of the one place in the file that holds `value`.
void FlipStoredDouble(const std::string& path, double value) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  char pattern[sizeof(double)];
  std::memcpy(pattern, &value, sizeof(double));
  const size_t at = bytes.find(std::string(pattern, sizeof(double)));
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(bytes.find(std::string(pattern, sizeof(double)), at + 1), std::string::npos);
  testing::FlipBit(path, static_cast<int64_t>(at));
}

void ExpectCorrupt(const std::function<void()>& read, const std::string& what) {
  try {
    read();
    FAIL() << "a corrupt " << what << " was read without an error";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(what + " fails its checksum (the file is corrupt)"), std::string::npos)
        << message;
  }
}

TEST(Hdf5File, AFlippedBitInADatasetFailsItsChecksumNamingTheDataset) {
  const std::string path = TempPath("flipped_data.h5");
  std::vector<double> values(1000);
  for (size_t k = 0; k < values.size(); ++k) values[k] = 0.125 + 1e-3 * static_cast<double>(k);
  {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    file.WriteDoubles("/state/p", values, "kPa");
    file.Commit();
  }
  FlipStoredDouble(path, values[500]);
  const Hdf5File file = Hdf5File::OpenRead(path);
  ExpectCorrupt([&] { file.ReadDoubles("/state/p"); }, "dataset '/state/p'");
}

TEST(Hdf5File, AFlippedBitInAnAttributeFailsTheChecksumOfItsObject) {
  // Few attributes sit in the object header, many in dense storage: both checked.
  for (const int count : {3, 30}) {
    const std::string path = TempPath("flipped_attribute.h5");
    {
      Hdf5File file = Hdf5File::CreateAtomic(path);
      file.CreateGroup("/runner");
      for (int k = 0; k < count; ++k) {
        file.SetAttribute("/runner", "a" + std::to_string(k), 1234.5678 + k);
      }
      file.Commit();
    }
    FlipStoredDouble(path, 1234.5678 + 2);
    try {
      const Hdf5File file = Hdf5File::OpenRead(path);
      const double value = file.ReadDoubleAttribute("/runner", "a2");
      ADD_FAILURE() << count << " attributes: read " << value << " without an error";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("fails its checksum"), std::string::npos)
          << error.what();
    }
  }
}

TEST(Hdf5File, AWriteOnAFullDiskIsAFileErrorThatKeepsTheOldFileAndEndsCleanly) {
  const std::string path = TempPath("full_disk.h5");
  {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    file.WriteDoubles("x", {1.0, 2.0, 3.0});
    file.Commit();
  }
  std::vector<double> big(200000, 0.5);
  // The child exits through exit(): HDF5 1.10's own exit handler would close
  // again the file whose close failed, and crash (common/hdf5_file.h).
  const testing::LimitedWrite write = testing::WriteWithFileSizeLimit(64 * 1024, [&] {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    file.WriteDoubles("x", big);
    file.WriteDoubles("y", big);
    file.Commit();
  });
  ASSERT_EQ(write.outcome, testing::LimitedWrite::kFileError)
      << "signal " << write.signal << ": " << write.message;
  EXPECT_NE(write.message.find("cannot write '" + path + "'"), std::string::npos) << write.message;
  EXPECT_NE(write.message.find("File too large"), std::string::npos) << write.message;
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  EXPECT_EQ(Hdf5File::OpenRead(path).ReadDoubles("x"), (std::vector<double>{1.0, 2.0, 3.0}));
}

TEST(Hdf5File, IsNeverRenamedOverAFolderOrADevice) {
  const std::string folder = TempPath("a_folder.h5");
  std::filesystem::create_directories(folder);
  EXPECT_THROW(Hdf5File::CreateAtomic(folder), InputError);
  EXPECT_TRUE(std::filesystem::is_directory(folder));
  EXPECT_THROW(Hdf5File::CreateAtomic("/dev/null"), InputError);
  EXPECT_TRUE(std::filesystem::is_character_file("/dev/null"));
  EXPECT_FALSE(std::filesystem::exists("/dev/null.tmp"));
}

}  // namespace
}  // namespace granasym
