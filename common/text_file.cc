#include "common/text_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"

namespace granasym {

std::string ReadTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read the file (" + std::strerror(errno) + ")");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void WriteTextFileAtomically(const std::string& path, const std::string& text) {
  std::error_code ignored;
  const std::filesystem::file_status status = std::filesystem::status(path, ignored);
  if (std::filesystem::is_directory(status)) {
    throw FileError("cannot write '" + path + "': it is a folder");
  }
  const bool in_place =
      std::filesystem::exists(status) && !std::filesystem::is_regular_file(status);
  const std::string target = in_place ? path : path + ".tmp";
  const std::string unchanged =
      in_place ? "" : "; '" + path + "' is not replaced (the partial '" + target + "' is removed)";
  std::FILE* out = std::fopen(target.c_str(), "wb");
  if (!out) {
    throw FileError("cannot write '" + path + "': " + std::strerror(errno) +
                    (in_place ? "" : " (creating '" + target + "')"));
  }
  // The first error's reason: a full disk shows in fwrite, or only when the
  // buffer is flushed, or when the file is closed.
  int error = std::fwrite(text.data(), 1, text.size(), out) == text.size() ? 0 : errno;
  if (std::fflush(out) != 0 && error == 0) error = errno;
  if (std::fclose(out) != 0 && error == 0) error = errno;
  if (error != 0) {
    if (!in_place) std::remove(target.c_str());
    throw FileError("cannot write '" + path + "': " + std::strerror(error) + unchanged);
  }
  if (!in_place && std::rename(target.c_str(), path.c_str()) != 0) {
    error = errno;
    std::remove(target.c_str());
    throw FileError("cannot rename '" + target + "' to '" + path + "': " + std::strerror(error) +
                    unchanged);
  }
}

std::string Trimmed(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const size_t last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::string TomlQuoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace granasym
