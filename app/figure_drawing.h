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

// Writes the wrappers of `figures` under OUT/figures/ and draws each figure
// with data (all of them, or those whose stem is in `only`); a figure that
// fails gets the reason in `not_drawn` and its caption. Prints one line per
// figure; returns the number that failed. `data_only`: wrappers, no drawing.
int DrawFigures(const std::string& out, std::vector<analysis::FigureSpec>* figures, bool data_only);

// Draws a calibration's whole-path figure, FOLDER/paths.png, from its plot
// data (paths.txt and path_<k>.csv, calibration/path_report.h) with
// plots/calibration_paths.gp; "" when drawn or when FOLDER has no paths,
// else why not (no gnuplot, gnuplot failed).
std::string DrawCalibrationPaths(const std::string& plot_data_dir);

}  // namespace granasym
