// The stage types a scene file can name, and the parser of a [[stage]] table.
#pragma once

#include <cstddef>
#include <string>

#include "dem/stage.h"

namespace granasym::dem {

// Reads one [[stage]] table (index k for the default name "stage<k+1>").
Stage ParseStage(const ConfigTable& table, size_t index);
// "strain_path, triaxial or rest": the types the parser knows.
std::string StageTypeNames();

}  // namespace granasym::dem
