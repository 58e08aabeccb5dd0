// Asymptotic states from CSV files (lab end states or states exported from
// other codes). Documented columns, units in the names; '#' lines are comments:
//
//   mean stress       p_kpa | p_mpa | p_pa                       (required, one)
//   void ratio        e | ln_1_plus_e                            (required, one)
//   stress direction  psi_sigma_deg | psi_sigma_rad | q_kpa      (required, one;
//                     q_kpa gives tan ψ_σ = (√2/3) q/p with p in kPa)
//   stretching dir.   psi_epsilon_deg | psi_epsilon_rad          (required unless kind = "asbs")
//   optional          weight, psi_sigma_uncertainty_deg, ln_1_plus_e_uncertainty
//
// A column named like a known quantity with other units (e.g. p_psi) is an
// "unknown units" error; any other unknown column is an error unless listed in
// `ignore_columns` (CsvTable::RequireOnlyColumns, the rule of every numeric
// table; common/csv_table.h has the others: no duplicate names, equal field
// counts, finite numbers). Each quantity comes from one column: two of one
// group (p_kpa and p_mpa; psi_sigma_deg, psi_sigma_rad and q_kpa; the two
// psi_epsilon units) are an error naming both, unless all but one are in
// `ignore_columns`. e and ln_1_plus_e may both be given (WriteStatesCsv writes
// both) when they agree in every row to 1e-6.
#pragma once

#include <string>
#include <vector>

#include "calibration/state_dataset.h"

namespace granasym::calibration {

struct CsvReadOptions {
  // "auto": the kind from ψ_ε (0° NCL, 90° CSL, 180° unloading, ...);
  // otherwise one StateKind name for every row.
  std::string kind = "auto";
  // ψ_ε within this of 0°, 90°, 180° counts as exactly there (deg).
  double kind_tolerance_deg = 0.5;
  // Defaults for rows without uncertainty columns: one standard deviation.
  double psi_sigma_uncertainty_deg = 0.5;
  double ln_volume_uncertainty = 0.002;
  double weight = 1.0;  // multiplies every row's own weight
  std::vector<std::string> ignore_columns;
  bool IsValid(std::string* why) const;
};

// Throws InputError naming the file, line and column for missing columns,
// unknown units, unparsable or invalid values (NaN included) and empty files.
StateDataset ReadStatesCsv(const std::string& path, const std::string& name,
                           const CsvReadOptions& options);
// The same from CSV text; `origin` names it in messages.
StateDataset ParseStatesCsv(const std::string& text, const std::string& origin,
                            const std::string& name, const CsvReadOptions& options);

// Writes a dataset in the format above (deg, kPa), for plots and round trips.
void WriteStatesCsv(const StateDataset& dataset, const std::string& path);

}  // namespace granasym::calibration
