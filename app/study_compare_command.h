// `granasym study compare A B [--out DIR]`: two study folders compared.
#pragma once

#include <CLI/CLI.hpp>

namespace granasym {

// Adds `compare` below the `study` subcommand.
void RegisterStudyCompareCommand(CLI::App* study);

}  // namespace granasym
