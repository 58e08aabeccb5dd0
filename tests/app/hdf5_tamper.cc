// Damages an HDF5 file on purpose, for the command-line tests
// (tests/app/partial_result_test.sh, corrupt checkpoints):
//   hdf5_tamper flip FILE DATASET [BYTE [BIT]]   flips a bit of the stored data
//   hdf5_tamper set-int FILE DATASET INDEX VALUE rewrites one 64-bit integer
//                                                (checksums then match)
#include "tests/common/hdf5_tamper.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  using namespace granasym::testing;
  try {
    const std::string command = argc > 1 ? argv[1] : "";
    if (command == "flip" && (argc == 4 || argc == 5 || argc == 6)) {
      const int64_t byte = argc > 4 ? std::atoll(argv[4]) : 0;
      const int bit = argc > 5 ? std::atoi(argv[5]) : 0;
      const int64_t offset = DatasetDataOffset(argv[2], argv[3]) + byte;
      FlipBit(argv[2], offset, bit);
      std::printf("flipped bit %d of byte %lld (%s)\n", bit, static_cast<long long>(offset),
                  argv[3]);
      return 0;
    }
    if (command == "set-int" && argc == 6) {
      const size_t index = static_cast<size_t>(std::atoll(argv[4]));
      const int64_t value = std::atoll(argv[5]);
      RewriteInts(argv[2], argv[3],
                  [&](std::vector<int64_t>& values) { values.at(index) = value; });
      return 0;
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "hdf5_tamper: %s\n", error.what());
    return 1;
  }
  std::fprintf(stderr,
               "usage: hdf5_tamper flip FILE DATASET [BYTE [BIT]]\n"
               "       hdf5_tamper set-int FILE DATASET INDEX VALUE\n");
  return 2;
}
