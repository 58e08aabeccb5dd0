#include "common/time_series.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "common/error.h"
#include "common/hdf5_file.h"

namespace granasym {
namespace {

std::string TempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("granasym_" + name)).string();
}

TEST(TimeSeries, RoundTripsThroughAFile) {
  TimeSeries series({{"p_kpa", "kPa", "mean stress"}, {"e", "1", ""}});
  series.AddRow({100.0, 0.8});
  series.AddRow({200.0, 0.7});
  const std::string path = TempPath("series.h5");
  {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    series.Write(file, "/series");
    file.Commit();
  }
  const TimeSeries again = TimeSeries::Read(Hdf5File::OpenRead(path), "/series");
  EXPECT_EQ(again.rows(), 2u);
  EXPECT_EQ(again.Values("e"), (std::vector<double>{0.8, 0.7}));
  EXPECT_EQ(again.columns()[0].units, "kPa");
}

// A shorter column would be read past its end (by WriteCsv, by a restart).
TEST(TimeSeries, AColumnOfAnotherLengthIsRefusedNamingIt) {
  const std::string path = TempPath("series_short.h5");
  {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    file.WriteDoubles("/series/p_kpa", {100.0, 200.0, 300.0});
    file.WriteDoubles("/series/e", {0.8, 0.7});
    file.SetAttribute("/series", "columns", "p_kpa,e");
    file.SetAttribute("/series", "rows", int64_t{3});
    file.Commit();
  }
  try {
    TimeSeries::Read(Hdf5File::OpenRead(path), "/series");
    FAIL() << "a short column was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(path + ": dataset /series/e has 2 rows, the series 3"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace granasym
