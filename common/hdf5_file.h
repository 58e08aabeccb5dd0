// RAII access to HDF5 files through the C API: datasets of doubles and
// integers, strings and attributes, addressed by slash-separated paths.
//
// HighFive is not packaged in Debian 12 and the official C++ bindings throw
// opaque exceptions, so this thin layer wraps the C API, checks every return
// code and names the failing call, the file and the object in its message.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace granasym {

class Hdf5File {
 public:
  // Creates `path` for writing. Data go to `path + ".tmp"` until Commit()
  // renames it, so an interrupted write never leaves a truncated file under the
  // final name. Without Commit() the temporary file is removed.
  static Hdf5File CreateAtomic(const std::string& path);
  // Opens an existing file read-only.
  static Hdf5File OpenRead(const std::string& path);

  Hdf5File(Hdf5File&& other) noexcept;
  Hdf5File& operator=(Hdf5File&& other) noexcept;
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;
  ~Hdf5File();

  // Closes the file and renames the temporary file to the final name.
  void Commit();

  const std::string& path() const { return path_; }

  // Writing. Intermediate groups are created as needed. `units` becomes the
  // dataset's "units" attribute when non-empty ("1" for dimensionless).
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

  // Reading.
  bool Exists(const std::string& name) const;
  std::vector<std::string> List(const std::string& group) const;
  std::vector<double> ReadDoubles(const std::string& name) const;
  // Returns a row-major matrix; `rows` and `cols` receive its shape.
  std::vector<double> ReadMatrix(const std::string& name, size_t* rows, size_t* cols) const;
  std::vector<int64_t> ReadInts(const std::string& name) const;
  std::string ReadString(const std::string& name) const;
  std::vector<std::string> ReadStrings(const std::string& name) const;
  bool HasAttribute(const std::string& object, const std::string& name) const;
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
