// Drawing the figures of analysis/figure_data.h with gnuplot, for `study
// figures` and `study compare`: each figure's wrapper OUT/figures/<stem>.plt
// (analysis::WriteFigureScripts) run once per format: PNG, PDF and SVG (the
// SVG with gnuplot's hypertext labels, which the report turns into hover
// text). gnuplot is found on PATH; the scripts next to the sources
// (GRANASYM_PLOTS_DIR at build time), or where the environment variable
// GRANASYM_PLOTS_DIR points.
#pragma once

#include <string>
#include <vector>

#include "analysis/figure_data.h"

namespace granasym {

// The folder of the gnuplot scripts (plots/study/).
std::string PlotsDirectory();

// Draws the calibration figures whose data the plot-data folder `plot_data`
// holds (calibration_report.h WritePlotData): profiles.png with
// plots/calibration_profiles.gp and pareto.png with plots/calibration_pareto.gp
// (the folder above PlotsDirectory()). Returns one line per figure: its path,
// or why it was not drawn (no gnuplot on PATH, gnuplot's message).
std::vector<std::string> DrawCalibrationFigures(const std::string& plot_data);

// Writes the wrappers of `figures` under OUT/figures/ and draws each figure
// with data (all of them, or those whose stem is in `only`); a figure that
// fails gets the reason in `not_drawn` and its caption. Prints one line per
// figure; returns the number that failed. `data_only`: wrappers, no drawing.
int DrawFigures(const std::string& out, std::vector<analysis::FigureSpec>* figures, bool data_only);

}  // namespace granasym
