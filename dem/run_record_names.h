// The names of the groups, datasets, attributes and series columns of a DEM
// run record: the result file RUN.h5 and its checkpoint RUN.h5.ckpt. Every
// writer and reader (dem/run_record.cc, calibration/dem_state_reader.cc, the
// tests) uses these constants, so that renaming one breaks the build, not a
// user. Header-only (it includes only common/quantity_names.h, where the
// quantities shared with the models' outputs are spelled): readers outside
// dem/ include it alone.
//
// Result file (all stresses kPa, compression positive):
//   /scene                 the scene text as given (attribute origin)
//   /series/<column>       one dataset per output column, with `units`
//   /series_histogram      relative-overlap histograms, when requested
//   /stages/<NNN>          per stage: name, type, rows, stop reason, its
//                          validity, the asymptote record, the type's own
//                          keys, and (when kept) its end state under end_state/
//   /summary               termination, message, validity flags, counters,
//                          times, time step (first, smallest, largest, rule),
//                          stiffness scaling, contact durations
//   /final_state           the packing at the end (input order): cell,
//                          positions, radii, velocities, spins; and the exact
//                          engine state under engine/
//   /sample                the initial packing of the lineage (and its GSD)
//   /provenance            program version, hashes, threads, CPU
// Checkpoint: /scene, /sample, /engine, /runner, /series, /histogram_rows,
//   /stages (the records of the stages done).
#pragma once

#include "common/quantity_names.h"

namespace granasym::dem::record {

// Top-level groups and datasets.
inline constexpr char kScene[] = "/scene";
inline constexpr char kSceneOrigin[] = "origin";
inline constexpr char kSeries[] = "/series";
inline constexpr char kSeriesHistogram[] = "/series_histogram";
inline constexpr char kStages[] = "/stages";
inline constexpr char kSummary[] = "/summary";
inline constexpr char kFinalState[] = "/final_state";
inline constexpr char kSample[] = "/sample";
inline constexpr char kProvenance[] = "/provenance";
// Checkpoint only.
inline constexpr char kEngine[] = "/engine";
inline constexpr char kRunner[] = "/runner";
inline constexpr char kHistogramRows[] = "/histogram_rows";

// Series columns, in the order of the rows (dem/output_columns.cc writes
// them; readers take them by these names).
inline constexpr char kColumnStep[] = "step";
inline constexpr char kColumnStage[] = "stage";
inline constexpr auto& kColumnMeanStress = quantity::kMeanStress;
inline constexpr auto& kColumnVoidRatio = quantity::kVoidRatio;
inline constexpr auto& kColumnPsiSigma = quantity::kPsiSigma;
inline constexpr char kColumnOverlapMax[] = "overlap_max";
inline constexpr auto& kColumnTime = quantity::kTime;
inline constexpr char kColumnTimeStep[] = "time_step_s";
inline constexpr char kColumnContactDurationMin[] = "contact_duration_min_s";
inline constexpr char kColumnCoordination[] = "coordination";
inline constexpr char kColumnMechanicalCoordination[] = "mechanical_coordination";
inline constexpr char kColumnInertialNumberDmin[] = "inertial_number_dmin";
inline constexpr char kColumnInertialNumberDmax[] = "inertial_number_dmax";
inline constexpr char kColumnCellX[] = "cell_x_m";
inline constexpr char kColumnCellY[] = "cell_y_m";
inline constexpr char kColumnCellZ[] = "cell_z_m";
inline constexpr char kColumnStress11[] = "sigma_11_kpa";
inline constexpr char kColumnStress22[] = "sigma_22_kpa";
inline constexpr char kColumnStress33[] = "sigma_33_kpa";
inline constexpr char kColumnStress12[] = "sigma_12_kpa";
inline constexpr char kColumnStress13[] = "sigma_13_kpa";
inline constexpr char kColumnStress23[] = "sigma_23_kpa";
inline constexpr auto& kColumnAxialStress = quantity::kAxialStress;
inline constexpr auto& kColumnRadialStress = quantity::kRadialStress;
inline constexpr auto& kColumnDeviator = quantity::kDeviator;
inline constexpr auto& kColumnPsiEpsilon = quantity::kPsiEpsilon;
inline constexpr char kColumnAxialRate[] = "rate_a_per_s";
inline constexpr char kColumnRadialRate[] = "rate_r_per_s";
inline constexpr char kColumnStretchingRate[] = "stretching_rate_per_s";
inline constexpr auto& kColumnAxialStrain = quantity::kAxialStrain;
inline constexpr auto& kColumnRadialStrain = quantity::kRadialStrain;
inline constexpr auto& kColumnVolumetricStrain = quantity::kVolumetricStrain;
inline constexpr auto& kColumnShearStrain = quantity::kShearStrain;
inline constexpr auto& kColumnLnVolume = quantity::kLnVolume;
inline constexpr char kColumnContacts[] = "contacts";
inline constexpr char kColumnOverlapMean[] = "overlap_mean";
inline constexpr char kColumnOverlapP50[] = "overlap_p50";
inline constexpr char kColumnOverlapP90[] = "overlap_p90";
inline constexpr char kColumnOverlapP99[] = "overlap_p99";
inline constexpr char kColumnStiffnessNumber[] = "stiffness_number";
inline constexpr char kColumnKineticEnergy[] = "kinetic_energy_j";
inline constexpr char kColumnUnbalancedForce[] = "unbalanced_force";

// Attributes of /stages/<NNN>.
inline constexpr char kStageName[] = "name";
inline constexpr char kStageType[] = "type";
inline constexpr char kStageFirstRow[] = "first_row";
inline constexpr char kStageLastRow[] = "last_row";
inline constexpr char kStageStopReason[] = "stop_reason";
inline constexpr char kStageEndState[] = "end_state";  // subgroup
inline constexpr char kStageFailed[] = "failed";       // 1: the run failed in this stage
// The asymptote record (stages whose detector ran): its kind, status,
// criterion, the window used, the state over it and the criterion's measures.
inline constexpr char kAsymptoteCriterion[] = "asymptote_criterion";  // one-line description
inline constexpr char kAsymptoteDetected[] = "asymptote_detected";    // 1 when status = detected
inline constexpr char kAsymptotePathKind[] = "asymptote_path_kind";
inline constexpr char kAsymptoteStatus[] = "asymptote_status";
inline constexpr char kAsymptoteSampleStrain[] = "asymptote_sample_strain";
inline constexpr char kAsymptoteCriterionWindowStrain[] = "asymptote_criterion_window_strain";
inline constexpr char kAsymptoteCriterionWindowLnp[] = "asymptote_criterion_window_lnp";
inline constexpr char kAsymptotePsiTolerance[] = "asymptote_psi_tolerance_deg";
inline constexpr char kAsymptoteLnpTolerance[] = "asymptote_lnp_tolerance";
inline constexpr char kAsymptoteSlopeTolerance[] = "asymptote_slope_tolerance";
inline constexpr char kAsymptotePsiEpsilonTolerance[] = "asymptote_psi_epsilon_tolerance_deg";
inline constexpr char kAsymptoteLnvTolerance[] = "asymptote_lnv_tolerance";
inline constexpr char kAsymptoteWindowStrain[] = "asymptote_window_strain";  // used
inline constexpr char kAsymptoteWindowLnp[] = "asymptote_window_lnp";        // used
inline constexpr char kAsymptoteMeanStressKpa[] = "asymptote_p_kpa";
inline constexpr char kAsymptoteVoidRatio[] = "asymptote_e";
inline constexpr char kAsymptotePsiSigmaDeg[] = "asymptote_psi_sigma_deg";
inline constexpr char kAsymptotePsiEpsilonDeg[] = "asymptote_psi_epsilon_deg";
inline constexpr char kAsymptoteQOverP[] = "asymptote_q_over_p";
inline constexpr char kAsymptoteCoordination[] = "asymptote_coordination";
inline constexpr char kAsymptoteMechanicalCoordination[] = "asymptote_mechanical_coordination";
inline constexpr char kAsymptoteInertialNumberDmin[] = "asymptote_inertial_number_dmin";
inline constexpr char kAsymptoteInertialNumberDmax[] = "asymptote_inertial_number_dmax";
inline constexpr char kAsymptoteMaxRelativeOverlap[] = "asymptote_max_relative_overlap";
inline constexpr char kAsymptotePsiChangeDeg[] = "asymptote_psi_change_deg";
inline constexpr char kAsymptoteLnpChange[] = "asymptote_lnp_change";
inline constexpr char kAsymptoteLnpHalfDifference[] = "asymptote_lnp_half_difference";
inline constexpr char kAsymptoteSlopeChange[] = "asymptote_slope_change";
inline constexpr char kAsymptotePsiEpsilonChangeDeg[] = "asymptote_psi_epsilon_change_deg";
inline constexpr char kAsymptoteLnvChange[] = "asymptote_lnv_change";
inline constexpr char kAsymptoteDlnpDstrain[] = "asymptote_dlnp_dstrain";
inline constexpr char kAsymptoteDln1peDlnp[] = "asymptote_dln1pe_dlnp";
// Written since extension states are kept above the floor (older records
// have none): the range of p over the window, the floor of the valid range,
// and whether the state is a window that held before the stage's end.
inline constexpr char kAsymptotePMinKpa[] = "asymptote_p_min_kpa";
inline constexpr char kAsymptotePMaxKpa[] = "asymptote_p_max_kpa";
inline constexpr char kAsymptoteFloorKpa[] = "asymptote_floor_kpa";
inline constexpr char kAsymptoteBeforeEnd[] = "asymptote_before_end";
// The validity of every stage (dem/stage_validity.h).
inline constexpr char kValidityMaxRelativeOverlap[] = "validity_max_relative_overlap";
inline constexpr char kValidityMaxInertialNumberDmax[] = "validity_max_inertial_number_dmax";
inline constexpr char kValidityMinMechanicalCoordination[] = "validity_min_mechanical_coordination";
inline constexpr char kValidityFinalMeanStressKpa[] = "validity_final_p_kpa";
inline constexpr char kValidityFlags[] = "validity_flags";  // comma-separated; "" when none
// The stage types' own keys.
inline constexpr char kStagePsiEpsilonDeg[] = "psi_epsilon_deg";
inline constexpr char kStageStretchingRate[] = "stretching_rate_per_s";
inline constexpr char kStageAxialStrainRate[] = "axial_strain_rate_per_s";
inline constexpr char kStageRadialStressKpa[] = "radial_stress_kpa";
inline constexpr char kStageMeanStressKpa[] = "mean_stress_kpa";
// Strain-path stages: the rate rule (dem::RateRule's names) and, for the
// inertial rule, its target and settings.
inline constexpr char kStageRateRule[] = "rate_rule";
inline constexpr char kStageRateInertialNumber[] = "rate_inertial_number";
inline constexpr char kStageRateDiameter[] = "rate_diameter";
inline constexpr char kStageRateMinMeanStressKpa[] = "rate_min_mean_stress_kpa";

// Attributes of /summary.
inline constexpr char kTermination[] = "termination";
// Its values (dem::Termination's names; readers outside dem/ compare with these).
inline constexpr char kTerminationNotRun[] = "not_run";
inline constexpr char kTerminationCompleted[] = "completed";
inline constexpr char kTerminationInterrupted[] = "interrupted";
inline constexpr char kTerminationFailed[] = "failed";
inline constexpr char kMessage[] = "message";
inline constexpr char kReport[] = "report";
inline constexpr char kValidity[] = "validity";  // the stages' validity flags, one line
inline constexpr char kSteps[] = "steps";
inline constexpr char kParticles[] = "particles";
inline constexpr char kSimulatedTime[] = "simulated_time_s";
inline constexpr char kWallSeconds[] = "wall_s";
inline constexpr char kLoopSeconds[] = "loop_wall_s";
inline constexpr char kParticleStepsPerSecond[] = "particle_steps_per_s";
inline constexpr char kNeighborBuilds[] = "neighbor_builds";
inline constexpr char kThreads[] = "threads";
inline constexpr char kRows[] = "rows";
inline constexpr char kStagesCompleted[] = "stages_completed";
inline constexpr char kTimeStep[] = "time_step_s";  // of the first row
inline constexpr char kTimeStepMin[] = "time_step_min_s";
inline constexpr char kTimeStepMax[] = "time_step_max_s";
inline constexpr char kTimeStepRule[] = "time_step_rule";  // "fixed" or the adaptive rule
inline constexpr char kStiffnessScaling[] = "stiffness_scaling";
inline constexpr char kContactDurationMinReduced[] = "contact_duration_min_reduced_mass_s";
inline constexpr char kContactDurationMaxReduced[] = "contact_duration_max_reduced_mass_s";
inline constexpr char kContactDurationMinSingle[] = "contact_duration_min_single_mass_s";
inline constexpr char kContactDurationMaxSingle[] = "contact_duration_max_single_mass_s";
inline constexpr char kCriticalTimeStep[] = "critical_time_step_s";
inline constexpr char kContactDurationDescription[] = "contact_duration_description";
inline constexpr char kTimeStepOverContactDuration[] = "time_step_over_min_contact_duration";

// A packing (/sample, /final_state): datasets.
inline constexpr char kCell[] = "cell";
inline constexpr char kPositions[] = "positions";
inline constexpr char kRadii[] = "radii";
inline constexpr char kVelocities[] = "velocities";
inline constexpr char kSpins[] = "spins";
inline constexpr char kGsdDiameters[] = "gsd_diameters";
inline constexpr char kGsdTarget[] = "gsd_target_percent";
inline constexpr char kGsdAchieved[] = "gsd_achieved_percent";

// The exact engine state (/engine in the checkpoint, engine/ below
// /final_state and end_state/ of a stage): particles in the engine's order
// with their ids, the cell, the neighbour list with its pair order and shear
// history, so that a run continued from it is bit-identical.
inline constexpr char kEngineGroup[] = "engine";
inline constexpr char kStatePosition[] = "position";  // N×4 scaled x, y, z and radius
inline constexpr char kStateVelocity[] = "velocity";  // N×4 fluctuation and 1/m
inline constexpr char kStateSpin[] = "spin";          // N×4 spin and 1/I
inline constexpr char kStateId[] = "id";              // input index of each particle
inline constexpr char kStateCell[] = "cell";
inline constexpr char kStateGradient[] = "gradient";
inline constexpr char kStateTime[] = "time";
inline constexpr char kStateStep[] = "step";
inline constexpr char kStateTimeStep[] = "time_step";  // Δt of the next step (s)
inline constexpr char kStateMaxDisplacement[] = "max_displacement";
inline constexpr char kStateForcesCurrent[] = "forces_current";
inline constexpr char kStateThreads[] = "threads";
inline constexpr char kListGroup[] = "list";
inline constexpr char kListOffsets[] = "offsets";
inline constexpr char kListNeighbors[] = "neighbors";
inline constexpr char kListShear[] = "shear";
inline constexpr char kListRolling[] = "rolling";  // rolling moments (with rolling resistance)
inline constexpr char kListBuildPositions[] = "build_positions";
inline constexpr char kListBuildCell[] = "build_cell";
inline constexpr char kListSkin[] = "skin";
inline constexpr char kListMaxRadius[] = "max_radius";
inline constexpr char kListBuilds[] = "builds";

// Attributes of /provenance.
inline constexpr char kProgramVersion[] = "program_version";
inline constexpr char kSceneSha256[] = "scene_sha256";
inline constexpr char kSceneCanonical[] = "scene_canonical";  // dataset: the hashed text
inline constexpr char kStartKind[] = "start_kind";            // generated | packing | state
inline constexpr char kStartSha256[] = "start_sha256";
inline constexpr char kParentFile[] = "parent_file";
inline constexpr char kParentStage[] = "parent_stage";
inline constexpr char kParentSceneSha256[] = "parent_scene_sha256";
inline constexpr char kCpuModel[] = "cpu_model";
// The caller's name for what the run computes (a study case's key); absent: none.
inline constexpr char kCaseKey[] = "case_key";

}  // namespace granasym::dem::record
