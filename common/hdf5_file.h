// RAII access to HDF5 files through the C API: datasets of doubles and
// integers, strings and attributes, addressed by slash-separated paths.
//
// HighFive is not packaged in Debian 12 and the official C++ bindings throw
// opaque exceptions, so this thin layer wraps the C API, checks every return
// code and names the failing call, the file and the object in its message.
//
// Integrity. Files are written in the HDF5 1.10 format (readable by HDF5 1.10
// and later), whose metadata carry checksums: the superblock, every object
// header with its attributes (numbers inline, strings by reference), the
// group structure and the chunk indexes. Every numeric dataset is chunked
// (chunks of at most 1 MiB) with HDF5's Fletcher32 filter, so a flipped bit
// in its data fails the read: InputError "FILE: dataset NAME fails its
// checksum (the file is corrupt)". Not covered: variable-length strings
// (WriteString, WriteStrings and string attributes live in HDF5's global
// heap, which has no checksum in any format version). They are short
// metadata: the scene text, names, messages and enumerations; readers that
// depend on them parse them (enumerations against their names) or compare
// them (the scene's hash), and empty datasets have no data to check.
//
// Failed writes. A write that fails (no space left, a file-size limit)
// throws FileError naming the final file and the system's reason; the
// temporary file is removed and a file already under the final name is left
// as it was. HDF5 1.10 keeps the ID of a file whose H5Fclose failed after
// freeing it and closes it again in its exit handler (a segfault at exit,
// HDF5 issue 2257, CVE-2020-10812, fixed in 1.14.0); this layer closes every
// file itself and switches that handler off (H5dont_atexit).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace granasym {

class Hdf5File {
 public:
  // Creates `path` for writing. Data go to `path + ".tmp"` until Commit()
  // renames it, so an interrupted write never leaves a truncated file under the
  // final name. Without Commit() the temporary file is removed. InputError
  // when `path` exists and is not a regular file (a folder, a device).
  static Hdf5File CreateAtomic(const std::string& path);
  // Opens an existing file read-only (InputError when it cannot be opened).
  static Hdf5File OpenRead(const std::string& path);

  Hdf5File(Hdf5File&& other) noexcept;
  Hdf5File& operator=(Hdf5File&& other) noexcept;
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;
  ~Hdf5File();

  // Flushes and closes the file and renames the temporary file to the final
  // name (FileError when any of it fails; the temporary file is removed).
  void Commit();

  const std::string& path() const { return path_; }

  // Writing (FileError when the file system refuses). Intermediate groups are
  // created as needed. `units` becomes the dataset's "units" attribute when
  // non-empty ("1" for dimensionless).
  void WriteDoubles(const std::string& name, const std::vector<double>& values,
                    const std::string& units = "");
  // Row-major matrix of rows x cols doubles.
  void WriteMatrix(const std::string& name, const std::vector<double>& values, size_t rows,
                   size_t cols, const std::string& units = "");
  void WriteInts(const std::string& name, const std::vector<int64_t>& values,
                 const std::string& units = "");
  void WriteString(const std::string& name, const std::string& value);
  // A one-dimensional dataset of variable-length UTF-8 strings (a text column).
  void WriteStrings(const std::string& name, const std::vector<std::string>& values);
  void CreateGroup(const std::string& name);
  void SetAttribute(const std::string& object, const std::string& name, double value);
  void SetAttribute(const std::string& object, const std::string& name, int64_t value);
  void SetAttribute(const std::string& object, const std::string& name, const std::string& value);
  void SetAttribute(const std::string& object, const std::string& name, const char* value) {
    SetAttribute(object, name, std::string(value));
  }

  // Reading. A checksum that does not match is an InputError naming the file
  // and the object; other failures are RuntimeErrors naming the call.
  bool Exists(const std::string& name) const;
  std::vector<std::string> List(const std::string& group) const;
  std::vector<double> ReadDoubles(const std::string& name) const;
  // Returns a row-major matrix; `rows` and `cols` receive its shape.
  std::vector<double> ReadMatrix(const std::string& name, size_t* rows, size_t* cols) const;
  std::vector<int64_t> ReadInts(const std::string& name) const;
  std::string ReadString(const std::string& name) const;
  std::vector<std::string> ReadStrings(const std::string& name) const;
  bool HasAttribute(const std::string& object, const std::string& name) const;
  // Reads every dataset of numbers (their Fletcher32 checksums) and throws
  // as a read does for the first that fails: a whole file checked at once,
  // e.g. a cached result before it is trusted.
  void CheckData() const;
  double ReadDoubleAttribute(const std::string& object, const std::string& name) const;
  int64_t ReadIntAttribute(const std::string& object, const std::string& name) const;
  std::string ReadStringAttribute(const std::string& object, const std::string& name) const;

 private:
  Hdf5File(int64_t id, std::string path, std::string temporary_path);
  void Close();
  int64_t id_ = -1;  // hid_t
  std::string path_;
  std::string temporary_path_;  // empty when opened for reading
};

}  // namespace granasym
