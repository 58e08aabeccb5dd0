// `granasym study figures DIR`: the paper's figures from a study folder.
#pragma once

#include <CLI/CLI.hpp>

namespace granasym {

// Adds `figures` below the `study` subcommand.
void RegisterStudyFiguresCommand(CLI::App* study);

}  // namespace granasym
