// Reading model, test and asymptote files; writing their results.
#include "constitutive/model_config.h"

#include <fmt/format.h>

#include <cmath>

#include "common/csv_table.h"
#include "common/error.h"
#include "common/quantity_names.h"
#include "common/state_measures.h"
#include "constitutive/hypoplastic_clay.h"
#include "constitutive/model_traits.h"

namespace granasym {

namespace {
// Ranges of sane settings (kPa, 1/s, s); the parameters' own are in their traits.
const Range kVoidRatio = {0.0, 20.0, false, true};                           // e of a state
const Range kSignedRate = Range::Closed(-kStrainRate.max, kStrainRate.max);  // axial, Voigt
const Range kDuration = {0.0, 1e9, false, true};                             // stage durations (s)

// The valid values of a stop of an element test.
Range StopRange(StopKind kind) {
  switch (kind) {
    case StopKind::kMeanStress:
      return kStressKpa;
    case StopKind::kAxialStrain:
    case StopKind::kVolumetricStrain:
    case StopKind::kShearStrain:
      return kStageStrain;
    case StopKind::kStrainPath:
      return {0.0, 1e3, false, true};
    case StopKind::kStressRatio:
      return Range::Closed(-3.0, 3.0);
    case StopKind::kAsymptote:
      return Range::Open(0.0, 1e-2);
  }
  return Range::Any();
}

}  // namespace

std::unique_ptr<ConstitutiveModel> ReadModel(const ConfigTable& table) {
  return Traits(table.GetEnum("kind", ModelKind::kHypoplasticClay)).read(table);
}

ModelState ReadInitialState(const ConstitutiveModel& model, const ConfigTable& table) {
  const double p = table.GetDouble("mean_stress_kpa", kStressKpa);
  const double psi = table.GetDouble("psi_sigma_deg", 0.0, Range::Open(-35.26, 54.73)) * kDegree;
  const bool has_e = table.Has("void_ratio");
  const bool has_ocr = table.Has("ocr");
  if (has_e == has_ocr) table.Fail("ocr", "give exactly one of void_ratio and ocr");
  try {
    return has_e
               ? InitialStateFromVoidRatio(model, p, psi, table.GetDouble("void_ratio", kVoidRatio))
               : InitialStateFromOcr(model, p, psi,
                                     table.GetDouble("ocr", Range::Closed(1.0, 1e6)));
  } catch (const InputError& error) {
    throw InputError(fmt::format("{}: [{}]: {}", table.origin(), table.KeyName(""), error.what()));
  }
}

std::vector<LoadingStage> ReadStages(const ConfigTable& root) {
  std::vector<LoadingStage> stages;
  for (const ConfigTable& table : root.GetTableArray("stage")) {
    const LoadingStageType type = table.GetEnum("type", LoadingStageType::kProportional);
    const double rate = table.GetDouble("stretching_rate", 1.0, kStrainRate);
    const double duration = table.GetDouble("duration_s", 1.0, kDuration);
    LoadingStage stage;
    if (type == LoadingStageType::kProportional) {
      stage = LoadingStage::Proportional(
          table.GetDouble("psi_epsilon_deg", Range::Closed(-180, 180)) * kDegree, rate, duration);
    } else if (type == LoadingStageType::kConstantRadialStress) {
      stage = LoadingStage::ConstantRadialStress(table.GetDouble("axial_rate", rate, kSignedRate),
                                                 duration);
    } else if (type == LoadingStageType::kIsochoric) {
      stage = LoadingStage::Isochoric(table.GetDouble("axial_rate", rate, kSignedRate), duration);
    } else if (type == LoadingStageType::kOedometric) {
      stage = LoadingStage::Oedometric(table.GetDouble("axial_rate", rate, kSignedRate), duration);
    } else if (type == LoadingStageType::kIsotropic) {
      stage = LoadingStage::IsotropicToMeanStress(
          table.GetDouble("target_mean_stress_kpa", kStressKpa), rate);
      if (table.Has("duration_s")) stage.duration = duration;
    } else {
      const std::vector<double> values = table.GetDoubles("rate", kSignedRate);
      if (values.size() != 6) {
        table.Fail("rate",
                   fmt::format("needs 6 values (Voigt 11,22,33,12,13,23), got {}", values.size()));
      }
      stage.duration = duration;
      stage.name = ToString(LoadingStageType::kMixed);
      for (int i = 0; i < 6; ++i) stage.rate[i] = values[i];
      std::vector<double> stress_controlled;
      if (table.Has("stress_controlled")) {
        stress_controlled = table.GetDoubles("stress_controlled", Range::Closed(0, 5));
      }
      for (double index : stress_controlled) {
        if (index != std::floor(index)) {
          table.Fail("stress_controlled", "lists component indices 0..5");
        }
        stage.control[static_cast<int>(index)] = ComponentControl::kStressRate;
      }
    }
    stage.name = table.GetString("name", stage.name);
    stage.output_points =
        static_cast<int>(table.GetInt("output_points", 100, Range::Closed(1, 1e6)));
    if (table.Has("stop")) {
      const ConfigTable stop = table.GetTable("stop");
      // The keys are the StopKind names; the mean stress carries its unit.
      for (StopKind kind : EnumValues<StopKind>()) {
        const std::string key =
            std::string(ToString(kind)) + (kind == StopKind::kMeanStress ? "_kpa" : "");
        if (stop.Has(key)) {
          const Range range = StopRange(kind);
          stage.stops.push_back({kind, stop.GetDouble(key, range)});
        }
      }
    }
    stages.push_back(stage);
  }
  if (stages.empty()) root.Fail("stage", "a test needs at least one [[stage]]");
  return stages;
}

ElementTestOptions ReadElementTestOptions(const ConfigTable& table) {
  ElementTestOptions options;
  options.method = table.GetEnum("method", options.method);
  options.integrator.kind = table.GetEnum("integrator", options.integrator.kind);
  options.integrator.jacobian = table.GetEnum("jacobian", options.integrator.jacobian);
  options.integrator.relative_tolerance = table.GetDouble(
      "relative_tolerance", options.integrator.relative_tolerance, Range::Closed(1e-14, 0.1));
  options.integrator.absolute_tolerance = table.GetDouble(
      "absolute_tolerance", options.integrator.absolute_tolerance, Range::Closed(1e-14, 1e3));
  options.integrator.arkode_order = static_cast<int>(
      table.GetInt("arkode_order", options.integrator.arkode_order, Range::Closed(2, 8)));
  options.stress_point.method = table.GetEnum("stress_point", options.stress_point.method);
  options.stress_point.tolerance = table.GetDouble(
      "stress_point_tolerance", options.stress_point.tolerance, Range::Open(0, 0.1));
  options.max_strain_increment =
      table.GetDouble("max_strain_increment", options.max_strain_increment, Range::Open(0, 0.1));
  options.limit_point_condition =
      table.GetDouble("limit_point_condition", options.limit_point_condition, Range::Open(0, 0.1));
  std::string why;
  if (!options.IsValid(&why)) table.Fail("method", why);
  return options;
}

void WriteElementTestResult(const ConstitutiveModel& model, const ElementTestResult& result,
                            const std::string& group, Hdf5File* file) {
  const size_t n = result.history.size();
  std::vector<double> time, stress, strain, stretching, e, p, q, psi_sigma, psi_epsilon, ocr, path;
  std::vector<int64_t> stage;
  const int num_internal = model.num_internal();
  std::vector<double> internal;
  for (const ElementTestRecord& record : result.history) {
    time.push_back(record.time);
    stress.insert(stress.end(), record.stress.begin(), record.stress.end());
    strain.insert(strain.end(), record.strain.begin(), record.strain.end());
    stretching.insert(stretching.end(), record.stretching.begin(), record.stretching.end());
    e.push_back(record.void_ratio);
    const AxisymmetricStress s = RecordStress(record);
    p.push_back(s.mean());
    q.push_back(s.deviator());
    psi_sigma.push_back(s.psi() / kDegree);
    psi_epsilon.push_back(RecordStretching(record).psi() / kDegree);
    ocr.push_back(record.ocr);
    path.push_back(record.strain_path);
    stage.push_back(record.stage);
    internal.insert(internal.end(), record.internal.begin(), record.internal.end());
  }
  file->CreateGroup(group);
  const std::string at = group + "/";
  file->WriteDoubles(at + quantity::kTime, time, "s");
  file->WriteMatrix(group + "/stress", stress, n, 6, "kPa");
  file->WriteMatrix(group + "/strain", strain, n, 6, "1");
  file->WriteMatrix(group + "/stretching", stretching, n, 6, "1/s");
  file->WriteDoubles(at + quantity::kVoidRatio, e, "1");
  file->WriteDoubles(at + quantity::kMeanStress, p, "kPa");
  file->WriteDoubles(at + quantity::kDeviator, q, "kPa");
  file->WriteDoubles(at + quantity::kPsiSigma, psi_sigma, "deg");
  file->WriteDoubles(at + quantity::kPsiEpsilon, psi_epsilon, "deg");
  file->WriteDoubles(at + quantity::kOverconsolidation, ocr, "1");
  file->WriteDoubles(group + "/strain_path", path, "1");
  file->WriteInts(group + "/stage", stage, "1");
  if (num_internal > 0) {
    file->WriteMatrix(group + "/internal", internal, n, num_internal, "kPa");
  }
  const ElementTestSummary& summary = result.summary;
  file->SetAttribute(group, "model", model.Describe());
  file->SetAttribute(group, "sign_convention", "compression positive; Voigt 11,22,33,12,13,23");
  file->SetAttribute(group, "termination", ToString(summary.termination));
  file->SetAttribute(group, "message", summary.message);
  file->SetAttribute(group, "report", summary.Report());
  file->SetAttribute(group, "steps", static_cast<int64_t>(summary.totals.steps));
  file->SetAttribute(group, "rejected_steps", static_cast<int64_t>(summary.totals.rejected_steps));
  file->SetAttribute(group, "rhs_evaluations",
                     static_cast<int64_t>(summary.totals.rhs_evaluations));
  file->SetAttribute(group, "wall_time_s", summary.totals.wall_time_s);
  for (size_t k = 0; k < summary.stages.size(); ++k) {
    const std::string stage_group = fmt::format("{}/stages/{}", group, k);
    file->CreateGroup(stage_group);
    file->SetAttribute(stage_group, "name", summary.stages[k].name);
    file->SetAttribute(stage_group, "stop", summary.stages[k].stop);
    file->SetAttribute(stage_group, "report", summary.stages[k].integration.Report());
  }
}

std::vector<std::string> ElementTestColumnNames() {
  return {quantity::kTime,        quantity::kAxialStress,  quantity::kRadialStress,
          quantity::kMeanStress,  quantity::kDeviator,     quantity::kVoidRatio,
          quantity::kAxialStrain, quantity::kRadialStrain, "strain_path",
          quantity::kPsiSigma,    quantity::kPsiEpsilon,   quantity::kOverconsolidation};
}

std::vector<std::vector<double>> ElementTestColumns(const ElementTestResult& result) {
  std::vector<std::vector<double>> values(ElementTestColumnNames().size());
  for (const ElementTestRecord& r : result.history) {
    const AxisymmetricStress s = RecordStress(r);
    const std::vector<double> row = {r.time,
                                     s.axial,
                                     s.radial,
                                     s.mean(),
                                     s.deviator(),
                                     r.void_ratio,
                                     r.strain[0],
                                     0.5 * (r.strain[1] + r.strain[2]),
                                     r.strain_path,
                                     s.psi() / kDegree,
                                     RecordStretching(r).psi() / kDegree,
                                     r.ocr};
    for (size_t c = 0; c < row.size(); ++c) values[c].push_back(row[c]);
  }
  return values;
}

void WriteElementTestCsv(const ElementTestResult& result, const std::string& path) {
  WriteCsv(path, ElementTestColumnNames(), ElementTestColumns(result));
}

AsymptoteTable ComputeAsymptotes(const ConstitutiveModel& model, const ConfigTable& root) {
  AsymptoteTable out;
  const ConfigTable table = root.GetTable("asymptotes");
  const int points = static_cast<int>(table.GetInt("analytic_points", 200, Range::Closed(2, 1e6)));
  // The analytic ASBS curve is the hypoplastic clay's (asymptotic_states.h).
  if (const auto* clay = dynamic_cast<const HypoplasticClay*>(&model)) {
    out.analytic = AnalyticAsymptoteCurve(*clay, points);
  }
  if (table.Has("psi_epsilon_deg")) {
    AsymptoteSearchOptions options;
    options.tolerance = table.GetDouble("tolerance", options.tolerance, Range::Open(0.0, 1e-2));
    options.max_strain_path =
        table.GetDouble("max_strain_path", options.max_strain_path, {0.0, 1e3, false, true});
    const ModelState initial = ReadInitialState(model, table.GetTable("initial"));
    for (double psi : table.GetDoubles("psi_epsilon_deg", Range::Closed(-180, 180))) {
      out.integrated.push_back(IntegrateAsymptote(model, initial, psi * kDegree, options));
    }
  }
  return out;
}

void WriteAsymptotes(const ConstitutiveModel& model, const AsymptoteTable& table,
                     const std::string& group, Hdf5File* file) {
  file->CreateGroup(group);
  file->SetAttribute(group, "model", model.Describe());
  auto write = [&](const std::string& sub, const std::vector<AsymptoticState>& states) {
    std::vector<double> psi_e, psi_s, ocr, ratio;
    for (const AsymptoticState& s : states) {
      psi_e.push_back(s.psi_epsilon / kDegree);
      psi_s.push_back(s.psi_sigma / kDegree);
      ocr.push_back(s.ocr);
      ratio.push_back(s.stress_ratio);
    }
    file->WriteDoubles(sub + "/" + quantity::kPsiEpsilon, psi_e, "deg");
    file->WriteDoubles(sub + "/" + quantity::kPsiSigma, psi_s, "deg");
    file->WriteDoubles(sub + "/" + quantity::kOverconsolidation, ocr, "1");
    file->WriteDoubles(sub + "/stress_ratio", ratio, "1");
  };
  if (!table.analytic.empty()) {
    write(group + "/analytic", table.analytic);
    file->SetAttribute(group + "/analytic", "source",
                       "Masin & Herle (2005) ASBS: D ~ -A^-1:N, OCR = 2 fd_SBS^(-1/alpha)");
  }
  if (!table.integrated.empty()) {
    std::vector<AsymptoticState> states;
    std::vector<int64_t> found;
    std::vector<double> path;
    for (const IntegratedAsymptote& a : table.integrated) {
      states.push_back(a.state);
      found.push_back(a.found ? 1 : 0);
      path.push_back(a.strain_path);
    }
    write(group + "/integrated", states);
    file->WriteInts(group + "/integrated/found", found, "1");
    file->WriteDoubles(group + "/integrated/strain_path", path, "1");
    file->SetAttribute(group + "/integrated", "criterion",
                       "|dpsi_sigma/ds| + |d ln OCR/ds| below tolerance (per unit strain path s)");
  }
}

}  // namespace granasym

namespace granasym {

ElementTestInput ReadElementTestInput(const ConfigTable& root) {
  ElementTestInput input;
  input.model = ReadModel(root.GetTable("model"));
  input.initial = ReadInitialState(*input.model, root.GetTable("initial"));
  input.options = root.Has("integration") ? ReadElementTestOptions(root.GetTable("integration"))
                                          : ElementTestOptions();
  if (input.options.method == DriveMethod::kStressPoint && !HasStressPointMethod(*input.model)) {
    root.GetTable("integration").Fail("method", "stress_point exists for modified_cam_clay only");
  }
  input.stages = ReadStages(root);
  root.CheckNoUnknownKeys();
  return input;
}

ElementTestResult RunElementTestInput(const ConfigTable& root, const std::string& input,
                                      const std::string& out, const std::string& csv) {
  const ElementTestInput test = ReadElementTestInput(root);
  const ConstitutiveModel* model = test.model.get();
  const ElementTestResult result = ElementTest(*model, test.options).Run(test.initial, test.stages);
  Hdf5File file = Hdf5File::CreateAtomic(out);
  WriteElementTestResult(*model, result, "/element_test", &file);
  file.SetAttribute("/element_test", "input", input);
  file.Commit();
  if (!csv.empty()) WriteElementTestCsv(result, csv);
  return result;
}

}  // namespace granasym
