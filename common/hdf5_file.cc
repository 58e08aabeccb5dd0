#include "common/hdf5_file.h"

#include <hdf5.h>

#include <cstdio>
#include <utility>

#include "common/error.h"

namespace granasym {
namespace {

// Silences HDF5's own error stack printing once; we report errors ourselves.
void QuietHdf5() {
  static const bool quiet = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)quiet;
}

[[noreturn]] void Fail(const std::string& call, const std::string& file,
                       const std::string& object) {
  throw RuntimeError("HDF5 call " + call + " failed for '" + object + "' in file '" + file + "'");
}

// Owns one hid_t and closes it with the matching function.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = -1; }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer closer_;
};

Handle CreateLinkProperties() {
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  return lcpl;
}

Handle StringType() {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  return type;
}

void WriteUnits(hid_t dataset, const std::string& units, const std::string& file,
                const std::string& name) {
  if (units.empty()) return;
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle type = StringType();
  Handle attribute(H5Acreate2(dataset, "units", type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose);
  if (!attribute.valid()) Fail("H5Acreate2(units)", file, name);
  const char* text = units.c_str();
  if (H5Awrite(attribute.get(), type.get(), &text) < 0) Fail("H5Awrite(units)", file, name);
}

template <typename T>
void WriteArray(hid_t file_id, const std::string& file, const std::string& name, hid_t mem_type,
                hid_t file_type, const T* data, const std::vector<hsize_t>& dims,
                const std::string& units) {
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  if (!space.valid()) Fail("H5Screate_simple", file, name);
  Handle lcpl = CreateLinkProperties();
  Handle dataset(H5Dcreate2(file_id, name.c_str(), file_type, space.get(), lcpl.get(), H5P_DEFAULT,
                            H5P_DEFAULT),
                 H5Dclose);
  if (!dataset.valid()) Fail("H5Dcreate2", file, name);
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  if (total > 0 && H5Dwrite(dataset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    Fail("H5Dwrite", file, name);
  }
  WriteUnits(dataset.get(), units, file, name);
}

template <typename T>
std::vector<T> ReadArray(hid_t file_id, const std::string& file, const std::string& name,
                         hid_t mem_type, std::vector<hsize_t>* dims_out) {
  Handle dataset(H5Dopen2(file_id, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) Fail("H5Dopen2", file, name);
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) Fail("H5Sget_simple_extent_ndims", file, name);
  std::vector<hsize_t> dims(static_cast<size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  std::vector<T> values(total);
  if (total > 0 &&
      H5Dread(dataset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    Fail("H5Dread", file, name);
  }
  if (dims_out) *dims_out = dims;
  return values;
}

Handle OpenObject(hid_t file_id, const std::string& file, const std::string& object) {
  Handle handle(H5Oopen(file_id, object.c_str(), H5P_DEFAULT), H5Oclose);
  if (!handle.valid()) Fail("H5Oopen", file, object);
  return handle;
}

}  // namespace

Hdf5File::Hdf5File(int64_t id, std::string path, std::string temporary_path)
    : id_(id), path_(std::move(path)), temporary_path_(std::move(temporary_path)) {}

Hdf5File Hdf5File::CreateAtomic(const std::string& path) {
  QuietHdf5();
  const std::string temporary = path + ".tmp";
  const hid_t id = H5Fcreate(temporary.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (id < 0) {
    throw RuntimeError("cannot create HDF5 file '" + temporary +
                       "' (H5Fcreate failed): check that the folder exists and is writable");
  }
  return Hdf5File(id, path, temporary);
}

Hdf5File Hdf5File::OpenRead(const std::string& path) {
  QuietHdf5();
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) {
    throw InputError("cannot open HDF5 file '" + path +
                     "' (H5Fopen failed): it does not exist or is not an HDF5 file");
  }
  return Hdf5File(id, path, "");
}

Hdf5File::Hdf5File(Hdf5File&& other) noexcept
    : id_(std::exchange(other.id_, -1)),
      path_(std::move(other.path_)),
      temporary_path_(std::move(other.temporary_path_)) {}

Hdf5File& Hdf5File::operator=(Hdf5File&& other) noexcept {
  if (this != &other) {
    Close();
    if (!temporary_path_.empty()) std::remove(temporary_path_.c_str());
    id_ = std::exchange(other.id_, -1);
    path_ = std::move(other.path_);
    temporary_path_ = std::move(other.temporary_path_);
  }
  return *this;
}

Hdf5File::~Hdf5File() {
  Close();
  if (!temporary_path_.empty()) std::remove(temporary_path_.c_str());
}

void Hdf5File::Close() {
  if (id_ >= 0) {
    H5Fclose(id_);
    id_ = -1;
  }
}

void Hdf5File::Commit() {
  GRANASYM_CHECK(!temporary_path_.empty()) << "Commit() on a file opened for reading";
  if (H5Fflush(id_, H5F_SCOPE_GLOBAL) < 0) Fail("H5Fflush", temporary_path_, "/");
  Close();
  if (std::rename(temporary_path_.c_str(), path_.c_str()) != 0) {
    throw RuntimeError("cannot rename '" + temporary_path_ + "' to '" + path_ + "'");
  }
  temporary_path_.clear();
}

void Hdf5File::WriteDoubles(const std::string& name, const std::vector<double>& values,
                            const std::string& units) {
  WriteArray(id_, path_, name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, values.data(), {values.size()},
             units);
}

void Hdf5File::WriteMatrix(const std::string& name, const std::vector<double>& values, size_t rows,
                           size_t cols, const std::string& units) {
  GRANASYM_CHECK(values.size() == rows * cols)
      << name << ": " << values.size() << " values for " << rows << "x" << cols;
  WriteArray(id_, path_, name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, values.data(), {rows, cols},
             units);
}

void Hdf5File::WriteInts(const std::string& name, const std::vector<int64_t>& values,
                         const std::string& units) {
  WriteArray(id_, path_, name, H5T_NATIVE_INT64, H5T_STD_I64LE, values.data(), {values.size()},
             units);
}

void Hdf5File::WriteString(const std::string& name, const std::string& value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle type = StringType();
  Handle lcpl = CreateLinkProperties();
  Handle dataset(
      H5Dcreate2(id_, name.c_str(), type.get(), space.get(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose);
  if (!dataset.valid()) Fail("H5Dcreate2", path_, name);
  const char* text = value.c_str();
  if (H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &text) < 0) {
    Fail("H5Dwrite", path_, name);
  }
}

void Hdf5File::WriteStrings(const std::string& name, const std::vector<std::string>& values) {
  const hsize_t size = values.size();
  Handle space(H5Screate_simple(1, &size, nullptr), H5Sclose);
  Handle type = StringType();
  Handle lcpl = CreateLinkProperties();
  Handle dataset(
      H5Dcreate2(id_, name.c_str(), type.get(), space.get(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose);
  if (!dataset.valid()) Fail("H5Dcreate2", path_, name);
  std::vector<const char*> texts;
  for (const std::string& value : values) texts.push_back(value.c_str());
  if (!texts.empty() &&
      H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, texts.data()) < 0) {
    Fail("H5Dwrite", path_, name);
  }
}

void Hdf5File::CreateGroup(const std::string& name) {
  if (Exists(name)) return;
  Handle lcpl = CreateLinkProperties();
  Handle group(H5Gcreate2(id_, name.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!group.valid()) Fail("H5Gcreate2", path_, name);
}

namespace {
template <typename T>
void WriteScalarAttribute(hid_t file_id, const std::string& file, const std::string& object,
                          const std::string& name, hid_t type, const T* value) {
  Handle target = OpenObject(file_id, file, object);
  if (H5Aexists(target.get(), name.c_str()) > 0) H5Adelete(target.get(), name.c_str());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attribute(
      H5Acreate2(target.get(), name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  if (!attribute.valid()) Fail("H5Acreate2(" + name + ")", file, object);
  if (H5Awrite(attribute.get(), type, value) < 0) Fail("H5Awrite(" + name + ")", file, object);
}
}  // namespace

void Hdf5File::SetAttribute(const std::string& object, const std::string& name, double value) {
  WriteScalarAttribute(id_, path_, object, name, H5T_NATIVE_DOUBLE, &value);
}

void Hdf5File::SetAttribute(const std::string& object, const std::string& name, int64_t value) {
  WriteScalarAttribute(id_, path_, object, name, H5T_NATIVE_INT64, &value);
}

void Hdf5File::SetAttribute(const std::string& object, const std::string& name,
                            const std::string& value) {
  Handle type = StringType();
  const char* text = value.c_str();
  WriteScalarAttribute(id_, path_, object, name, type.get(), &text);
}

bool Hdf5File::Exists(const std::string& name) const {
  if (name == "/" || name.empty()) return true;
  // Check each prefix: H5Lexists fails on a missing intermediate group.
  size_t position = name[0] == '/' ? 1 : 0;
  while (true) {
    const size_t slash = name.find('/', position);
    const std::string prefix = name.substr(0, slash);
    if (H5Lexists(id_, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) return true;
    position = slash + 1;
  }
}

std::vector<std::string> Hdf5File::List(const std::string& group) const {
  Handle handle(H5Gopen2(id_, group.c_str(), H5P_DEFAULT), H5Gclose);
  if (!handle.valid()) Fail("H5Gopen2", path_, group);
  H5G_info_t info;
  if (H5Gget_info(handle.get(), &info) < 0) Fail("H5Gget_info", path_, group);
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t size = H5Lget_name_by_idx(handle.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i,
                                            nullptr, 0, H5P_DEFAULT);
    if (size < 0) Fail("H5Lget_name_by_idx", path_, group);
    std::string name(static_cast<size_t>(size), '\0');
    H5Lget_name_by_idx(handle.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(),
                       static_cast<size_t>(size) + 1, H5P_DEFAULT);
    names.push_back(name);
  }
  return names;
}

std::vector<double> Hdf5File::ReadDoubles(const std::string& name) const {
  return ReadArray<double>(id_, path_, name, H5T_NATIVE_DOUBLE, nullptr);
}

std::vector<double> Hdf5File::ReadMatrix(const std::string& name, size_t* rows,
                                         size_t* cols) const {
  std::vector<hsize_t> dims;
  std::vector<double> values = ReadArray<double>(id_, path_, name, H5T_NATIVE_DOUBLE, &dims);
  if (dims.size() != 2) {
    throw RuntimeError("dataset '" + name + "' in '" + path_ + "' is not a matrix");
  }
  *rows = dims[0];
  *cols = dims[1];
  return values;
}

std::vector<int64_t> Hdf5File::ReadInts(const std::string& name) const {
  return ReadArray<int64_t>(id_, path_, name, H5T_NATIVE_INT64, nullptr);
}

std::string Hdf5File::ReadString(const std::string& name) const {
  Handle dataset(H5Dopen2(id_, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) Fail("H5Dopen2", path_, name);
  Handle type = StringType();
  char* text = nullptr;
  if (H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &text) < 0) {
    Fail("H5Dread", path_, name);
  }
  std::string value = text ? text : "";
  H5free_memory(text);
  return value;
}

std::vector<std::string> Hdf5File::ReadStrings(const std::string& name) const {
  Handle dataset(H5Dopen2(id_, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) Fail("H5Dopen2", path_, name);
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) Fail("H5Sget_simple_extent_npoints", path_, name);
  std::vector<char*> texts(static_cast<size_t>(count), nullptr);
  Handle type = StringType();
  if (count > 0 &&
      H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, texts.data()) < 0) {
    Fail("H5Dread", path_, name);
  }
  std::vector<std::string> values;
  for (char* text : texts) {
    values.emplace_back(text ? text : "");
    H5free_memory(text);
  }
  return values;
}

bool Hdf5File::HasAttribute(const std::string& object, const std::string& name) const {
  if (!Exists(object)) return false;
  Handle target = OpenObject(id_, path_, object);
  return H5Aexists(target.get(), name.c_str()) > 0;
}

namespace {
template <typename T>
T ReadScalarAttribute(hid_t file_id, const std::string& file, const std::string& object,
                      const std::string& name, hid_t type) {
  Handle target = OpenObject(file_id, file, object);
  Handle attribute(H5Aopen(target.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!attribute.valid()) Fail("H5Aopen(" + name + ")", file, object);
  T value{};
  if (H5Aread(attribute.get(), type, &value) < 0) Fail("H5Aread(" + name + ")", file, object);
  return value;
}
}  // namespace

double Hdf5File::ReadDoubleAttribute(const std::string& object, const std::string& name) const {
  return ReadScalarAttribute<double>(id_, path_, object, name, H5T_NATIVE_DOUBLE);
}

int64_t Hdf5File::ReadIntAttribute(const std::string& object, const std::string& name) const {
  return ReadScalarAttribute<int64_t>(id_, path_, object, name, H5T_NATIVE_INT64);
}

std::string Hdf5File::ReadStringAttribute(const std::string& object,
                                          const std::string& name) const {
  Handle type = StringType();
  char* text = ReadScalarAttribute<char*>(id_, path_, object, name, type.get());
  std::string value = text ? text : "";
  H5free_memory(text);
  return value;
}

}  // namespace granasym
