// Reading the calibration file.
#include "calibration/calibration_config.h"

#include <fmt/format.h>
#include <fnmatch.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "common/error.h"
#include "common/key_table.h"
#include "common/text_file.h"

namespace granasym::calibration {

namespace {

std::string Resolve(const std::string& base, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(base).parent_path() / p).lexically_normal().string();
}

std::vector<std::string> SplitComma(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    const size_t a = part.find_first_not_of(" \t");
    const size_t b = part.find_last_not_of(" \t");
    if (a != std::string::npos) parts.push_back(part.substr(a, b - a + 1));
  }
  return parts;
}

// `pattern` (resolved) with *, ? or [...] in its file name: the matching
// files, sorted; without wildcards: the path itself.
std::vector<std::string> ExpandGlob(const ConfigTable& t, const std::string& key,
                                    const std::string& pattern) {
  const std::filesystem::path p(pattern);
  const std::string file = p.filename().string();
  if (file.find_first_of("*?[") == std::string::npos) return {pattern};
  if (p.parent_path().string().find_first_of("*?[") != std::string::npos) {
    t.Fail(key, "= '" + pattern + "': wildcards are valid in the file name only, not in folders");
  }
  std::vector<std::string> matches;
  const std::filesystem::path folder = p.parent_path().empty() ? "." : p.parent_path();
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    if (entry.is_regular_file() &&
        fnmatch(file.c_str(), entry.path().filename().string().c_str(), 0) == 0) {
      matches.push_back(entry.path().string());
    }
  }
  std::sort(matches.begin(), matches.end());
  if (matches.empty()) {
    t.Fail(key, "= '" + pattern + "' matches no file" +
                    (error ? " (cannot read the folder '" + folder.string() + "')" : ""));
  }
  return matches;
}

// [parameters.<key>]: the user's choices for the model's parameters.
std::vector<ParameterChoice> ReadParameterChoices(const ConfigTable& parameters,
                                                  const ModelParameters& defaults) {
  std::vector<ParameterChoice> choices;
  for (const ParameterSpec& spec : defaults.specs()) {
    if (!parameters.Has(spec.name)) continue;
    const ConfigTable t = parameters.GetTable(spec.name);
    ParameterChoice choice;
    choice.name = spec.name;
    choice.free = t.GetBool("free", true);
    choice.has_value = t.Has("value");
    // Values and bounds lie where the model is defined.
    if (choice.has_value) choice.value = t.GetDouble("value", spec.domain);
    choice.has_lower = t.Has("lower");
    if (choice.has_lower) choice.lower = t.GetDouble("lower", spec.domain);
    choice.has_upper = t.Has("upper");
    if (choice.has_upper) choice.upper = t.GetDouble("upper", spec.domain);
    if (!choice.free && !choice.has_value) {
      t.Fail("value", "a fixed parameter (free = false) needs a value");
    }
    const double lower = choice.has_lower ? choice.lower : spec.lower;
    const double upper = choice.has_upper ? choice.upper : spec.upper;
    if (choice.free && !(lower < upper)) {
      t.Fail(choice.has_lower ? "lower" : "upper",
             fmt::format("lower = {} must be below upper = {}", lower, upper));
    }
    if (choice.free && choice.has_value && !(choice.value >= lower && choice.value <= upper)) {
      t.Fail("value", fmt::format("value = {} lies outside [{}, {}]", choice.value, lower, upper));
    }
    choices.push_back(choice);
  }
  parameters.CheckNoUnknownKeys();
  return choices;
}

// The selections of a study dataset (study_state_reader.h).
void ReadStudySelections(const ConfigTable& t, StudyReadOptions* o) {
  if (t.Has("kinds")) {
    o->kinds = t.GetStrings("kinds");
    for (const std::string& kind : o->kinds) {
      if (std::find(StudyTableKinds().begin(), StudyTableKinds().end(), kind) ==
          StudyTableKinds().end()) {
        t.Fail("kinds", "holds '" + kind +
                            "': expected a list of ncl, csl, compression, "
                            "extension, triaxial");
      }
    }
    if (o->kinds.empty()) t.Fail("kinds", "is empty: give at least one kind or leave it out");
  }
  if (t.Has("statuses")) {
    o->statuses = t.GetStrings("statuses");
    for (const std::string& status : o->statuses) {
      if (std::find(StudyTableStatuses().begin(), StudyTableStatuses().end(), status) ==
          StudyTableStatuses().end()) {
        t.Fail("statuses", "holds '" + status +
                               "': expected a list of detected, drifting, "
                               "not_reached, gas, invalid, no_result");
      }
    }
    if (o->statuses.empty()) t.Fail("statuses", "is empty: give at least one status");
  }
  if (t.Has("exclude_flags")) o->exclude_flags = t.GetStrings("exclude_flags");
  if (t.Has("ncl_references")) o->ncl_references = t.GetStrings("ncl_references");
  if (t.Has("cases")) {
    o->cases = t.GetStrings("cases");
    if (o->cases.empty()) t.Fail("cases", "is empty: name at least one case or leave it out");
  }
  if (t.Has("psi_epsilon_range_deg")) {
    const std::vector<double> range =
        t.GetDoubles("psi_epsilon_range_deg", Range::Closed(-180, 180));
    if (range.size() != 2 || !(range[0] < range[1])) {
      t.Fail("psi_epsilon_range_deg", "must be [lo, hi] with -180 <= lo < hi <= 180 (deg)");
    }
    o->psi_epsilon_min_deg = range[0];
    o->psi_epsilon_max_deg = range[1];
  }
  o->triaxial_kind_tolerance_deg = t.GetDouble(
      "triaxial_kind_tolerance_deg", o->triaxial_kind_tolerance_deg, Range::Closed(0, 44));
  if (t.Has("max_inertial_number")) {
    o->max_inertial_number = t.GetDouble("max_inertial_number", Range::Open(0, 10));
  }
}

// The keys of a DEM dataset besides its files (dem_state_reader.h).
void ReadDemOptions(const ConfigTable& t, DemReadOptions* o) {
  o->ncl_min_p_kpa = t.GetDouble("ncl_min_p_kpa", o->ncl_min_p_kpa, Range::NonNegative());
  o->max_line_points =
      static_cast<int>(t.GetInt("max_line_points", o->max_line_points, Range::AtLeast(2)));
  if (t.Has("asbs_ln_1_plus_e")) {
    // Each value: ln(1+e) of a void ratio e > 0; NaN fails Range::Contains.
    o->asbs_ln_1_plus_e = t.GetDoubles("asbs_ln_1_plus_e", Range::Positive());
    if (o->asbs_ln_1_plus_e.empty()) {
      t.Fail("asbs_ln_1_plus_e", "is empty: give at least one ln(1+e) value or leave the key out");
    }
  }
  o->unloading_weight = t.GetDouble("unloading_weight", o->unloading_weight, Range::NonNegative());
}

// The keys of a path dataset besides its file (path_dataset.h).
void ReadPathOptions(const ConfigTable& t, PathReadOptions* o) {
  o->stages = t.GetStrings("stages");
  if (o->stages.empty()) {
    t.Fail("stages", "is empty: name the consecutive stages the path runs through");
  }
  o->control = t.GetEnum("control", o->control);
  o->kind = t.GetEnum("path_kind", o->kind);
  o->points = static_cast<int>(t.GetInt("points", o->points, Range::Closed(3, 10000)));
  o->ln_p_uncertainty = t.GetDouble("ln_p_uncertainty", o->ln_p_uncertainty, Range::Positive());
}

// The keys of a CSV dataset besides its file (csv_state_reader.h).
void ReadCsvOptions(const ConfigTable& t, CsvReadOptions* o) {
  // "auto" or one StateKind name.
  o->kind = t.GetString("kind", o->kind);
  if (o->kind != "auto" && !FromString<StateKind>(o->kind)) {
    t.Fail("kind", "= '" + o->kind + "' is not valid: expected auto, " + AllowedNames<StateKind>());
  }
  o->ignore_columns = SplitComma(t.GetString("ignore_columns", ""));
}

// One [[dataset]] (the k-th, 0-based), its paths resolved against `origin`.
DatasetConfig ReadDataset(const ConfigTable& t, size_t k, const std::string& origin) {
  DatasetConfig d;
  d.name = t.GetString("name", fmt::format("dataset{}", k + 1));
  const bool has_dem = t.Has("dem"), has_csv = t.Has("csv"), has_study = t.Has("study");
  const bool has_dem_path = t.Has("dem_path"), has_study_path = t.Has("study_path");
  if (int{has_dem} + int{has_csv} + int{has_study} + int{has_dem_path} + int{has_study_path} != 1) {
    t.Fail(has_dem || has_csv || has_study || has_dem_path || has_study_path ? "study" : "dem",
           "give exactly one of study = \"STUDY_DIR\", dem = \"RUN.h5\" (or an array of files "
           "and globs), csv = \"FILE.csv\" (asymptotic states), dem_path = \"RUN.h5\" and "
           "study_path = \"STUDY_DIR\" (a whole path, with stages = [...])");
  }
  d.is_dem = has_dem;
  d.is_study = has_study;
  d.is_path = has_dem_path || has_study_path;
  if (has_dem_path) {
    d.paths.push_back(Resolve(origin, t.GetString("dem_path")));
  } else if (has_study_path) {
    d.study_path = Resolve(origin, t.GetString("study_path"));
    d.path_case = t.GetString("case");
    d.path_replicate = static_cast<int>(t.GetInt("replicate", 1, Range::AtLeast(1)));
    d.paths.push_back(StudyCaseResult(d.study_path, d.path_replicate, d.path_case));
  } else if (has_dem) {
    const std::vector<std::string> given = t.GetStrings("dem");
    if (given.empty()) t.Fail("dem", "is an empty array: give at least one result file");
    for (const std::string& entry : given) {
      for (const std::string& file : ExpandGlob(t, "dem", Resolve(origin, entry))) {
        d.paths.push_back(file);
      }
    }
  } else {
    d.paths.push_back(Resolve(origin, t.GetString(has_csv ? "csv" : "study")));
  }
  d.path = d.paths.front();
  const double weight = t.GetDouble("weight", 1.0, Range::NonNegative());
  const double u_psi =
      t.GetDouble("psi_sigma_uncertainty_deg", d.is_path ? 1.0 : 0.5, Range::Positive());
  const double u_v = t.GetDouble("ln_1_plus_e_uncertainty", 0.002, Range::Positive());
  // The keys every kind of dataset has.
  const auto set_weights = [&](auto* o) {
    o->weight = weight;
    o->psi_sigma_uncertainty_deg = u_psi;
    o->ln_volume_uncertainty = u_v;
  };
  if (d.is_path) {
    set_weights(&d.path_read);
    ReadPathOptions(t, &d.path_read);
  } else if (has_study) {
    set_weights(&d.study);
    ReadStudySelections(t, &d.study);
  }
  if (has_dem) {
    set_weights(&d.dem);
    ReadDemOptions(t, &d.dem);
  } else if (has_csv) {
    set_weights(&d.csv);
    ReadCsvOptions(t, &d.csv);
  }
  return d;
}

// [fitter] and [fitter.nlopt].
void ReadFitter(const ConfigTable& f, CalibrationConfig* config) {
  config->method = f.GetEnum("method", config->method);
  config->fix_undetermined = f.GetBool("fix_undetermined", config->fix_undetermined);
  config->ceres.max_iterations = static_cast<int>(
      f.GetInt("max_iterations", config->ceres.max_iterations, Range::Closed(1, 1e6)));
  config->ceres.stall_deviance =
      f.GetDouble("stall_deviance", config->ceres.stall_deviance, Range::Closed(0, 10));
  config->ceres.uncertainty.scale_by_residual_variance =
      f.GetBool("scale_by_residual_variance", config->ceres.uncertainty.scale_by_residual_variance);
  config->profiles.enabled = f.GetBool("profiles", config->profiles.enabled);
  config->profiles.points_per_side = static_cast<int>(
      f.GetInt("profile_points_per_side", config->profiles.points_per_side, Range::Closed(2, 50)));
  config->profiles.max_restarts = static_cast<int>(
      f.GetInt("profile_restarts", config->profiles.max_restarts, Range::Closed(0, 10)));
  config->profiles.fast_refits = f.GetBool("fast_refits", config->profiles.fast_refits);
  config->pareto.fast_refits = config->profiles.fast_refits;
  config->pareto.enabled = f.GetBool("pareto", config->pareto.enabled);
  config->pareto.points =
      static_cast<int>(f.GetInt("pareto_points", config->pareto.points, Range::Closed(5, 101)));
  if (config->pareto.points % 2 == 0) {
    f.Fail("pareto_points", fmt::format("pareto_points = {} must be odd (the middle point is the "
                                        "ordinary fit)",
                                        config->pareto.points));
  }
  if (f.Has("nlopt")) {
    const ConfigTable t = f.GetTable("nlopt");
    config->nlopt.algorithm = t.GetEnum("algorithm", config->nlopt.algorithm);
    config->nlopt.starts =
        static_cast<int>(t.GetInt("starts", config->nlopt.starts, Range::Closed(1, 1000)));
    config->nlopt.max_evaluations = static_cast<int>(
        t.GetInt("max_evaluations", config->nlopt.max_evaluations, Range::Closed(10, 1e8)));
    config->nlopt.seed = static_cast<uint64_t>(t.GetInt("seed", 1, Range::NonNegative()));
    config->nlopt.polish = t.GetEnum("polish", config->nlopt.polish);
  }
  config->nlopt.uncertainty = config->ceres.uncertainty;
  config->nlopt.ceres = config->ceres;
}

// The output paths: beside the calibration file unless [output] names them.
void ReadOutput(const ConfigTable& root, CalibrationConfig* config) {
  const std::filesystem::path stem = std::filesystem::path(config->origin).replace_extension("");
  config->hdf5_path = stem.string() + ".h5";
  config->summary_path = stem.string() + ".txt";
  config->plot_data_dir = stem.string() + "_plots";
  config->status_path = stem.string() + "_status.toml";
  if (root.Has("output")) {
    const ConfigTable o = root.GetTable("output");
    if (o.Has("hdf5")) config->hdf5_path = Resolve(config->origin, o.GetString("hdf5"));
    if (o.Has("summary")) config->summary_path = Resolve(config->origin, o.GetString("summary"));
    if (o.Has("plot_data")) {
      config->plot_data_dir = Resolve(config->origin, o.GetString("plot_data"));
    }
    if (o.Has("status")) config->status_path = Resolve(config->origin, o.GetString("status"));
  }
}

}  // namespace

const KeyTable& CalibrationKeys() {
  static const KeyTable table = [] {
    const std::string study = "study datasets", dem = "dem datasets", csv = "csv datasets",
                      path = "path datasets";
    std::vector<KeySpec> keys = {
        OtherKey("", "model", KeyType::kTable, "", "required", "the model to calibrate"),
        OtherKey("", "parameters", KeyType::kTable, "", "all free, from the data",
                 "choices for the model's parameters, one table per parameter"),
        OtherKey("", "dataset", KeyType::kTables, "", "required",
                 "the data: one or more, each exactly one of study, dem, csv"),
        OtherKey("", "fitter", KeyType::kTable, "", "the defaults below", "the fit"),
        OtherKey("", "output", KeyType::kTable, "", "beside the calibration file",
                 "where the results go (paths relative to the calibration file)"),
        OtherKey("model", "kind", KeyType::kString, AllowedNames<ModelKind>(), "hypoplastic_clay",
                 "the constitutive model"),
        OtherKey("model", "asymptotes", KeyType::kString, AllowedNames<AsymptoteMethod>(),
                 "analytic", "how the model's asymptotic states are computed"),
    };
    for (ModelKind kind : EnumValues<ModelKind>()) {
      const std::string when = "model.kind = " + std::string(ToString(kind));
      const ModelParameters defaults = ModelParameters::Defaults(kind);
      for (const ParameterSpec& spec : defaults.specs()) {
        keys.push_back(OtherKey("parameters", spec.name, KeyType::kTable, "", "free",
                                spec.description + " (" + spec.symbol + ")", when));
        const std::string t = "parameters." + spec.name;
        const std::string unit = spec.units == "1" ? "" : spec.units;
        keys.push_back(OtherKey(t, "free", KeyType::kBool, "true or false", "true",
                                "fitted, or fixed at value", when));
        keys.push_back(NumberKey(t, "value", KeyType::kNumber, unit, spec.domain,
                                 "from the data (typical " + fmt::format("{:g}", spec.value) + ")",
                                 "start or fixed value", when));
        keys.push_back(NumberKey(t, "lower", KeyType::kNumber, unit, spec.domain,
                                 fmt::format("{:g}", spec.lower), "lower bound of the fit", when));
        keys.push_back(NumberKey(t, "upper", KeyType::kNumber, unit, spec.domain,
                                 fmt::format("{:g}", spec.upper), "upper bound of the fit", when));
      }
    }
    const std::vector<KeySpec> rest = {
        OtherKey("dataset[]", "name", KeyType::kString, "a name", "dataset<N>",
                 "the dataset's name in the report"),
        OtherKey("dataset[]", "study", KeyType::kString, "a study folder", "none",
                 "the study's asymptotic_states.h5"),
        OtherKey("dataset[]", "dem", KeyType::kStrings, "result files and globs", "none",
                 "granasym DEM results"),
        OtherKey("dataset[]", "csv", KeyType::kString, "a CSV file of states", "none",
                 "states in a CSV table"),
        NumberKey("dataset[]", "weight", KeyType::kNumber, "", Range::NonNegative(), "1",
                  "multiplies the squared residuals; 0: read and drawn, not fitted"),
        NumberKey("dataset[]", "psi_sigma_uncertainty_deg", KeyType::kNumber, "deg",
                  Range::Positive(), "0.5 (1 for path datasets)",
                  "uncertainty of psi_sigma per state or path sample"),
        NumberKey("dataset[]", "ln_1_plus_e_uncertainty", KeyType::kNumber, "", Range::Positive(),
                  "0.002", "uncertainty of ln(1+e) per state"),
        OtherKey("dataset[]", "kinds", KeyType::kStrings,
                 "ncl, csl, compression, extension, triaxial", "all", "the kinds of states taken",
                 study),
        OtherKey("dataset[]", "statuses", KeyType::kStrings,
                 "detected, drifting, not_reached, gas, invalid, no_result", "detected",
                 "the detector statuses taken", study),
        OtherKey("dataset[]", "exclude_flags", KeyType::kStrings, "validity flags",
                 "overlap_above_10pct, gas", "rows carrying any of them are left out", study),
        OtherKey("dataset[]", "ncl_references", KeyType::kStrings, "NCL case names", "all",
                 "only states whose OCR refers to these NCL cases", study),
        OtherKey("dataset[]", "cases", KeyType::kStrings, "case names", "all", "only these cases",
                 study),
        NumberKey("dataset[]", "psi_epsilon_range_deg", KeyType::kNumbers, "deg",
                  Range::Closed(-180, 180), "[-180, 180]", "[lo, hi] of the psi_epsilon taken",
                  study),
        NumberKey("dataset[]", "triaxial_kind_tolerance_deg", KeyType::kNumber, "deg",
                  Range::Closed(0, 44), "2", "triaxial states within this of 90 deg are critical",
                  study),
        NumberKey("dataset[]", "max_inertial_number", KeyType::kNumber, "", Range::Open(0, 10),
                  "no bound", "only rows with I(d_max) below it", study),
        NumberKey("dataset[]", "ncl_min_p_kpa", KeyType::kNumber, "kPa", Range::NonNegative(), "50",
                  "lowest p of NCL rows", dem),
        NumberKey("dataset[]", "max_line_points", KeyType::kInteger, "", Range::AtLeast(2), "12",
                  "most NCL/unloading rows per stage", dem),
        NumberKey("dataset[]", "asbs_ln_1_plus_e", KeyType::kNumbers, "", Range::Positive(), "none",
                  "ASBS cross-section points at these ln(1+e) (clay models)", dem),
        OtherKey("dataset[]", "kind", KeyType::kString, "auto, " + AllowedNames<StateKind>(),
                 "auto", "the kind of every state of the file", csv),
        OtherKey("dataset[]", "ignore_columns", KeyType::kString, "comma-separated column names",
                 "none", "columns to skip", csv),
        NumberKey("dataset[]", "unloading_weight", KeyType::kNumber, "", Range::NonNegative(), "1",
                  "weight of the unload-reload rows (unloading points)", dem),
        OtherKey("dataset[]", "dem_path", KeyType::kString, "a result file", "none",
                 "a whole DEM path (with stages)"),
        OtherKey("dataset[]", "study_path", KeyType::kString, "a study folder", "none",
                 "a whole path of a study's case (with case, replicate and stages)"),
        OtherKey("dataset[]", "case", KeyType::kString, "a case name", "required",
                 "the study case whose path is fitted", path),
        NumberKey("dataset[]", "replicate", KeyType::kInteger, "", Range::AtLeast(1), "1",
                  "the replicate of that case", path),
        OtherKey("dataset[]", "stages", KeyType::kStrings, "stage names", "required",
                 "the consecutive stages the path runs through", path),
        OtherKey("dataset[]", "control", KeyType::kString, AllowedNames<PathControl>(), "auto",
                 "how the model is driven along the path (drained: sigma_r follows the DEM's)",
                 path),
        OtherKey("dataset[]", "path_kind", KeyType::kString, AllowedNames<PathKind>(), "auto",
                 "what the path is (cycles, isochoric, drained, ...)", path),
        NumberKey("dataset[]", "points", KeyType::kInteger, "", Range::Closed(3, 10000), "40",
                  "samples on the path's strain length (plus the stage ends)", path),
        NumberKey("dataset[]", "ln_p_uncertainty", KeyType::kNumber, "", Range::Positive(), "0.02",
                  "uncertainty of ln p per path sample", path),
        OtherKey("fitter", "method", KeyType::kString, AllowedNames<FitMethod>(), "ceres",
                 "the fitter (both: the two compared)"),
        OtherKey("fitter", "fix_undetermined", KeyType::kBool, "true or false", "true",
                 "fix parameters the data do not determine, and refit"),
        NumberKey("fitter", "max_iterations", KeyType::kInteger, "", Range::Closed(1, 1e6), "200",
                  "Ceres iterations"),
        NumberKey("fitter", "stall_deviance", KeyType::kNumber, "", Range::Closed(0, 10), "0.01",
                  "converged when the deviance 2 cost/s^2 falls by less than this over 10 "
                  "successful Ceres steps (0: off)"),
        OtherKey("fitter", "scale_by_residual_variance", KeyType::kBool, "true or false", "true",
                 "scale the covariance by the residual variance (uncertainties as weights)"),
        OtherKey("fitter", "profiles", KeyType::kBool, "true or false", "true",
                 "profile likelihood of every parameter (intervals, flat parameters)"),
        NumberKey("fitter", "profile_points_per_side", KeyType::kInteger, "", Range::Closed(2, 50),
                  "8", "grid points on each side of the optimum of a profile"),
        NumberKey("fitter", "profile_restarts", KeyType::kInteger, "", Range::Closed(0, 10), "3",
                  "refits from a profile's point of least cost where it lies below the fit's"),
        OtherKey("fitter", "fast_refits", KeyType::kBool, "true or false", "true",
                 "the undetermined search's, profiles' and Pareto front's fits by forward "
                 "differences to a cost tolerance of 1e-8"),
        OtherKey("fitter", "pareto", KeyType::kBool, "true or false", "true",
                 "the Pareto front of the two groups of residuals"),
        NumberKey("fitter", "pareto_points", KeyType::kInteger, "", Range::Closed(5, 101), "11",
                  "weights of the Pareto sweep (odd: the middle point is the ordinary fit)"),
        OtherKey("fitter", "nlopt", KeyType::kTable, "", "the defaults below", "the global search"),
        OtherKey("fitter.nlopt", "algorithm", KeyType::kString, AllowedNames<GlobalAlgorithm>(),
                 "crs2", "NLopt's global algorithm"),
        NumberKey("fitter.nlopt", "starts", KeyType::kInteger, "", Range::Closed(1, 1000), "3",
                  "independent global searches"),
        NumberKey("fitter.nlopt", "max_evaluations", KeyType::kInteger, "", Range::Closed(10, 1e8),
                  "1500", "evaluations per search"),
        NumberKey("fitter.nlopt", "seed", KeyType::kInteger, "", Range::NonNegative(), "1",
                  "NLopt's random seed of the first start"),
        OtherKey("fitter.nlopt", "polish", KeyType::kString, AllowedNames<LocalPolish>(), "bobyqa",
                 "the local polish of the best start"),
        OtherKey("output", "hdf5", KeyType::kString, "a file path", "CALIBRATION.h5",
                 "the fit's HDF5 file"),
        OtherKey("output", "summary", KeyType::kString, "a file path", "CALIBRATION.txt",
                 "the text summary"),
        OtherKey("output", "plot_data", KeyType::kString, "a folder", "CALIBRATION_plots",
                 "CSV/DAT files for plots/*.gp"),
        OtherKey("output", "status", KeyType::kString, "a file path", "CALIBRATION_status.toml",
                 "the fit's status and reason"),
    };
    keys.insert(keys.end(), rest.begin(), rest.end());
    return KeyTable("calibration",
                    "a calibration file (granasym calibrate FILE): the model, its parameters, "
                    "the datasets, the fitter and the outputs",
                    std::move(keys));
  }();
  return table;
}

std::string StudyCaseResult(const std::string& study, int replicate, const std::string& case_name) {
  return (std::filesystem::path(study) / "cases" / fmt::format("r{}", replicate) / case_name /
          "result.h5")
      .lexically_normal()
      .string();
}

CalibrationConfig ReadCalibrationConfig(const ConfigTable& root) {
  root.UseKeys({&CalibrationKeys()});
  CalibrationConfig config;
  config.origin = root.origin();
  const ConfigTable model = root.GetTable("model");
  config.model = model.GetEnum("kind", ModelKind::kHypoplasticClay);
  config.predictor.method = model.GetEnum("asymptotes", AsymptoteMethod::kAnalytic);
  if (root.Has("parameters")) {
    config.parameters =
        ReadParameterChoices(root.GetTable("parameters"), ModelParameters::Defaults(config.model));
  }
  const std::vector<ConfigTable> datasets = root.GetTableArray("dataset");
  if (datasets.empty()) root.Fail("dataset", "at least one [[dataset]] is needed");
  for (size_t k = 0; k < datasets.size(); ++k) {
    config.datasets.push_back(ReadDataset(datasets[k], k, config.origin));
  }
  if (root.Has("fitter")) ReadFitter(root.GetTable("fitter"), &config);
  ReadOutput(root, &config);
  std::string why;
  if (!config.ceres.IsValid(&why) || !config.nlopt.IsValid(&why)) root.Fail("fitter", why);
  root.CheckNoUnknownKeys();
  return config;
}

CalibrationConfig ReadCalibrationConfigFile(const std::string& path) {
  return ReadCalibrationConfig(ConfigTable::ParseFile(path));
}

namespace {

// A TOML float that reads back to the same double (shortest round trip).
std::string TomlFloat(double value) {
  std::string text = fmt::format("{}", value);
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";  // not an integer
  return text;
}

std::string TomlStrings(const std::vector<std::string>& values) {
  std::string text;
  for (const std::string& v : values) text += (text.empty() ? "" : ", ") + TomlQuoted(v);
  return "[" + text + "]";
}

std::string TomlFloats(const std::vector<double>& values) {
  std::string text;
  for (double v : values) text += (text.empty() ? "" : ", ") + TomlFloat(v);
  return "[" + text + "]";
}

// `path` relative to the calibration file's folder.
std::string RelativeTo(const std::string& origin, const std::string& path) {
  const std::filesystem::path folder =
      std::filesystem::path(origin).parent_path().lexically_normal();
  std::filesystem::path relative = std::filesystem::path(path).lexically_relative(folder);
  if (relative.empty()) return path;
  if (!relative.has_filename() && relative.has_parent_path()) relative = relative.parent_path();
  return relative.string();
}

std::string CommaList(const std::vector<std::string>& values) {
  std::string text;
  for (const std::string& v : values) text += (text.empty() ? "" : ",") + v;
  return text;
}

}  // namespace

std::string CalibrationConfigText(const CalibrationConfig& config, const std::string& header) {
  const auto rel = [&](const std::string& path) {
    return TomlQuoted(RelativeTo(config.origin, path));
  };
  // The keys every kind of dataset has.
  const auto weights = [](const auto& o) {
    return fmt::format(
        "weight = {}\npsi_sigma_uncertainty_deg = {}\nln_1_plus_e_uncertainty = {}\n",
        TomlFloat(o.weight), TomlFloat(o.psi_sigma_uncertainty_deg),
        TomlFloat(o.ln_volume_uncertainty));
  };
  std::string s = header;
  s += fmt::format("[model]\nkind = {}\nasymptotes = {}\n", TomlQuoted(ToString(config.model)),
                   TomlQuoted(ToString(config.predictor.method)));
  for (const ParameterChoice& p : config.parameters) {
    s += fmt::format("\n[parameters.{}]\nfree = {}\n", p.name, p.free ? "true" : "false");
    if (p.has_value) s += "value = " + TomlFloat(p.value) + "\n";
    if (p.has_lower) s += "lower = " + TomlFloat(p.lower) + "\n";
    if (p.has_upper) s += "upper = " + TomlFloat(p.upper) + "\n";
  }
  for (const DatasetConfig& d : config.datasets) {
    s += "\n[[dataset]]\nname = " + TomlQuoted(d.name) + "\n";
    if (d.is_study) {
      const StudyReadOptions& o = d.study;
      s += "study = " + rel(d.path) + "\n";
      s += weights(o);
      s += "kinds = " + TomlStrings(o.kinds) + "\n";
      s += "statuses = " + TomlStrings(o.statuses) + "\n";
      s += "exclude_flags = " + TomlStrings(o.exclude_flags) + "\n";
      if (!o.ncl_references.empty())
        s += "ncl_references = " + TomlStrings(o.ncl_references) + "\n";
      if (!o.cases.empty()) s += "cases = " + TomlStrings(o.cases) + "\n";
      s += "psi_epsilon_range_deg = " + TomlFloats({o.psi_epsilon_min_deg, o.psi_epsilon_max_deg}) +
           "\n";
      s += "triaxial_kind_tolerance_deg = " + TomlFloat(o.triaxial_kind_tolerance_deg) + "\n";
      if (std::isfinite(o.max_inertial_number)) {
        s += "max_inertial_number = " + TomlFloat(o.max_inertial_number) + "\n";
      }
    } else if (d.is_path) {
      const PathReadOptions& o = d.path_read;
      if (!d.study_path.empty()) {
        s += "study_path = " + rel(d.study_path) + "\n";
        s += "case = " + TomlQuoted(d.path_case) + "\n";
        s += fmt::format("replicate = {}\n", d.path_replicate);
      } else {
        s += "dem_path = " + rel(d.path) + "\n";
      }
      s += "stages = " + TomlStrings(o.stages) + "\n";
      s += weights(o);
      s += fmt::format("control = {}\npath_kind = {}\npoints = {}\nln_p_uncertainty = {}\n",
                       TomlQuoted(ToString(o.control)), TomlQuoted(ToString(o.kind)), o.points,
                       TomlFloat(o.ln_p_uncertainty));
    } else if (d.is_dem) {
      const DemReadOptions& o = d.dem;
      std::vector<std::string> files;
      for (const std::string& path : d.paths) files.push_back(RelativeTo(config.origin, path));
      s += "dem = " + TomlStrings(files) + "\n";
      s += weights(o);
      s +=
          fmt::format("ncl_min_p_kpa = {}\nmax_line_points = {}\nunloading_weight = {}\n",
                      TomlFloat(o.ncl_min_p_kpa), o.max_line_points, TomlFloat(o.unloading_weight));
      if (!o.asbs_ln_1_plus_e.empty()) {
        s += "asbs_ln_1_plus_e = " + TomlFloats(o.asbs_ln_1_plus_e) + "\n";
      }
    } else {
      const CsvReadOptions& o = d.csv;
      s += "csv = " + rel(d.path) + "\n";
      s += weights(o);
      s += "kind = " + TomlQuoted(o.kind) + "\n";
      if (!o.ignore_columns.empty()) {
        s += "ignore_columns = " + TomlQuoted(CommaList(o.ignore_columns)) + "\n";
      }
    }
  }
  s += fmt::format(
      "\n[fitter]\nmethod = {}\nfix_undetermined = {}\nmax_iterations = {}\n"
      "stall_deviance = {}\nscale_by_residual_variance = {}\nprofiles = "
      "{}\nprofile_points_per_side = {}\n"
      "profile_restarts = {}\nfast_refits = {}\npareto = {}\npareto_points = {}\n",
      TomlQuoted(ToString(config.method)), config.fix_undetermined ? "true" : "false",
      config.ceres.max_iterations, TomlFloat(config.ceres.stall_deviance),
      config.ceres.uncertainty.scale_by_residual_variance ? "true" : "false",
      config.profiles.enabled ? "true" : "false", config.profiles.points_per_side,
      config.profiles.max_restarts, config.profiles.fast_refits ? "true" : "false",
      config.pareto.enabled ? "true" : "false", config.pareto.points);
  s += fmt::format(
      "[fitter.nlopt]\nalgorithm = {}\nstarts = {}\nmax_evaluations = {}\nseed = {}\n"
      "polish = {}\n",
      TomlQuoted(ToString(config.nlopt.algorithm)), config.nlopt.starts,
      config.nlopt.max_evaluations, config.nlopt.seed, TomlQuoted(ToString(config.nlopt.polish)));
  s += fmt::format("\n[output]\nhdf5 = {}\nsummary = {}\nplot_data = {}\nstatus = {}\n",
                   rel(config.hdf5_path), rel(config.summary_path), rel(config.plot_data_dir),
                   rel(config.status_path));
  return s;
}

}  // namespace granasym::calibration
