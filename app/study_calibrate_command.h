// `granasym study calibrate DIR [--models ...]`: calibrate each model against
// the study's state table (DIR/asymptotic_states.h5) and write, per model,
// DIR/calibration/<model>/: calibration.toml (the generated input, to edit
// and rerun with `granasym calibrate`), calibration.h5, summary.txt,
// parameters.csv, warnings.txt, model.toml and plot_data/.
#pragma once

#include <CLI/CLI.hpp>

namespace granasym {

void RegisterStudyCalibrateCommand(CLI::App* study);

}  // namespace granasym
