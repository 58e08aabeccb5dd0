// The `granasym model` subcommands: element tests and asymptotic states of
// the constitutive models (run TEST.toml, asymptotes MODEL.toml).
#pragma once

#include <CLI/CLI.hpp>

namespace granasym {

void RegisterModelCommands(CLI::App& app);

}  // namespace granasym
