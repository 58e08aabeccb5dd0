// `granasym study report DIR`: the study's report, DIR/index.html and
// DIR/report.md (analysis/report.h).
#pragma once

#include <CLI/CLI.hpp>

namespace granasym {

// Adds the `report` subcommand to the `study` command.
void RegisterStudyReportCommand(CLI::App* study);

}  // namespace granasym
