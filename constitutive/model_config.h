// TOML input of models, initial states, stages and integration options
// (validated through ConfigTable: messages name the file, key, value and the
// valid range) and HDF5/CSV output of element tests and asymptotic states.
// The file layout is documented by constitutive/examples/*.toml.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/hdf5_file.h"
#include "constitutive/asymptotic_states.h"
#include "constitutive/constitutive_model.h"
#include "constitutive/element_test.h"

namespace granasym {

// [model] table: kind = "hypoplastic_clay" | "modified_cam_clay" | "hypoplastic_sand" and
// its parameters.
std::unique_ptr<ConstitutiveModel> ReadModel(const ConfigTable& model_table);
// [initial] table: mean_stress_kpa, psi_sigma_deg, and void_ratio or ocr.
ModelState ReadInitialState(const ConstitutiveModel& model, const ConfigTable& initial_table);
// [[stage]] array of the root table.
std::vector<LoadingStage> ReadStages(const ConfigTable& root);
// [integration] table (optional keys; defaults of ElementTestOptions).
ElementTestOptions ReadElementTestOptions(const ConfigTable& integration_table);

// Writes the history (compression positive, with units) and the summaries under `group`.
void WriteElementTestResult(const ConstitutiveModel& model, const ElementTestResult& result,
                            const std::string& group, Hdf5File* file);
// One row per record: time, stresses, strains, e, p, q, ψ_σ, ψ_ε, OCR, internals.
void WriteElementTestCsv(const ElementTestResult& result, const std::string& path);

struct AsymptoteTable {
  std::vector<AsymptoticState> analytic;   // hypoplastic clay only (analytic ASBS)
  std::vector<IntegratedAsymptote> integrated;
};
// Computes what an asymptotes file asks for ([model], [asymptotes]).
AsymptoteTable ComputeAsymptotes(const ConstitutiveModel& model, const ConfigTable& root);
void WriteAsymptotes(const ConstitutiveModel& model, const AsymptoteTable& table,
                     const std::string& group, Hdf5File* file);

}  // namespace granasym
