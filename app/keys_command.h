// granasym keys [KIND]: the key tables of the input files, as the parsers
// consult them (common/key_table.h).
#pragma once

#include <CLI/CLI.hpp>

namespace granasym {

void RegisterKeysCommand(CLI::App& app);

}  // namespace granasym
