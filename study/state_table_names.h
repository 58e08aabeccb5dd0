// The names of the study's state table in DIR/asymptotic_states.h5 (written by
// study/state_table.cc): one dataset /states/<column> per column, one entry
// per row. Header-only, so that readers (calibration) agree with the writer
// without linking the study library.
#pragma once

namespace granasym::study::table {

constexpr char kFileName[] = "asymptotic_states.h5";
constexpr char kStatesGroup[] = "/states";

// Integer column.
constexpr char kColumnReplicate[] = "replicate";
// Number columns (units in the datasets' `units` attribute).
constexpr char kColumnPsiEpsilon[] = "psi_epsilon_deg";  // deg
constexpr char kColumnMeanStress[] = "p_kpa";            // kPa
constexpr char kColumnVoidRatio[] = "e";
constexpr char kColumnLnVolume[] = "ln_1_plus_e";
constexpr char kColumnPsiSigma[] = "psi_sigma_deg";  // deg
constexpr char kColumnStressRatio[] = "q_over_p";
constexpr char kColumnOcr[] = "ocr";                  // p_e*/p against the study's NCL
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
// Text columns.
constexpr char kColumnKind[] = "kind";      // ncl, csl, compression, extension, triaxial
constexpr char kColumnStatus[] = "status";  // detected, drifting, not_reached, gas, invalid, no_result
constexpr char kColumnCase[] = "case";      // r<K>/<case name>
constexpr char kColumnCaseName[] = "case_name";
constexpr char kColumnStage[] = "stage";  // the stage's name, or "joined" (path convergence)
constexpr char kColumnRun[] = "run";
constexpr char kColumnFigures[] = "figures";
constexpr char kColumnFlags[] = "flags";  // validity flags, ';'-separated
constexpr char kColumnDetector[] = "detector";
constexpr char kColumnMessage[] = "message";
constexpr char kColumnNclReference[] = "ncl_reference";

// Values of the kind, status and stage columns that readers select by.
constexpr char kStatusDetected[] = "detected";
constexpr char kStageJoined[] = "joined";
constexpr char kFlagSeparator = ';';

}  // namespace granasym::study::table
