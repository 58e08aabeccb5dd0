// Every numeric key of the three models' test files against NaN, ±inf, 0, a
// negative number, 1e308 and 1e-300: rejected with a message naming the key
// and the value, or listed here as valid and accepted. And states outside a
// model's domain: rejected at the start, a failure during a run.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/error.h"
#include "constitutive/model_config.h"
#include "tests/common/hostile_values.h"

namespace granasym {
namespace {

struct Key {
  std::string name;  // dotted name as messages spell it
  std::string mark;  // placeholder in the template
  std::string valid;
  std::set<std::string> accepted;  // hostile values that are valid settings
};

struct ModelTemplate {
  std::string kind;
  std::string text;
  std::vector<Key> keys;
};

// Stages and integration options shared by the three templates.
const char* kStages = R"(
[integration]
relative_tolerance = {rtol}
absolute_tolerance = {atol}
max_strain_increment = {dmax}
limit_point_condition = {limit}
[[stage]]
name = "isotropic"
type = "isotropic"
target_mean_stress_kpa = {target}
stretching_rate = {rate}
[[stage]]
name = "proportional"
type = "proportional"
psi_epsilon_deg = {psie}
duration_s = {duration}
output_points = {points}
[stage.stop]
mean_stress_kpa = {stop_p}
axial_strain = {stop_ea}
volumetric_strain = {stop_ev}
shear_strain = {stop_es}
strain_path = {stop_path}
stress_ratio = {stop_ratio}
asymptote = {stop_asym}
[[stage]]
name = "radial"
type = "constant_radial_stress"
axial_rate = {axial_rate}
[[stage]]
name = "mixed"
type = "mixed"
rate = [{voigt}, 0.0, 0.0, 0.0, 0.0, 0.0]
)";

std::vector<Key> SharedKeys(int first_stage) {
  auto stage = [&](int k, const std::string& key) {
    return "stage[" + std::to_string(first_stage + k) + "]." + key;
  };
  return {
      {"integration.relative_tolerance", "rtol", "1e-8", {}},
      {"integration.absolute_tolerance", "atol", "1e-8", {}},
      {"integration.max_strain_increment", "dmax", "0.01", {}},
      {"integration.limit_point_condition", "limit", "1e-6", {}},
      {stage(0, "target_mean_stress_kpa"), "target", "200.0", {}},
      {stage(0, "stretching_rate"), "rate", "1.0", {}},
      {stage(1, "psi_epsilon_deg"), "psie", "90.0", {"0", "-1"}},
      {stage(1, "duration_s"), "duration", "1.0", {}},
      {stage(1, "output_points"), "points", "100", {}},
      {stage(1, "stop.mean_stress_kpa"), "stop_p", "1000.0", {}},
      {stage(1, "stop.axial_strain"), "stop_ea", "0.3", {"0", "-1"}},
      {stage(1, "stop.volumetric_strain"), "stop_ev", "0.3", {"0", "-1"}},
      {stage(1, "stop.shear_strain"), "stop_es", "0.3", {"0", "-1"}},
      {stage(1, "stop.strain_path"), "stop_path", "0.5", {}},
      {stage(1, "stop.stress_ratio"), "stop_ratio", "1.0", {"0", "-1"}},
      {stage(1, "stop.asymptote"), "stop_asym", "1e-7", {}},
      {stage(2, "axial_rate"), "axial_rate", "1.0", {"0", "-1"}},
      {stage(3, "rate[0]"), "voigt", "-1.0", {"0", "-1"}},
  };
}

std::vector<ModelTemplate> Templates() {
  ModelTemplate clay{"hypoplastic_clay",
                     R"([model]
kind = "hypoplastic_clay"
phi_c_deg = {phi}
lambda_star = {lambda}
kappa_star = {kappa}
n_intercept = {N}
r = {r}
reference_pressure_kpa = {pr}
minimum_mean_stress_kpa = {pmin}
[initial]
mean_stress_kpa = {p0}
psi_sigma_deg = {psi0}
ocr = {ocr}
)",
                     {{"model.phi_c_deg", "phi", "22.6", {}},
                      {"model.lambda_star", "lambda", "0.11", {}},
                      {"model.kappa_star", "kappa", "0.016", {}},
                      {"model.n_intercept", "N", "1.375", {}},
                      {"model.r", "r", "0.4", {}},
                      {"model.reference_pressure_kpa", "pr", "1.0", {}},
                      {"model.minimum_mean_stress_kpa", "pmin", "1e-9", {}},
                      {"initial.mean_stress_kpa", "p0", "50.0", {}},
                      {"initial.psi_sigma_deg", "psi0", "0.0", {"0", "-1"}},
                      {"initial.ocr", "ocr", "2.0", {}}}};
  ModelTemplate sand{"hypoplastic_sand",
                     R"([model]
kind = "hypoplastic_sand"
phi_c_deg = {phi}
h_s_kpa = {hs}
n = {n}
e_d0 = {ed}
e_c0 = {ec}
e_i0 = {ei}
alpha = {alpha}
beta = {beta}
[initial]
mean_stress_kpa = {p0}
void_ratio = {e0}
)",
                     {{"model.phi_c_deg", "phi", "33.0", {}},
                      {"model.h_s_kpa", "hs", "1.5e6", {}},
                      {"model.n", "n", "0.28", {}},
                      {"model.e_d0", "ed", "0.55", {}},
                      {"model.e_c0", "ec", "0.95", {}},
                      {"model.e_i0", "ei", "1.05", {}},
                      {"model.alpha", "alpha", "0.25", {}},
                      {"model.beta", "beta", "1.5", {}},
                      {"initial.mean_stress_kpa", "p0", "100.0", {}},
                      {"initial.void_ratio", "e0", "0.8", {}}}};
  ModelTemplate cam{"modified_cam_clay",
                    R"([model]
kind = "modified_cam_clay"
critical_state_ratio = {M}
lambda_star = {lambda}
kappa_star = {kappa}
n_intercept = {N}
poisson_ratio = {nu}
yield_tolerance = {ytol}
rate_form_band = {band}
[initial]
mean_stress_kpa = {p0}
ocr = {ocr}
)",
                    {{"model.critical_state_ratio", "M", "0.9", {}},
                     {"model.lambda_star", "lambda", "0.11", {}},
                     {"model.kappa_star", "kappa", "0.016", {}},
                     {"model.n_intercept", "N", "1.375", {}},
                     {"model.poisson_ratio", "nu", "0.25", {"0"}},
                     {"model.yield_tolerance", "ytol", "1e-9", {}},
                     {"model.rate_form_band", "band", "1e-6", {}},
                     {"initial.mean_stress_kpa", "p0", "50.0", {}},
                     {"initial.ocr", "ocr", "2.0", {}}}};
  std::vector<ModelTemplate> templates = {clay, sand, cam};
  for (ModelTemplate& t : templates) {
    t.text += kStages;
    for (const Key& key : SharedKeys(0)) t.keys.push_back(key);
  }
  return templates;
}

const std::vector<std::pair<std::string, std::string>> kValues = {
    {"nan", "nan"}, {"inf", "inf"},      {"-inf", "-inf"},     {"0", "0"},
    {"-1", "-1"},   {"1e308", "1e+308"}, {"1e-300", "1e-300"},
};

std::string With(const ModelTemplate& t, const Key* target, const std::string& value) {
  std::string text = t.text;
  for (const Key& key : t.keys) {
    const std::string mark = "{" + key.mark + "}";
    const size_t at = text.find(mark);
    EXPECT_NE(at, std::string::npos) << t.kind << " " << mark;
    if (at != std::string::npos) {
      text.replace(at, mark.size(), &key == target ? value : key.valid);
    }
  }
  return text;
}

// Reads everything a `model run` reads before it integrates.
void Read(const std::string& text) {
  const ConfigTable root = ConfigTable::ParseString(text, "hostile_model.toml");
  const std::unique_ptr<ConstitutiveModel> model = ReadModel(root.GetTable("model"));
  ReadInitialState(*model, root.GetTable("initial"));
  ReadElementTestOptions(root.GetTable("integration"));
  ReadStages(root);
  root.CheckNoUnknownKeys();
}

TEST(ModelHostileValues, TheTemplatesAreValid) {
  for (const ModelTemplate& t : Templates()) {
    EXPECT_NO_THROW(Read(With(t, nullptr, ""))) << t.kind;
  }
}

TEST(ModelHostileValues, EveryNumericKeyRejectsOrAcceptsEachValueAsListed) {
  int cases = 0;
  for (const ModelTemplate& t : Templates()) {
    for (const Key& key : t.keys) {
      for (const auto& [literal, spelling] : granasym::testing::HostileNumbers()) {
        ++cases;
        std::string message;
        try {
          Read(With(t, &key, literal));
        } catch (const InputError& error) {
          message = error.what();
        } catch (const std::exception& error) {
          ADD_FAILURE() << t.kind << " " << key.name << " = " << literal
                        << ": not an input error: " << error.what();
          continue;
        }
        const std::string what = t.kind + " " + key.name + " = " + literal;
        granasym::testing::ExpectOutcome(what, key.accepted.count(literal) > 0, message,
                                         "hostile_model.toml", "'" + key.name + "'", spelling);
      }
    }
  }
  EXPECT_EQ(cases, 7 * (10 + 10 + 9 + 3 * 18));
}

std::string ErrorOf(const std::string& text) {
  try {
    Read(text);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(ModelDomain, StatesOutsideTheModelsDomainAreRejectedAtTheStart) {
  const std::vector<ModelTemplate> t = Templates();
  const ModelTemplate& clay = t[0];
  const ModelTemplate& sand = t[1];
  const ModelTemplate& cam = t[2];
  auto key = [](const ModelTemplate& m, const std::string& mark) {
    for (const Key& k : m.keys) {
      if (k.mark == mark) return &k;
    }
    ADD_FAILURE() << mark;
    return &m.keys.front();
  };
  // Clay looser than its NCL (OCR < 1).
  std::string message = ErrorOf(With(clay, key(clay, "ocr"), "0.5"));
  EXPECT_NE(message.find("'initial.ocr' = 0.5"), std::string::npos) << message;
  // Clay and Cam clay at 1e6 kPa: the NCL gives e < 0 there.
  for (const ModelTemplate* m : {&clay, &cam}) {
    message = ErrorOf(With(*m, key(*m, "p0"), "1e6"));
    EXPECT_NE(message.find("[initial]"), std::string::npos) << m->kind << ": " << message;
    EXPECT_NE(message.find("must be > 0"), std::string::npos) << m->kind << ": " << message;
  }
  // Sand looser than e_i.
  message = ErrorOf(With(sand, key(sand, "e0"), "1.2"));
  EXPECT_NE(message.find("above the loosest e_i"), std::string::npos) << message;
  // A negative intercept is out of range by itself, whatever the state.
  message = ErrorOf(With(clay, key(clay, "N"), "-5"));
  EXPECT_NE(message.find("'model.n_intercept' = -5"), std::string::npos) << message;
  // A consistency check of several parameters names the table, not one key.
  message = ErrorOf(With(clay, key(clay, "kappa"), "0.2"));
  EXPECT_NE(message.find("kappa_star"), std::string::npos) << message;
}

TEST(ModelDomain, CompressionTowardsANegativeVoidRatioFailsInsteadOfRecordingIt) {
  // ln(1+e) = 1.375 - 0.11 ln p reaches 0 at p = 2.7e5 kPa: compression to
  // 1e7 kPa must stop with a failure before e <= 0, with every record valid.
  const std::string text = R"([model]
kind = "hypoplastic_clay"
phi_c_deg = 22.6
lambda_star = 0.11
kappa_star = 0.016
n_intercept = 1.375
r = 0.4
[initial]
mean_stress_kpa = 100.0
ocr = 1.0
[[stage]]
type = "isotropic"
target_mean_stress_kpa = 1e7
stretching_rate = 1.0
duration_s = 100.0
)";
  const ConfigTable root = ConfigTable::ParseString(text, "to_zero.toml");
  const std::string out = (std::filesystem::temp_directory_path() / "granasym_to_zero.h5").string();
  const ElementTestResult result = RunElementTestInput(root, "to_zero.toml", out, "");
  EXPECT_FALSE(result.summary.success()) << result.summary.Report();
  ASSERT_FALSE(result.history.empty());
  for (const ElementTestRecord& record : result.history) {
    EXPECT_GT(record.void_ratio, 0.0) << "p " << record.stress[0];
  }
  // The failure says why, in the model's terms.
  EXPECT_NE(result.summary.Report().find("void ratio e = -"), std::string::npos)
      << result.summary.Report();
  EXPECT_NE(result.summary.Report().find("must be > 0"), std::string::npos)
      << result.summary.Report();
  std::filesystem::remove(out);
}

}  // namespace
}  // namespace granasym
