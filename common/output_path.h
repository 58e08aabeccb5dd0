// Checks of output paths before any work starts: an output never overwrites
// an input, lies in a folder that exists and can be written, and is not a
// folder itself. Commands call these before their first step, so that no
// result is lost to a path that could not have been written.
#pragma once

#include <string>
#include <vector>

namespace granasym {

// A file a command reads or writes, with the flag or key that names it.
struct NamedPath {
  std::string what;  // e.g. "--out", "scene file", "[sample] packing"
  std::string path;
};

// True when `a` and `b` name the same file: the same path after resolving
// '.', '..' and links, or (both existing) the same file through a hard link.
bool SameFile(const std::string& a, const std::string& b);

// Throws InputError when an output is one of the inputs, two outputs are one
// file, an output is an existing folder, or its folder is missing or not
// writable. Empty paths are skipped (optional outputs not given).
void CheckOutputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs);

// Same for an output folder (a study): it may exist (a second run reuses it)
// but must be a writable folder, or be creatable in a writable folder, and
// must not be one of the inputs.
void CheckOutputFolder(const NamedPath& folder, const std::vector<NamedPath>& inputs);

}  // namespace granasym
