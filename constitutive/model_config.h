// TOML input of models, initial states, stages and integration options
// (validated through ConfigTable: messages name the file, key, value and the
// valid range) and HDF5/CSV output of element tests and asymptotic states.
// The file layout is documented by constitutive/examples/*.toml.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/enum_names.h"
#include "common/hdf5_file.h"
#include "constitutive/asymptotic_states.h"
#include "constitutive/constitutive_model.h"
#include "constitutive/element_driver.h"

namespace granasym {

// [model] table: kind = "hypoplastic_clay" | "modified_cam_clay" | "hypoplastic_sand" and
// its parameters, the keys of its traits (constitutive/model_traits.h).
std::unique_ptr<ConstitutiveModel> ReadModel(const ConfigTable& model_table);
// [initial] table: mean_stress_kpa, psi_sigma_deg, and void_ratio or ocr.
ModelState ReadInitialState(const ConstitutiveModel& model, const ConfigTable& initial_table);
// The `type` of a [[stage]]: which LoadingStage helper makes it.
enum class LoadingStageType {
  kProportional,
  kConstantRadialStress,
  kIsochoric,
  kOedometric,
  kIsotropic,
  kMixed,
};
template <>
struct EnumNames<LoadingStageType> {
  static constexpr EnumEntry<LoadingStageType> kEntries[] = {
      {LoadingStageType::kProportional, "proportional",
       "proportional stretching at psi_epsilon_deg and stretching_rate"},
      {LoadingStageType::kConstantRadialStress, "constant_radial_stress",
       "drained triaxial: axial_rate prescribed, radial stress held"},
      {LoadingStageType::kIsochoric, "isochoric", "axial_rate prescribed at constant volume"},
      {LoadingStageType::kOedometric, "oedometric", "axial_rate prescribed, no radial strain"},
      {LoadingStageType::kIsotropic, "isotropic",
       "isotropic loading or unloading to target_mean_stress_kpa"},
      {LoadingStageType::kMixed, "mixed",
       "six Voigt rates; stress_controlled lists the stress-rate components"},
  };
};

// [[stage]] array of the root table.
std::vector<LoadingStage> ReadStages(const ConfigTable& root);
// [integration] table (optional keys; defaults of ElementTestOptions).
ElementTestOptions ReadElementTestOptions(const ConfigTable& integration_table);

// An element-test input read and checked (ReadElementTestInput).
struct ElementTestInput {
  std::unique_ptr<ConstitutiveModel> model;
  ModelState initial;
  ElementTestOptions options;
  std::vector<LoadingStage> stages;
};
// Reads the root of a `granasym model run` file ([model], [initial],
// optional [integration], [[stage]]) and rejects unknown keys.
ElementTestInput ReadElementTestInput(const ConfigTable& root);
// Reads a whole element-test input (the root of a `granasym model run` file:
// [model], [initial], optional [integration], [[stage]]), rejects unknown
// keys, runs it and writes the result to `out` (HDF5, atomically) and, when
// `csv` is not empty, the records as CSV. `input` names the input in the file.
ElementTestResult RunElementTestInput(const ConfigTable& root, const std::string& input,
                                      const std::string& out, const std::string& csv);

// Writes the history (compression positive, each dataset with its units) and
// the summaries under `group`: time_s, stress, strain, stretching (Voigt
// matrices), e, p_kpa, q_kpa, psi_sigma_deg, psi_epsilon_deg, ocr,
// strain_path, stage and the internal variables (names of
// common/quantity_names.h, which lists their former spellings).
void WriteElementTestResult(const ConstitutiveModel& model, const ElementTestResult& result,
                            const std::string& group, Hdf5File* file);
// One row per record, compression positive: time_s, sigma_a_kpa,
// sigma_r_kpa, p_kpa, q_kpa, e, eps_a, eps_r, strain_path, psi_sigma_deg,
// psi_epsilon_deg, ocr (common/quantity_names.h).
void WriteElementTestCsv(const ElementTestResult& result, const std::string& path);
// The CSV's columns: their names and one vector of values per column (the
// Python module's arrays).
std::vector<std::string> ElementTestColumnNames();
std::vector<std::vector<double>> ElementTestColumns(const ElementTestResult& result);

struct AsymptoteTable {
  std::vector<AsymptoticState> analytic;  // hypoplastic clay only (analytic ASBS)
  std::vector<IntegratedAsymptote> integrated;
};
// Computes what an asymptotes file asks for ([model], [asymptotes]).
AsymptoteTable ComputeAsymptotes(const ConstitutiveModel& model, const ConfigTable& root);
void WriteAsymptotes(const ConstitutiveModel& model, const AsymptoteTable& table,
                     const std::string& group, Hdf5File* file);

}  // namespace granasym
