// The `granasym study` subcommands: run a programme (in parallel, sharded),
// show a study folder's status, merge the folders of shards.
#pragma once

#include <CLI/CLI.hpp>

namespace granasym {

void RegisterStudyCommands(CLI::App& app);

}  // namespace granasym
