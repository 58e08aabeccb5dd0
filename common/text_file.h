// Whole text files: read one, or write one atomically (a temporary file in
// the same folder, flushed, then renamed over the target), so that a crash or
// a full disk never leaves a truncated file under the final name.
#pragma once

#include <string>

namespace granasym {

// The file's bytes; InputError naming the file when it cannot be read.
std::string ReadTextFile(const std::string& path);
// FileError naming the file and the system's reason when it cannot be
// written or renamed; the temporary `path + ".tmp"` is then removed and a file
// under `path` is left as it was. A `path` that exists and is not a regular
// file (a device such as /dev/stdout or /dev/full, a pipe) is written in
// place: renaming a file over it would replace it.
void WriteTextFileAtomically(const std::string& path, const std::string& text);
// `text` as a TOML basic string: in double quotes, with '"', '\\' and line
// breaks escaped (for the small TOML records a program writes).
std::string TomlQuoted(const std::string& text);

// `text` without leading and trailing blanks (spaces, tabs, carriage returns).
std::string Trimmed(const std::string& text);

}  // namespace granasym
