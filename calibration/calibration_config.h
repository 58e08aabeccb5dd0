// The calibration file (TOML), validated through ConfigTable: every error
// names the file, the key, the bad value and what is valid. Layout:
//
//   [model]
//   kind = "hypoplastic_clay"     # or "modified_cam_clay" or "hypoplastic_sand"
//   asymptotes = "analytic"       # or "integrated" (clay models: slow reference path)
//
//   [parameters.lambda_star]      # one table per parameter, all optional:
//   free = true                   #   fitted (default) or fixed at `value`
//   value = 0.1                   #   start or fixed value; default: from the data
//   lower = 0.001                 #   bounds of the fit; default: the model's
//   upper = 0.5                   #   traits (constitutive/model_traits.cc)
//   # names: the keys of the model's parameter vector, as in its [model]
//   # table (ModelTraits::parameters; model.toml of a calibration lists them)
//
//   [[dataset]]                   # one or more; exactly one of study, dem, csv,
//                                 #   dem_path, study_path
//   name = "dem"
//   study = "STUDY_DIR"           # a study folder: its asymptotic_states.h5
//   dem = ["run.h5", "runs/*.h5"] # granasym DEM results: a file or an array of
//                                 #   files and globs (wildcards in file names)
//   csv = "states.csv"
//   weight = 1.0                  # multiplies the squared residuals; 0: read
//                                 #   and drawn, not fitted
//   psi_sigma_uncertainty_deg = 0.5   # per state (study: of one replicate)
//   ln_1_plus_e_uncertainty = 0.002
//   # study datasets (study_state_reader.h):
//   kinds = ["ncl", "csl", "compression", "extension", "triaxial"]  # default all
//   statuses = ["detected"]       # detector statuses taken (default)
//   exclude_flags = ["overlap_above_10pct", "gas"]  # default
//   psi_epsilon_range_deg = [-180, 180]
//   ncl_references = ["ncl"]      # only states whose OCR refers to these NCL
//                                 #   cases (default all)
//   cases = ["nc100_psi90_I0.001_E500"]  # only these case names (default all)
//   triaxial_kind_tolerance_deg = 2.0  # triaxial states within this of 90 deg: CSL
//   max_inertial_number = 1e-3    # only rows with I(d_max) below it (default:
//                                 #   no bound; rows without I are then left out)
//   # csv datasets:
//   kind = "auto"                 # auto | ncl | csl | compression | extension | asbs |
//                                 #   unloading
//   ignore_columns = "q_kpa,t_s"  # comma-separated columns to skip
//   # dem datasets:
//   ncl_min_p_kpa = 50.0          # lowest p of NCL rows
//   max_line_points = 12          # most NCL/unloading rows per stage
//   unloading_weight = 1.0        # weight of the unloading and reload rows
//                                 #   (kind unloading, never NCL rows: a reload
//                                 #   row lies below the largest p before its
//                                 #   stage); fitted against the model driven
//                                 #   isotropically from the branch's start;
//                                 #   0: read and drawn, not fitted
//   # whole-path datasets (path_dataset.h): the model integrated along the
//   # DEM's own strain path from the DEM's own initial state:
//   dem_path = "run.h5"           # a DEM result file, or
//   study_path = "STUDY_DIR"      #   a study's case: STUDY_DIR/cases/r<replicate>/<case>/result.h5
//   case = "ncl_cycles"           #   (study_path only)
//   replicate = 1                 #   (study_path only; default 1)
//   stages = ["unload1", "reload1"]  # consecutive stages of the file (required)
//   control = "auto"              # auto | strain | drained (sigma_r follows the DEM)
//   path_kind = "auto"            # auto | unload_reload | isochoric | drained |
//                                 #   cycling | general (reports and figures)
//   points = 40                   # samples evenly spaced in strain path length,
//                                 #   plus the stage boundaries
//   ln_p_uncertainty = 0.02       # of ln p per sample; psi_sigma_uncertainty_deg
//                                 #   defaults to 1.0 for paths; ln_1_plus_e_uncertainty
//                                 #   (0.002) enters under drained control only;
//                                 #   `weight`: the path counts as `weight` states
//   asbs_ln_1_plus_e = [0.55, 0.58]  # optional: ASBS cross-section points
//                                 #   at these ln(1+e) (each finite and > 0),
//                                 #   one per value and detected asymptote,
//                                 #   along the stage's asymptotic line
//                                 #   (slope asymptote_dln1pe_dlnp); stages
//                                 #   with |slope| < 1e-4 (isochoric, e.g.
//                                 #   psi_epsilon = 90 deg) and points more
//                                 #   than 1.0 in ln p from the asymptote are
//                                 #   skipped with a warning (clay models only)
//
//   [fitter]
//   method = "ceres"              # ceres | nlopt | both (then the two are compared)
//   fix_undetermined = true       # fix parameters the data do not determine, refit
//   max_iterations = 200          # ceres
//   stall_deviance = 0.01         # ceres: converged when the deviance
//                                 #   2 cost/s^2 falls by less than this over
//                                 #   10 successful steps (0: off)
//   scale_by_residual_variance = true
//   profiles = true               # profile-likelihood intervals of every fitted
//                                 #   and undetermined parameter (profile_likelihood.h)
//   profile_points_per_side = 8   #   grid points each side of the optimum (2-50)
//   pareto = true                 # the Pareto front of two residual groups (pareto.h)
//   pareto_points = 11            #   weighted-sum sweep: odd, 5-101
//   [fitter.nlopt]
//   algorithm = "crs2"            # crs2 | isres | direct_l | mlsl
//   starts = 3
//   max_evaluations = 1500
//   seed = 1
//   polish = "bobyqa"             # bobyqa | ceres | none
//
//   [output]                      # paths relative to the calibration file
//   hdf5 = "calibration.h5"       # default: the calibration file with .h5
//   summary = "calibration.txt"   # default: the calibration file with .txt
//   plot_data = "calibration_plots"  # folder of CSV/DAT files for plots/*.gp
//   status = "calibration_status.toml"  # the fit's status and reason
//                                 #   (fit_status.h); default: the calibration
//                                 #   file with _status.toml
#pragma once

#include <string>
#include <vector>

#include "calibration/asymptote_predictor.h"
#include "calibration/ceres_fitter.h"
#include "calibration/csv_state_reader.h"
#include "calibration/dem_state_reader.h"
#include "calibration/model_parameters.h"
#include "calibration/nlopt_fitter.h"
#include "calibration/pareto.h"
#include "calibration/path_dataset.h"
#include "calibration/profile_likelihood.h"
#include "calibration/study_state_reader.h"
#include "common/config.h"
#include "common/enum_names.h"

namespace granasym {
class KeyTable;
}  // namespace granasym

namespace granasym::calibration {

struct DatasetConfig {
  std::string name;
  std::string path;                // the first of `paths`
  std::vector<std::string> paths;  // resolved against the calibration file's folder,
                                   // globs expanded (dem); one for csv and study
  bool is_dem = false;
  bool is_study = false;
  bool is_path = false;  // dem_path or study_path: a whole path (path_read)
  // study_path datasets: the study folder, case and replicate (`path` is then
  // the case's result.h5); empty for dem_path.
  std::string study_path, path_case;
  int path_replicate = 1;
  CsvReadOptions csv;
  DemReadOptions dem;
  StudyReadOptions study;
  PathReadOptions path_read;
};

// A study case's DEM result: STUDY/cases/r<replicate>/<case>/result.h5.
std::string StudyCaseResult(const std::string& study, int replicate, const std::string& case_name);

// A user's choice for one parameter; unset fields take the defaults.
struct ParameterChoice {
  std::string name;
  bool free = true;
  bool has_value = false, has_lower = false, has_upper = false;
  double value = 0.0, lower = 0.0, upper = 0.0;
};

enum class FitMethod { kCeres, kNlopt, kBoth };

}  // namespace granasym::calibration

namespace granasym {
template <>
struct EnumNames<calibration::FitMethod> {
  using M = calibration::FitMethod;
  static constexpr EnumEntry<M> kEntries[] = {
      {M::kCeres, "ceres", "Ceres least squares from the starting values"},
      {M::kNlopt, "nlopt", "NLopt global search and a local polish"},
      {M::kBoth, "both", "both, and the two optima compared"},
  };
};
}  // namespace granasym

namespace granasym::calibration {

// The name-table functions (common/enum_names.h) for this namespace's enums.
using granasym::FromString;
using granasym::ToString;

struct CalibrationConfig {
  std::string origin;  // the calibration file
  ModelKind model = ModelKind::kHypoplasticClay;
  PredictorOptions predictor;
  std::vector<ParameterChoice> parameters;
  std::vector<DatasetConfig> datasets;
  FitMethod method = FitMethod::kCeres;
  // Fix the parameters the data do not determine and refit (RunCalibration).
  bool fix_undetermined = true;
  CeresFitter::Options ceres;
  NloptFitter::Options nlopt;
  // After the fit: profile likelihoods and the Pareto front (RunCalibration).
  ProfileOptions profiles;
  ParetoOptions pareto;
  std::string hdf5_path, summary_path, plot_data_dir, status_path;
};

// Reads and validates the whole file (unknown keys included).
// The keys of a calibration file (common/key_table.h; `granasym keys
// calibration`); the [parameters.<name>] entries come from every model's
// traits (constitutive/model_traits.h), so a new parameter is listed with
// its unit, domain and typical value.
const KeyTable& CalibrationKeys();

CalibrationConfig ReadCalibrationConfig(const ConfigTable& root);
CalibrationConfig ReadCalibrationConfigFile(const std::string& path);

// The calibration file of `config`: every key that the reader takes, paths
// relative to the folder of `config.origin`, after `header` (comment lines).
// Reading it back gives `config` again (tests/calibration/calibration_config_test.cc),
// so a configuration built in code (analysis/study_calibration.h) leaves a
// file that a user can edit and rerun with `granasym calibrate`.
std::string CalibrationConfigText(const CalibrationConfig& config, const std::string& header = "");

}  // namespace granasym::calibration
