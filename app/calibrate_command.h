// `granasym calibrate CONFIG.toml`: fit a constitutive model to asymptotic
// states (calibration/calibration_config.h documents the file).
#pragma once

#include <CLI/CLI.hpp>

namespace granasym {

void RegisterCalibrateCommand(CLI::App& app);

}  // namespace granasym
