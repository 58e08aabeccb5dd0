// Test helpers that damage HDF5 files on purpose, through the C API: the file
// offset of a dataset's stored data (its first chunk, or its contiguous
// block), a flipped bit at an offset, and datasets and attributes rewritten
// with other values (checksums recomputed: the data then break invariants,
// not checksums). Header-only; the including target links HDF5.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace granasym::testing {

// Before any other HDF5 call of a test, as Hdf5File does: no exit handler
// (see common/hdf5_file.h), whichever initialises the library first.
inline void PrepareHdf5() { H5dont_atexit(); }

// The file offset of the first stored byte of `dataset`'s data.
inline int64_t DatasetDataOffset(const std::string& path, const std::string& dataset) {
  PrepareHdf5();
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error("cannot open " + path);
  const hid_t data = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
  if (data < 0) {
    H5Fclose(file);
    throw std::runtime_error("no dataset " + dataset + " in " + path);
  }
  const hid_t dcpl = H5Dget_create_plist(data);
  haddr_t address = HADDR_UNDEF;
  if (H5Pget_layout(dcpl) == H5D_CHUNKED) {
    const hid_t space = H5Dget_space(data);
    hsize_t chunk_offset[8] = {0};
    unsigned filter_mask = 0;
    hsize_t size = 0;
    H5Dget_chunk_info(data, space, 0, chunk_offset, &filter_mask, &address, &size);
    H5Sclose(space);
  } else {
    address = H5Dget_offset(data);
  }
  H5Pclose(dcpl);
  H5Dclose(data);
  H5Fclose(file);
  if (address == HADDR_UNDEF) throw std::runtime_error(dataset + " has no stored data");
  return static_cast<int64_t>(address);
}

// Flips bit `bit` (0..7) of the byte at `offset`.
inline void FlipBit(const std::string& path, int64_t offset, int bit = 0) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  if (!file) throw std::runtime_error("cannot open " + path);
  file.seekg(offset);
  char byte = 0;
  file.get(byte);
  byte = static_cast<char>(byte ^ (1 << bit));
  file.seekp(offset);
  file.put(byte);
  if (!file) throw std::runtime_error("cannot flip a bit in " + path);
}

// Flips a bit in the data of `dataset`, `byte` bytes into its first chunk.
inline void FlipDatasetBit(const std::string& path, const std::string& dataset, int64_t byte = 0,
                           int bit = 0) {
  FlipBit(path, DatasetDataOffset(path, dataset) + byte, bit);
}

// Reads `dataset` (its element type in memory: H5T_NATIVE_INT64 or
// H5T_NATIVE_DOUBLE), lets `change` modify the values and writes them back
// in place, through HDF5 (so its checksums match the new values).
template <typename T, typename Change>
void RewriteDataset(const std::string& path, const std::string& dataset, hid_t memory_type,
                    Change change) {
  PrepareHdf5();
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error("cannot open " + path + " for writing");
  const hid_t data = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
  const hid_t space = H5Dget_space(data);
  std::vector<T> values(static_cast<size_t>(H5Sget_simple_extent_npoints(space)));
  herr_t status = H5Dread(data, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  change(values);
  if (status >= 0)
    status = H5Dwrite(data, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Sclose(space);
  H5Dclose(data);
  if (H5Fclose(file) < 0 || status < 0) throw std::runtime_error("cannot rewrite " + dataset);
}

inline void RewriteInts(const std::string& path, const std::string& dataset,
                        const std::function<void(std::vector<int64_t>&)>& change) {
  RewriteDataset<int64_t>(path, dataset, H5T_NATIVE_INT64, change);
}

// Overwrites the 64-bit integer attribute `name` of `object`.
inline void RewriteIntAttribute(const std::string& path, const std::string& object,
                                const std::string& name, int64_t value) {
  PrepareHdf5();
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error("cannot open " + path + " for writing");
  // Through the object: H5Aopen_by_name cannot write an attribute in dense storage.
  const hid_t target = H5Oopen(file, object.c_str(), H5P_DEFAULT);
  const hid_t attribute = H5Aopen(target, name.c_str(), H5P_DEFAULT);
  const herr_t status = H5Awrite(attribute, H5T_NATIVE_INT64, &value);
  H5Aclose(attribute);
  H5Oclose(target);
  if (H5Fclose(file) < 0 || status < 0) throw std::runtime_error("cannot rewrite " + name);
}

}  // namespace granasym::testing
