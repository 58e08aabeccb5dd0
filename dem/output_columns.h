// The output row of a DEM run: one table in which each column carries its
// name, units, description and the function that computes it from the
// measurements of the row, so that nothing must agree by position.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/state_measures.h"
#include "common/time_series.h"
#include "dem/contact_statistics.h"
#include "dem/engine.h"

namespace granasym::dem {

// What the columns of one row are computed from (measured once per row).
struct RowMeasures {
  const Engine& engine;
  int64_t stage = 0;
  AxisymmetricStress stress;    // σ_a, σ_r (Pa)
  AxisymmetricRate rate;        // axial and radial rates, compression positive (1/s)
  double stretching = 0;        // ‖D‖ (1/s)
  double eps_a = 0, eps_r = 0;  // logarithmic strains from the reference cell
  double void_ratio = 0;
  ContactStatistics contacts;
  double min_diameter = 0, max_diameter = 0;  // (m)

  // Measures the engine's current state (after a force evaluation with stress).
  RowMeasures(const Engine& engine, int64_t stage, const std::array<double, 3>& reference_cell,
              double min_diameter, double max_diameter, const std::vector<double>* histogram_edges);
};

struct OutputColumn {
  const char* name;
  const char* units;  // "1" for dimensionless
  const char* description;
  double (*value)(const RowMeasures& row);
};

// The columns of /series, in their order.
const std::vector<OutputColumn>& OutputColumns();
// The same as TimeSeries columns (name, units, description).
std::vector<TimeSeries::Column> SeriesColumns();
// The values of one row, in column order.
std::vector<double> RowValues(const RowMeasures& row);

}  // namespace granasym::dem
