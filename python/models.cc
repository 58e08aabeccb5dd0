// The constitutive models: a model of a kind and its parameters (the keys of
// its [model] table, constitutive/model_traits.h), its element tests (the
// tables of a `granasym model run` file as dicts, read by
// ReadElementTestInput), its asymptotic states and its ASBS cross-section at
// a void ratio (calibration/asymptote_predictor.h).
#include <fmt/format.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "calibration/asymptote_predictor.h"
#include "common/config.h"
#include "common/error.h"
#include "common/quantity_names.h"
#include "common/state_measures.h"
#include "common/text_file.h"
#include "constitutive/model_config.h"
#include "constitutive/model_traits.h"
#include "python/bindings.h"

namespace py = pybind11;

namespace granasym::python {
namespace {

struct Model {
  ModelKind kind;
  py::dict parameters;
  std::string block;  // its [model] table
  std::unique_ptr<ConstitutiveModel> model;

  // The parameter vector of the traits (ModelTraits::parameters), which the
  // asymptotes need in full.
  std::vector<double> Values() const {
    std::vector<double> values;
    for (const FittedParameter& p : Traits(kind).parameters) {
      if (!parameters.contains(p.traits.key)) {
        throw InputError(fmt::format(
            "{}: the asymptotes need every parameter of the vector; '{}' ({}) is missing",
            ToString(kind), p.traits.key, p.traits.description));
      }
      values.push_back(parameters[p.traits.key].cast<double>());
    }
    return values;
  }
};

Model MakeModel(const std::string& kind, const py::dict& parameters) {
  Model m;
  const std::optional<ModelKind> k = FromString<ModelKind>(kind);
  if (!k) {
    throw InputError(
        fmt::format("model kind '{}' is not valid: expected {}", kind, AllowedNames<ModelKind>()));
  }
  m.kind = *k;
  m.parameters = py::dict(parameters);
  m.block = "[model]\nkind = " + TomlQuoted(kind) + "\n" + TomlTable(parameters, "model");
  const ConfigTable root = ConfigTable::ParseString(m.block, "granasym.Model(" + kind + ")");
  m.model = ReadModel(root.GetTable("model"));
  root.CheckNoUnknownKeys();
  return m;
}

struct ElementTestRun {
  ElementTestResult result;
};

py::object RecordsFrame(const ElementTestRun& run) {
  const std::vector<std::string> names = ElementTestColumnNames();
  const std::vector<std::vector<double>> values = ElementTestColumns(run.result);
  std::vector<std::pair<std::string, py::object>> columns;
  for (size_t c = 0; c < names.size(); ++c) columns.emplace_back(names[c], Array(values[c]));
  std::vector<double> stage;
  for (const ElementTestRecord& r : run.result.history) stage.push_back(r.stage);
  columns.emplace_back("stage", Array(stage).attr("astype")("int64"));
  py::dict units;
  for (const std::string& name : names) {
    if (name.size() > 4 && name.compare(name.size() - 4, 4, "_kpa") == 0)
      units[py::str(name)] = "kPa";
    if (name.size() > 4 && name.compare(name.size() - 4, 4, "_deg") == 0)
      units[py::str(name)] = "deg";
  }
  units[quantity::kTime] = "s";
  return DataFrame(columns, units);
}

ElementTestRun RunElementTest(const Model& m, const py::dict& initial, const py::list& stages,
                              const py::dict& integration) {
  std::string text = m.block + "\n[initial]\n" + TomlTable(initial, "initial");
  if (!integration.empty()) text += "\n[integration]\n" + TomlTable(integration, "integration");
  int k = 0;
  for (const py::handle stage : stages) {
    if (!py::isinstance<py::dict>(stage)) {
      throw InputError(fmt::format("stages[{}]: expected a dict of a [[stage]] table", k));
    }
    text += "\n[[stage]]\n" + TomlTable(stage.cast<py::dict>(), fmt::format("stage[{}]", k));
    ++k;
  }
  const ElementTestInput input =
      ReadElementTestInput(ConfigTable::ParseString(text, "granasym element_test"));
  ElementTestRun run;
  py::gil_scoped_release release;
  run.result = ElementTest(*input.model, input.options).Run(input.initial, input.stages);
  return run;
}

calibration::AsymptotePredictor Predictor(const Model& m) {
  return calibration::AsymptotePredictor(m.kind, calibration::PredictorOptions());
}

py::object Asymptotes(const Model& m, const std::vector<double>& psi_epsilon_deg,
                      const std::vector<double>& psi_sigma_deg) {
  std::vector<double> eps, sig;
  for (double x : psi_epsilon_deg) eps.push_back(x * kDegree);
  for (double x : psi_sigma_deg) sig.push_back(x * kDegree);
  std::vector<calibration::Prediction> by_stretching, by_stress;
  std::string why;
  if (!Predictor(m).Predict(m.Values(), eps, sig, &by_stretching, &by_stress, &why)) {
    throw InputError(std::string(ToString(m.kind)) + ": " + why);
  }
  std::vector<double> e, s, ocr, q, clamped;
  for (const auto* list : {&by_stretching, &by_stress}) {
    for (const calibration::Prediction& p : *list) {
      e.push_back(p.psi_epsilon / kDegree);
      s.push_back(p.psi_sigma / kDegree);
      ocr.push_back(std::exp(p.ln_ocr));
      q.push_back(StressRatio(p.psi_sigma));
      clamped.push_back(p.clamped ? 1 : 0);
    }
  }
  py::dict units;
  units[quantity::kPsiEpsilon] = "deg";
  units[quantity::kPsiSigma] = "deg";
  return DataFrame({{quantity::kPsiEpsilon, Array(e)},
                    {quantity::kPsiSigma, Array(s)},
                    {quantity::kOverconsolidation, Array(ocr)},
                    {"q_over_p", Array(q)},
                    {"clamped", Array(clamped).attr("astype")("bool")}},
                   units);
}

py::object StatesAtPressures(const Model& m, const std::vector<double>& psi_epsilon_deg,
                             const std::vector<double>& p_kpa) {
  if (psi_epsilon_deg.size() != p_kpa.size()) {
    throw InputError(
        fmt::format("states_at_pressures: {} values of psi_epsilon_deg, {} of p_kpa: "
                    "give one p per direction",
                    psi_epsilon_deg.size(), p_kpa.size()));
  }
  std::vector<double> eps;
  for (double x : psi_epsilon_deg) eps.push_back(x * kDegree);
  std::vector<calibration::StatePrediction> states;
  std::string why;
  if (!Predictor(m).PredictAtPressures(m.Values(), eps, p_kpa, &states, &why)) {
    throw InputError(std::string(ToString(m.kind)) + ": " + why);
  }
  std::vector<double> s, lnv, e, ocr;
  for (const calibration::StatePrediction& state : states) {
    s.push_back(state.psi_sigma / kDegree);
    lnv.push_back(state.ln_volume);
    e.push_back(std::expm1(state.ln_volume));
    ocr.push_back(std::exp(state.ln_ocr));
  }
  py::dict units;
  units[quantity::kPsiEpsilon] = "deg";
  units[quantity::kMeanStress] = "kPa";
  units[quantity::kPsiSigma] = "deg";
  return DataFrame({{quantity::kPsiEpsilon, Array(psi_epsilon_deg)},
                    {quantity::kMeanStress, Array(p_kpa)},
                    {quantity::kPsiSigma, Array(s)},
                    {quantity::kVoidRatio, Array(e)},
                    {quantity::kLnVolume, Array(lnv)},
                    {quantity::kOverconsolidation, Array(ocr)}},
                   units);
}

py::object AsbsSection(const Model& m, double void_ratio, int points) {
  if (!(void_ratio > 0) || points < 2) {
    throw InputError(fmt::format(
        "asbs_section: e = {}, points = {}: expected e > 0 and points >= 2", void_ratio, points));
  }
  std::vector<calibration::Prediction> curve;
  std::string why;
  if (!Predictor(m).Curve(m.Values(), points, &curve, &why)) {
    throw InputError(std::string(ToString(m.kind)) + ": " + why);
  }
  const double pe = m.model->EquivalentPressure(void_ratio);
  std::vector<double> s, e, ocr, p, q;
  for (const calibration::Prediction& c : curve) {
    s.push_back(c.psi_sigma / kDegree);
    e.push_back(c.psi_epsilon / kDegree);
    ocr.push_back(std::exp(c.ln_ocr));
    p.push_back(pe * std::exp(-c.ln_ocr));
    q.push_back(p.back() * StressRatio(c.psi_sigma));
  }
  py::dict units;
  units[quantity::kPsiSigma] = "deg";
  units[quantity::kPsiEpsilon] = "deg";
  units[quantity::kMeanStress] = "kPa";
  units[quantity::kDeviator] = "kPa";
  py::object frame = DataFrame({{quantity::kPsiSigma, Array(s)},
                                {quantity::kPsiEpsilon, Array(e)},
                                {quantity::kOverconsolidation, Array(ocr)},
                                {quantity::kMeanStress, Array(p)},
                                {quantity::kDeviator, Array(q)}},
                               units);
  frame.attr("attrs")["e"] = void_ratio;
  frame.attr("attrs")["p_e_star_kpa"] = pe;
  return frame;
}

}  // namespace

void BindModels(py::module_& module) {
  module.def(
      "model_parameters",
      [](const std::string& kind) {
        const std::optional<ModelKind> k = FromString<ModelKind>(kind);
        if (!k) {
          throw InputError(fmt::format("model kind '{}' is not valid: expected {}", kind,
                                       AllowedNames<ModelKind>()));
        }
        std::vector<std::string> key, unit, description;
        std::vector<double> typical, lower, upper;
        for (const FittedParameter& p : Traits(*k).parameters) {
          key.push_back(p.traits.key);
          unit.push_back(p.traits.unit);
          description.push_back(p.traits.description);
          typical.push_back(p.typical);
          lower.push_back(p.lower);
          upper.push_back(p.upper);
        }
        return DataFrame({{"parameter", py::cast(key)},
                          {"unit", py::cast(unit)},
                          {"typical", Array(typical)},
                          {"lower", Array(lower)},
                          {"upper", Array(upper)},
                          {"description", py::cast(description)}});
      },
      py::arg("kind"),
      "The parameter vector of a model kind (its traits): key, unit, typical value, default "
      "bounds of a fit, meaning.");

  py::class_<ElementTestRun>(module, "ElementTestResult",
                             "The records of an element test and its summary.")
      .def_property_readonly("records", &RecordsFrame,
                             "one row per record (the columns of `granasym model run --csv`, "
                             "and the stage's index)")
      .def_property_readonly(
          "arrays",
          [](const ElementTestRun& run) {
            const std::vector<std::string> names = ElementTestColumnNames();
            const std::vector<std::vector<double>> values = ElementTestColumns(run.result);
            py::dict arrays;
            for (size_t c = 0; c < names.size(); ++c) arrays[py::str(names[c])] = Array(values[c]);
            return arrays;
          },
          "the records' columns as numpy arrays")
      .def_property_readonly(
          "success", [](const ElementTestRun& run) { return run.result.summary.success(); },
          "whether every stage ran to its end or its stop")
      .def_property_readonly(
          "termination",
          [](const ElementTestRun& run) { return ToString(run.result.summary.termination); })
      .def_property_readonly("message",
                             [](const ElementTestRun& run) { return run.result.summary.message; })
      .def_property_readonly(
          "stops",
          [](const ElementTestRun& run) {
            std::vector<std::string> stops;
            for (const StageSummary& s : run.result.summary.stages) stops.push_back(s.stop);
            return stops;
          },
          "per stage: 'duration' or the stop that ended it, e.g. 'mean_stress=100'")
      .def("__repr__", [](const ElementTestRun& run) {
        return "<granasym.ElementTestResult " + run.result.summary.Report() + ">";
      });

  py::class_<Model>(module, "Model",
                    "A constitutive model: hypoplastic_clay, modified_cam_clay or "
                    "hypoplastic_sand with the keys of its [model] table.")
      .def(py::init(&MakeModel), py::arg("kind"), py::arg("parameters"))
      .def_property_readonly("kind", [](const Model& m) { return ToString(m.kind); })
      .def_property_readonly("parameters", [](const Model& m) { return py::dict(m.parameters); })
      .def_property_readonly("describe", [](const Model& m) { return m.model->Describe(); })
      .def(
          "equivalent_pressure",
          [](const Model& m, double e) { return m.model->EquivalentPressure(e); }, py::arg("e"),
          "Hvorslev's p_e* (kPa): the mean stress on the isotropic NCL at void ratio e")
      .def(
          "void_ratio_for_ocr",
          [](const Model& m, double p_kpa, double ocr) {
            return m.model->VoidRatioForOcr(p_kpa, ocr);
          },
          py::arg("p_kpa"), py::arg("ocr"), "the void ratio at which p_e*/p = ocr at p (kPa)")
      .def("element_test", &RunElementTest, py::arg("initial"), py::arg("stages"),
           py::arg("integration") = py::dict(),
           R"(Runs an element test: the tables of a `granasym model run` file as dicts.

initial: {mean_stress_kpa, psi_sigma_deg, void_ratio or ocr}.
stages: a list of [[stage]] tables, e.g. {"type": "proportional",
  "psi_epsilon_deg": 45.0, "stretching_rate": 1.0, "duration_s": 0.2,
  "stop": {"mean_stress_kpa": 500.0}}; types proportional,
  constant_radial_stress, isochoric, oedometric, isotropic and mixed (six
  Voigt rates, stress_controlled lists the stress-rate components).
integration: the optional [integration] table.)")
      .def("asymptotes", &Asymptotes, py::arg("psi_epsilon_deg") = std::vector<double>{},
           py::arg("psi_sigma_deg") = std::vector<double>{},
           "The asymptotic states of stretching directions psi_epsilon_deg, then of stress "
           "directions psi_sigma_deg (the ASBS): psi_sigma_deg, OCR = p_e*/p, q/p (models with a "
           "linear NCL)")
      .def("states_at_pressures", &StatesAtPressures, py::arg("psi_epsilon_deg"), py::arg("p_kpa"),
           "The state that proportional stretching at each psi_epsilon_deg reaches at the "
           "paired p (the sand model's asymptotes, which depend on p)")
      .def("asbs_section", &AsbsSection, py::arg("e"), py::arg("points") = 200,
           "The ASBS cross-section at void ratio e: p and q (kPa) of the asymptotic states of "
           "`points` stress directions, p = p_e*(e)/OCR (models with a linear NCL)")
      .def("__repr__",
           [](const Model& m) { return "<granasym.Model " + m.model->Describe() + ">"; });
}

}  // namespace granasym::python
