// Asymptotic states from a study's state table, DIR/asymptotic_states.h5
// (study/state_table_names.h; written by `granasym study run`): the rows that
// pass the selections below, grouped by (case_name, stage) over replicates.
// Rows of stage "joined" (path convergence, paper Sec. 4.3) are states too;
// the ensemble rows (source `ensemble`: the replicates' mean paths) are left
// out, since the replicates' own rows are averaged here.
//
// Selections (each state enters once):
//   kinds: ncl, csl, compression, extension, triaxial (default all); a
//     triaxial (stress-controlled) state takes the kind of its measured ψ_ε
//     (within triaxial_kind_tolerance_deg of 90° it is a critical state);
//   psi_epsilon_range_deg: [lo, hi] of the row's ψ_ε (default all);
//   statuses: detector statuses taken (default ["detected"]);
//   exclude_flags: rows carrying any of these validity flags are left out
//     (default ["overlap_above_10pct", "gas"]);
//   ncl_references: only rows whose OCR refers to one of these NCL cases
//     (default all; a study with samples of other materials, e.g. φ = 0,
//     names its own NCL case here so that the others stay out);
//   cases: only rows of these case names (default all; `study calibrate`
//     names the rate study's quasi-static cases here, analysis/rate_study.h);
//   max_inertial_number: only rows with I(d_max) below it (default: no
//     bound; rows without an inertial number are then left out too, and
//     what the bound left out is a dataset warning).
// Each state carries the largest I(d_min), I(d_max) of its replicates' rows
// and the union of their validity flags (joined rows carry those of the two
// paths they join, study/state_table.h).
// Replicates: the state is the replicate mean of ln p, ln(1+e), ψ_σ and ψ_ε
// (and of the table's OCR); its uncertainties are the standard errors of the
// mean of ψ_σ and ln(1+e), floored at the stated uncertainty / √n (n
// replicates with the stated per-state scatter cannot give less); one
// replicate keeps the stated uncertainties. The 95 % interval half-widths
// (Student t, n − 1 degrees of freedom) go with the state for the report.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "calibration/state_dataset.h"

namespace granasym::calibration {

struct StudyReadOptions {
  std::vector<std::string> kinds = {"ncl", "csl", "compression", "extension", "triaxial"};
  double psi_epsilon_min_deg = -180.0, psi_epsilon_max_deg = 180.0;
  std::vector<std::string> statuses = {"detected"};
  std::vector<std::string> exclude_flags = {"overlap_above_10pct", "gas"};
  std::vector<std::string> ncl_references;                               // empty: all
  std::vector<std::string> cases;                                        // empty: all
  double max_inertial_number = std::numeric_limits<double>::infinity();  // of I(d_max)
  double triaxial_kind_tolerance_deg = 2.0;
  double kind_tolerance_deg = 0.5;         // ψ_ε within this of 0°, 90° counts as there
  double psi_sigma_uncertainty_deg = 0.5;  // one standard deviation, per state
  double ln_volume_uncertainty = 0.002;
  double weight = 1.0;
  bool IsValid(std::string* why) const;
};

// The kinds and statuses a study table can hold (for messages and checks).
const std::vector<std::string>& StudyTableKinds();
const std::vector<std::string>& StudyTableStatuses();

// `directory`: the study folder (or its asymptotic_states.h5 itself). Throws
// InputError naming the file for a missing or foreign file, and when no row
// passes the selections (with the counts by kind and status that exist).
StateDataset ReadStatesStudy(const std::string& directory, const std::string& name,
                             const StudyReadOptions& options);

}  // namespace granasym::calibration
