// The names of the study's state table in DIR/asymptotic_states.h5 (written by
// study/state_table.cc): one dataset /states/<column> per column, one entry
// per row. Header-only, so that readers (calibration) agree with the writer
// without linking the study library.
#pragma once

#include "common/enum_names.h"

namespace granasym::study {

// The kind of an asymptotic state, as the table's `kind` column names it:
// from the detector's path kind, with the ψ_ε = 0° compression states as
// the NCL; `none` for a case without a result.
enum class TableKind { kNcl, kCsl, kCompression, kExtension, kTriaxial, kNone };
// What the detector said of a state (dem::AsymptoteStatus), or that its
// case has no result.
enum class TableStatus { kDetected, kDrifting, kNotReached, kGas, kInvalid, kNoResult };
// Where a row comes from: one replicate's stage (or case without a result),
// the replicates' ensemble-mean path of a stage run through its detector
// (study/ensemble_path.h), or where two paths of one replicate join.
enum class TableSource { kReplicate, kEnsemble, kJoined };

}  // namespace granasym::study

template <>
struct granasym::EnumNames<granasym::study::TableKind> {
  using K = study::TableKind;
  static constexpr EnumEntry<K> kEntries[] = {
      {K::kNcl, "ncl", "isotropic normal compression (psi_epsilon = 0)"},
      {K::kCsl, "csl", "critical state (an isochoric path, psi_epsilon = 90 deg)"},
      {K::kCompression, "compression", "a strain path with 0 < |psi_epsilon| < 90 deg"},
      {K::kExtension, "extension", "a strain path with |psi_epsilon| > 90 deg"},
      {K::kTriaxial, "triaxial", "a stress-controlled (drained triaxial) stage"},
      {K::kNone, "none", "a case without a result"},
  };
};

template <>
struct granasym::EnumNames<granasym::study::TableStatus> {
  using S = study::TableStatus;
  static constexpr EnumEntry<S> kEntries[] = {
      {S::kDetected, "detected", "the detector's criterion held over a full window"},
      {S::kDrifting, "drifting", "a full window, but the criterion did not hold at the stage end"},
      {S::kNotReached, "not_reached", "the window never filled"},
      {S::kGas, "gas", "a gas or liquefied state: no asymptotic state"},
      {S::kInvalid, "invalid", "the stage failed a validity guard"},
      {S::kNoResult, "no_result", "the case has no result (not run, failed, interrupted)"},
  };
};

template <>
struct granasym::EnumNames<granasym::study::TableSource> {
  using S = study::TableSource;
  static constexpr EnumEntry<S> kEntries[] = {
      {S::kReplicate, "replicate", "one replicate's stage, or a case without a result"},
      {S::kEnsemble, "ensemble",
       "the replicates' ensemble-mean path of a stage, run through the stage's detector"},
      {S::kJoined, "joined",
       "where two paths of one psi_epsilon from different starting states join (path "
       "convergence)"},
  };
};

namespace granasym::study::table {

constexpr char kFileName[] = "asymptotic_states.h5";
constexpr char kStatesGroup[] = "/states";

// Integer column: the replicate K of r<K>; 0 for an ensemble row.
constexpr char kColumnReplicate[] = "replicate";
// Number columns (units in the datasets' `units` attribute).
constexpr char kColumnPsiEpsilon[] = "psi_epsilon_deg";  // deg
constexpr char kColumnMeanStress[] = "p_kpa";            // kPa
constexpr char kColumnVoidRatio[] = "e";
constexpr char kColumnLnVolume[] = "ln_1_plus_e";
constexpr char kColumnPsiSigma[] = "psi_sigma_deg";  // deg
constexpr char kColumnStressRatio[] = "q_over_p";
constexpr char kColumnOcr[] = "ocr";  // p_e*/p against the study's NCL
constexpr char kColumnEquivalentPressure[] = "p_e_star_kpa";
constexpr char kColumnInertialNumberDmin[] = "inertial_number_dmin";
constexpr char kColumnInertialNumberDmax[] = "inertial_number_dmax";
constexpr char kColumnCoordination[] = "coordination";
constexpr char kColumnMechanicalCoordination[] = "mechanical_coordination";
constexpr char kColumnMaxRelativeOverlap[] = "max_relative_overlap";
constexpr char kColumnWindowStrain[] = "window_strain";
constexpr char kColumnWindowLnp[] = "window_lnp";
constexpr char kColumnPsiChange[] = "psi_change_deg";
constexpr char kColumnSlopeChange[] = "slope_change";
constexpr char kColumnLnpChange[] = "lnp_change";
constexpr char kColumnSlope[] = "dln1pe_dlnp";
constexpr char kColumnWindowPMin[] = "window_p_min_kpa";  // kPa
constexpr char kColumnWindowPMax[] = "window_p_max_kpa";  // kPa
// Integer column: 1 for an extension state whose window held before the stage end.
constexpr char kColumnHeldBeforeEnd[] = "held_before_end";
// Text columns.
constexpr char kColumnKind[] = "kind";  // ncl, csl, compression, extension, triaxial
constexpr char kColumnStatus[] =
    "status";                           // detected, drifting, not_reached, gas, invalid, no_result
constexpr char kColumnCase[] = "case";  // r<K>/<case name>, mean/<case name> (ensemble)
constexpr char kColumnCaseName[] = "case_name";
constexpr char kColumnStage[] = "stage";  // the stage's name, or "joined" (path convergence)
constexpr char kColumnRun[] = "run";
constexpr char kColumnFigures[] = "figures";
constexpr char kColumnFlags[] = "flags";  // validity flags, ';'-separated
constexpr char kColumnDetector[] = "detector";
constexpr char kColumnMessage[] = "message";
constexpr char kColumnNclReference[] = "ncl_reference";
// replicate, ensemble or joined (TableSource); tables written before it have
// none: their rows are replicates', or joined where the stage is "joined".
constexpr char kColumnSource[] = "source";

// The stage column's value for a path-convergence state.
constexpr char kStageJoined[] = "joined";
// The case column's prefix of an ensemble row (its replicate column is 0).
constexpr char kEnsembleCasePrefix[] = "mean/";
constexpr char kFlagSeparator = ';';

}  // namespace granasym::study::table
