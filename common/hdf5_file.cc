#include "common/hdf5_file.h"

#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <utility>

#include "common/error.h"

namespace granasym {
namespace {

// Once per process, before any other HDF5 call: no exit handler (see the
// header: it would close again a file whose H5Fclose failed, and crash), and
// no printing of HDF5's error stack (the errors are reported here).
// The error stack's printing is set per thread in a thread-safe HDF5 (as
// Debian's is): each thread that calls HDF5 through this layer switches it
// off before its first call, or a worker's failed read prints HDF5's own
// diagnostics (some 40 lines) before this layer's message.
void InitializeHdf5() {
  static const bool initialized = [] {
    H5dont_atexit();
    return true;
  }();
  (void)initialized;
  thread_local const bool silenced = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)silenced;
}

// What HDF5's error stack says about the call that just failed.
struct Hdf5Reason {
  std::string system;     // the operating system's reason for a failed read or write
  std::string innermost;  // the most specific message
  bool checksum = false;  // a checksum did not match: the file is corrupt
  std::string Text() const { return system.empty() ? innermost : system; }
};

herr_t CollectReason(unsigned depth, const H5E_error2_t* error, void* data) {
  Hdf5Reason& reason = *static_cast<Hdf5Reason*>(data);
  const std::string description = error->desc ? error->desc : "";
  if (description.find("checksum") != std::string::npos) reason.checksum = true;
  // The POSIX driver's message: "... errno = 28, error message = 'No space left on device', ...".
  const std::string marker = "error message = '";
  const size_t at = description.find(marker);
  if (at != std::string::npos && reason.system.empty()) {
    const size_t start = at + marker.size();
    reason.system = description.substr(start, description.find('\'', start) - start);
  }
  if (depth == 0) reason.innermost = description;
  return 0;
}

Hdf5Reason LastReason() {
  Hdf5Reason reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, CollectReason, &reason);
  return reason;
}

// A failed write: the final file is not replaced and the temporary file is
// removed (by ~Hdf5File, while this exception unwinds).
[[noreturn]] void FailWrite(const std::string& call, const std::string& file,
                            const std::string& object) {
  const std::string reason = LastReason().Text();
  throw FileError(fmt::format(
      "cannot write '{}': HDF5 call {} failed for '{}' ({}); '{}' is not replaced (the partial "
      "'{}.tmp' is removed)",
      file, call, object, reason.empty() ? "HDF5 gives no reason" : reason, file, file));
}

// A failed read; `what` names the object ("dataset '/series/p_kpa'").
[[noreturn]] void FailRead(const std::string& call, const std::string& file,
                           const std::string& what) {
  const Hdf5Reason reason = LastReason();
  if (reason.checksum) {
    throw InputError(fmt::format("{}: {} fails its checksum (the file is corrupt)", file, what));
  }
  throw RuntimeError(fmt::format("HDF5 call {} failed for {} in file '{}'{}", call, what, file,
                                 reason.Text().empty() ? "" : ": " + reason.Text()));
}

std::string Dataset(const std::string& name) { return "dataset '" + name + "'"; }
std::string Object(const std::string& name) { return "object '" + name + "'"; }
std::string Attribute(const std::string& object, const std::string& name) {
  return "attribute '" + name + "' of '" + object + "'";
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

// The largest chunk: the whole dataset up to this size (most are one chunk),
// else slabs of whole rows; it stays within HDF5's default chunk cache (1 MiB).
constexpr hsize_t kMaxChunkBytes = hsize_t{1} << 20;

// Chunked layout with a Fletcher32 checksum per chunk. An empty dataset stays
// contiguous: it has no data to check (a chunk cannot be empty), and its shape
// is in the checksummed object header.
Handle DatasetProperties(const std::vector<hsize_t>& dims, size_t element_bytes,
                         const std::string& file, const std::string& name) {
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (!dcpl.valid()) FailWrite("H5Pcreate(dataset)", file, name);
  hsize_t total = 1, row_bytes = element_bytes;
  for (size_t k = 0; k < dims.size(); ++k) {
    total *= dims[k];
    if (k > 0) row_bytes *= dims[k];
  }
  if (dims.empty() || total == 0) return dcpl;
  // Rows per chunk: as even a split as the limit allows (a partial last chunk
  // takes the space of a full one).
  const hsize_t max_rows = std::max<hsize_t>(kMaxChunkBytes / row_bytes, 1);
  const hsize_t chunks = (dims[0] + max_rows - 1) / max_rows;
  std::vector<hsize_t> chunk = dims;
  chunk[0] = (dims[0] + chunks - 1) / chunks;
  if (H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()) < 0) {
    FailWrite("H5Pset_chunk", file, name);
  }
  if (H5Pset_fletcher32(dcpl.get()) < 0) FailWrite("H5Pset_fletcher32", file, name);
  return dcpl;
}

void WriteUnits(hid_t dataset, const std::string& units, const std::string& file,
                const std::string& name) {
  if (units.empty()) return;
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle type = StringType();
  Handle attribute(H5Acreate2(dataset, "units", type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose);
  if (!attribute.valid()) FailWrite("H5Acreate2(units)", file, name);
  const char* text = units.c_str();
  if (H5Awrite(attribute.get(), type.get(), &text) < 0) FailWrite("H5Awrite(units)", file, name);
}

template <typename T>
void WriteArray(hid_t file_id, const std::string& file, const std::string& name, hid_t mem_type,
                hid_t file_type, const T* data, const std::vector<hsize_t>& dims,
                const std::string& units) {
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  if (!space.valid()) FailWrite("H5Screate_simple", file, name);
  Handle lcpl = CreateLinkProperties();
  Handle dcpl = DatasetProperties(dims, sizeof(T), file, name);
  Handle dataset(H5Dcreate2(file_id, name.c_str(), file_type, space.get(), lcpl.get(), dcpl.get(),
                            H5P_DEFAULT),
                 H5Dclose);
  if (!dataset.valid()) FailWrite("H5Dcreate2", file, name);
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  if (total > 0 && H5Dwrite(dataset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    FailWrite("H5Dwrite", file, name);
  }
  WriteUnits(dataset.get(), units, file, name);
}

template <typename T>
std::vector<T> ReadArray(hid_t file_id, const std::string& file, const std::string& name,
                         hid_t mem_type, std::vector<hsize_t>* dims_out) {
  Handle dataset(H5Dopen2(file_id, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) FailRead("H5Dopen2", file, Dataset(name));
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  if (!space.valid()) FailRead("H5Dget_space", file, Dataset(name));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) FailRead("H5Sget_simple_extent_ndims", file, Dataset(name));
  std::vector<hsize_t> dims(static_cast<size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  std::vector<T> values(total);
  if (total > 0 &&
      H5Dread(dataset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    FailRead("H5Dread", file, Dataset(name));
  }
  if (dims_out) *dims_out = dims;
  return values;
}

Handle OpenObject(hid_t file_id, const std::string& file, const std::string& object) {
  Handle handle(H5Oopen(file_id, object.c_str(), H5P_DEFAULT), H5Oclose);
  if (!handle.valid()) FailRead("H5Oopen", file, Object(object));
  return handle;
}

// Creates with the 1.10 format: checksummed metadata and chunk indexes.
Handle CreateFileAccessProperties(const std::string& path) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  if (!fapl.valid() || H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V110, H5F_LIBVER_V110) < 0) {
    FailWrite("H5Pset_libver_bounds", path, "/");
  }
  return fapl;
}

}  // namespace

Hdf5File::Hdf5File(int64_t id, std::string path, std::string temporary_path)
    : id_(id), path_(std::move(path)), temporary_path_(std::move(temporary_path)) {}

Hdf5File Hdf5File::CreateAtomic(const std::string& path) {
  InitializeHdf5();
  // The temporary file is renamed over the final name: never over a folder
  // or a device (as root, /dev/full would become a plain file).
  std::error_code ignored;
  const std::filesystem::file_status status = std::filesystem::status(path, ignored);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    throw InputError("cannot write the HDF5 file '" + path +
                     "': it exists and is not a regular file (a folder or a device); an HDF5 "
                     "file is written beside its final name and renamed to it");
  }
  const std::string temporary = path + ".tmp";
  const Handle fapl = CreateFileAccessProperties(path);
  const hid_t id = H5Fcreate(temporary.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (id < 0) {
    const std::string reason = LastReason().Text();
    std::remove(temporary.c_str());
    throw FileError("cannot write '" + path + "': H5Fcreate of '" + temporary + "' failed (" +
                    (reason.empty() ? "HDF5 gives no reason" : reason) +
                    "): check that the folder exists, is writable and has space; '" + path +
                    "' is not replaced");
  }
  return Hdf5File(id, path, temporary);
}

Hdf5File Hdf5File::OpenRead(const std::string& path) {
  InitializeHdf5();
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) {
    if (LastReason().checksum) {
      throw InputError("cannot open HDF5 file '" + path +
                       "': its superblock fails its checksum (the file is corrupt)");
    }
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

// On the error paths only (the file is abandoned): a close that fails is not
// retried, and the ID is never used again.
void Hdf5File::Close() {
  if (id_ >= 0) H5Fclose(std::exchange(id_, -1));
}

void Hdf5File::Commit() {
  InitializeHdf5();
  GRANASYM_CHECK(!temporary_path_.empty()) << "Commit() on a file opened for reading";
  if (H5Fflush(id_, H5F_SCOPE_GLOBAL) < 0) FailWrite("H5Fflush", path_, "/");
  // The last metadata are written on close: a failed close is a failed write.
  if (H5Fclose(std::exchange(id_, -1)) < 0) FailWrite("H5Fclose", path_, "/");
  if (std::rename(temporary_path_.c_str(), path_.c_str()) != 0) {
    throw FileError("cannot rename '" + temporary_path_ + "' to '" + path_ +
                    "': " + std::strerror(errno) + "; '" + path_ + "' is not replaced");
  }
  temporary_path_.clear();
}

void Hdf5File::WriteDoubles(const std::string& name, const std::vector<double>& values,
                            const std::string& units) {
  InitializeHdf5();
  WriteArray(id_, path_, name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, values.data(), {values.size()},
             units);
}

void Hdf5File::WriteMatrix(const std::string& name, const std::vector<double>& values, size_t rows,
                           size_t cols, const std::string& units) {
  InitializeHdf5();
  GRANASYM_CHECK(values.size() == rows * cols)
      << name << ": " << values.size() << " values for " << rows << "x" << cols;
  WriteArray(id_, path_, name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, values.data(), {rows, cols},
             units);
}

void Hdf5File::WriteInts(const std::string& name, const std::vector<int64_t>& values,
                         const std::string& units) {
  InitializeHdf5();
  WriteArray(id_, path_, name, H5T_NATIVE_INT64, H5T_STD_I64LE, values.data(), {values.size()},
             units);
}

void Hdf5File::WriteString(const std::string& name, const std::string& value) {
  InitializeHdf5();
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle type = StringType();
  Handle lcpl = CreateLinkProperties();
  Handle dataset(
      H5Dcreate2(id_, name.c_str(), type.get(), space.get(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose);
  if (!dataset.valid()) FailWrite("H5Dcreate2", path_, name);
  const char* text = value.c_str();
  if (H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &text) < 0) {
    FailWrite("H5Dwrite", path_, name);
  }
}

void Hdf5File::WriteStrings(const std::string& name, const std::vector<std::string>& values) {
  InitializeHdf5();
  const hsize_t size = values.size();
  Handle space(H5Screate_simple(1, &size, nullptr), H5Sclose);
  Handle type = StringType();
  Handle lcpl = CreateLinkProperties();
  Handle dataset(
      H5Dcreate2(id_, name.c_str(), type.get(), space.get(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose);
  if (!dataset.valid()) FailWrite("H5Dcreate2", path_, name);
  std::vector<const char*> texts;
  for (const std::string& value : values) texts.push_back(value.c_str());
  if (!texts.empty() &&
      H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, texts.data()) < 0) {
    FailWrite("H5Dwrite", path_, name);
  }
}

void Hdf5File::CreateGroup(const std::string& name) {
  InitializeHdf5();
  if (Exists(name)) return;
  Handle lcpl = CreateLinkProperties();
  Handle group(H5Gcreate2(id_, name.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!group.valid()) FailWrite("H5Gcreate2", path_, name);
}

namespace {
template <typename T>
void WriteScalarAttribute(hid_t file_id, const std::string& file, const std::string& object,
                          const std::string& name, hid_t type, const T* value) {
  Handle target(H5Oopen(file_id, object.c_str(), H5P_DEFAULT), H5Oclose);
  if (!target.valid()) FailWrite("H5Oopen", file, object);
  if (H5Aexists(target.get(), name.c_str()) > 0) H5Adelete(target.get(), name.c_str());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attribute(
      H5Acreate2(target.get(), name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  if (!attribute.valid()) FailWrite("H5Acreate2(" + name + ")", file, object);
  if (H5Awrite(attribute.get(), type, value) < 0) FailWrite("H5Awrite(" + name + ")", file, object);
}
}  // namespace

void Hdf5File::SetAttribute(const std::string& object, const std::string& name, double value) {
  InitializeHdf5();
  WriteScalarAttribute(id_, path_, object, name, H5T_NATIVE_DOUBLE, &value);
}

void Hdf5File::SetAttribute(const std::string& object, const std::string& name, int64_t value) {
  InitializeHdf5();
  WriteScalarAttribute(id_, path_, object, name, H5T_NATIVE_INT64, &value);
}

void Hdf5File::SetAttribute(const std::string& object, const std::string& name,
                            const std::string& value) {
  InitializeHdf5();
  Handle type = StringType();
  const char* text = value.c_str();
  WriteScalarAttribute(id_, path_, object, name, type.get(), &text);
}

bool Hdf5File::Exists(const std::string& name) const {
  InitializeHdf5();
  if (name == "/" || name.empty()) return true;
  // Check each prefix: H5Lexists fails on a missing intermediate group.
  size_t position = name[0] == '/' ? 1 : 0;
  while (true) {
    const size_t slash = name.find('/', position);
    const std::string prefix = name.substr(0, slash);
    const htri_t exists = H5Lexists(id_, prefix.c_str(), H5P_DEFAULT);
    // It also fails below a dataset ("/a/b" of a dataset "/a"): no such
    // object, unless a checksum failed on the way.
    if (exists < 0 && LastReason().checksum) FailRead("H5Lexists", path_, Object(prefix));
    if (exists <= 0) return false;
    if (slash == std::string::npos) return true;
    position = slash + 1;
  }
}

std::vector<std::string> Hdf5File::List(const std::string& group) const {
  InitializeHdf5();
  Handle handle(H5Gopen2(id_, group.c_str(), H5P_DEFAULT), H5Gclose);
  if (!handle.valid()) FailRead("H5Gopen2", path_, Object(group));
  H5G_info_t info;
  if (H5Gget_info(handle.get(), &info) < 0) FailRead("H5Gget_info", path_, Object(group));
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t size = H5Lget_name_by_idx(handle.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i,
                                            nullptr, 0, H5P_DEFAULT);
    if (size < 0) FailRead("H5Lget_name_by_idx", path_, Object(group));
    std::string name(static_cast<size_t>(size), '\0');
    if (H5Lget_name_by_idx(handle.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(),
                           static_cast<size_t>(size) + 1, H5P_DEFAULT) < 0) {
      FailRead("H5Lget_name_by_idx", path_, Object(group));
    }
    names.push_back(name);
  }
  return names;
}

std::vector<double> Hdf5File::ReadDoubles(const std::string& name) const {
  InitializeHdf5();
  return ReadArray<double>(id_, path_, name, H5T_NATIVE_DOUBLE, nullptr);
}

std::vector<double> Hdf5File::ReadMatrix(const std::string& name, size_t* rows,
                                         size_t* cols) const {
  InitializeHdf5();
  std::vector<hsize_t> dims;
  std::vector<double> values = ReadArray<double>(id_, path_, name, H5T_NATIVE_DOUBLE, &dims);
  if (dims.size() != 2) {
    throw InputError(path_ + ": dataset '" + name + "' is not a matrix");
  }
  *rows = dims[0];
  *cols = dims[1];
  return values;
}

std::vector<int64_t> Hdf5File::ReadInts(const std::string& name) const {
  InitializeHdf5();
  return ReadArray<int64_t>(id_, path_, name, H5T_NATIVE_INT64, nullptr);
}

std::string Hdf5File::ReadString(const std::string& name) const {
  InitializeHdf5();
  Handle dataset(H5Dopen2(id_, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) FailRead("H5Dopen2", path_, Dataset(name));
  Handle type = StringType();
  char* text = nullptr;
  if (H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &text) < 0) {
    FailRead("H5Dread", path_, Dataset(name));
  }
  std::string value = text ? text : "";
  H5free_memory(text);
  return value;
}

namespace {

// H5Lvisit: the paths of every dataset below the root.
herr_t CollectDataset(hid_t group, const char* name, const H5L_info_t* info, void* data) {
  if (info->type != H5L_TYPE_HARD) return 0;
  const hid_t object = H5Oopen(group, name, H5P_DEFAULT);
  if (object < 0) return 0;  // reported when read
  if (H5Iget_type(object) == H5I_DATASET) {
    static_cast<std::vector<std::string>*>(data)->push_back(std::string("/") + name);
  }
  H5Oclose(object);
  return 0;
}

}  // namespace

void Hdf5File::CheckData() const {
  InitializeHdf5();
  std::vector<std::string> datasets;
  if (H5Lvisit(id_, H5_INDEX_NAME, H5_ITER_INC, CollectDataset, &datasets) < 0) {
    FailRead("H5Lvisit", path_, "its groups");
  }
  for (const std::string& name : datasets) {
    Handle dataset(H5Dopen2(id_, name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!dataset.valid()) FailRead("H5Dopen2", path_, Dataset(name));
    Handle file_type(H5Dget_type(dataset.get()), H5Tclose);
    if (!file_type.valid()) FailRead("H5Dget_type", path_, Dataset(name));
    // Variable-length strings live in the global heap, which has no checksum.
    if (H5Tget_class(file_type.get()) == H5T_STRING || H5Tis_variable_str(file_type.get()) > 0) {
      continue;
    }
    Handle type(H5Tget_native_type(file_type.get(), H5T_DIR_ASCEND), H5Tclose);
    if (!type.valid()) FailRead("H5Tget_native_type", path_, Dataset(name));
    Handle space(H5Dget_space(dataset.get()), H5Sclose);
    if (!space.valid()) FailRead("H5Dget_space", path_, Dataset(name));
    const hssize_t count = H5Sget_simple_extent_npoints(space.get());
    if (count < 0) FailRead("H5Sget_simple_extent_npoints", path_, Dataset(name));
    if (count == 0) continue;
    std::vector<unsigned char> buffer(static_cast<size_t>(count) * H5Tget_size(type.get()));
    if (H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0) {
      FailRead("H5Dread", path_, Dataset(name));
    }
  }
}

std::vector<std::string> Hdf5File::ReadStrings(const std::string& name) const {
  InitializeHdf5();
  Handle dataset(H5Dopen2(id_, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) FailRead("H5Dopen2", path_, Dataset(name));
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) FailRead("H5Sget_simple_extent_npoints", path_, Dataset(name));
  std::vector<char*> texts(static_cast<size_t>(count), nullptr);
  Handle type = StringType();
  if (count > 0 &&
      H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, texts.data()) < 0) {
    FailRead("H5Dread", path_, Dataset(name));
  }
  std::vector<std::string> values;
  for (char* text : texts) {
    values.emplace_back(text ? text : "");
    H5free_memory(text);
  }
  return values;
}

bool Hdf5File::HasAttribute(const std::string& object, const std::string& name) const {
  InitializeHdf5();
  if (!Exists(object)) return false;
  Handle target = OpenObject(id_, path_, object);
  const htri_t exists = H5Aexists(target.get(), name.c_str());
  if (exists < 0) FailRead("H5Aexists", path_, Attribute(object, name));
  return exists > 0;
}

namespace {
template <typename T>
T ReadScalarAttribute(hid_t file_id, const std::string& file, const std::string& object,
                      const std::string& name, hid_t type) {
  Handle target = OpenObject(file_id, file, object);
  Handle attribute(H5Aopen(target.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!attribute.valid()) FailRead("H5Aopen", file, Attribute(object, name));
  T value{};
  if (H5Aread(attribute.get(), type, &value) < 0) {
    FailRead("H5Aread", file, Attribute(object, name));
  }
  return value;
}
}  // namespace

double Hdf5File::ReadDoubleAttribute(const std::string& object, const std::string& name) const {
  InitializeHdf5();
  return ReadScalarAttribute<double>(id_, path_, object, name, H5T_NATIVE_DOUBLE);
}

int64_t Hdf5File::ReadIntAttribute(const std::string& object, const std::string& name) const {
  InitializeHdf5();
  return ReadScalarAttribute<int64_t>(id_, path_, object, name, H5T_NATIVE_INT64);
}

std::string Hdf5File::ReadStringAttribute(const std::string& object,
                                          const std::string& name) const {
  InitializeHdf5();
  Handle type = StringType();
  char* text = ReadScalarAttribute<char*>(id_, path_, object, name, type.get());
  std::string value = text ? text : "";
  H5free_memory(text);
  return value;
}

}  // namespace granasym
