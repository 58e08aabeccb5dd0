#include "common/output_path.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "common/error.h"

namespace granasym {
namespace fs = std::filesystem;

namespace {

fs::path Resolved(const std::string& path) {
  std::error_code error;
  const fs::path resolved = fs::weakly_canonical(fs::absolute(path, error), error);
  return error ? fs::absolute(path).lexically_normal() : resolved;
}

std::string Quoted(const NamedPath& p) { return p.what + " '" + p.path + "'"; }

// The folder an output file goes to: it exists, is a folder and is writable.
void CheckFolderOf(const NamedPath& output) {
  fs::path folder = fs::path(output.path).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code error;
  const fs::file_status status = fs::status(folder, error);
  if (!fs::exists(status)) {
    throw InputError(Quoted(output) + ": the folder '" + folder.string() +
                     "' does not exist: create it first or choose another path");
  }
  if (!fs::is_directory(status)) {
    throw InputError(Quoted(output) + ": '" + folder.string() + "' is not a folder");
  }
  if (::access(folder.c_str(), W_OK | X_OK) != 0) {
    throw InputError(Quoted(output) + ": the folder '" + folder.string() + "' cannot be written (" +
                     std::strerror(errno) + ")");
  }
}

}  // namespace

bool SameFile(const std::string& a, const std::string& b) {
  std::error_code error;
  if (fs::exists(a, error) && fs::exists(b, error) && fs::equivalent(a, b, error)) return true;
  return Resolved(a) == Resolved(b);
}

void CheckOutputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
  for (size_t k = 0; k < outputs.size(); ++k) {
    const NamedPath& output = outputs[k];
    if (output.path.empty()) continue;
    for (const NamedPath& input : inputs) {
      if (!input.path.empty() && SameFile(output.path, input.path)) {
        throw InputError(Quoted(output) + " names the same file as " + Quoted(input) +
                         ": no output overwrites an input; choose another output path");
      }
    }
    for (size_t j = 0; j < k; ++j) {
      if (!outputs[j].path.empty() && SameFile(output.path, outputs[j].path)) {
        throw InputError(Quoted(output) + " and " + Quoted(outputs[j]) +
                         " are the same file: give each output its own path");
      }
    }
    std::error_code error;
    if (fs::is_directory(output.path, error)) {
      throw InputError(Quoted(output) + " is a folder: give a file name (e.g. '" +
                       (fs::path(output.path) / "result.h5").string() + "')");
    }
    CheckFolderOf(output);
  }
}

void CheckOutputFolder(const NamedPath& folder, const std::vector<NamedPath>& inputs) {
  std::error_code error;
  if (fs::exists(folder.path, error)) {
    if (!fs::is_directory(folder.path, error)) {
      throw InputError(Quoted(folder) + " exists and is not a folder: give a folder path");
    }
    if (::access(folder.path.c_str(), W_OK | X_OK) != 0) {
      throw InputError(Quoted(folder) + " cannot be written (" + std::strerror(errno) + ")");
    }
  } else {
    CheckFolderOf(folder);
  }
  const fs::path root = Resolved(folder.path);
  for (const NamedPath& input : inputs) {
    if (input.path.empty()) continue;
    const fs::path file = Resolved(input.path);
    if (file == root) {
      throw InputError(Quoted(folder) + " names the same path as " + Quoted(input) +
                       ": no output overwrites an input");
    }
  }
}

}  // namespace granasym
