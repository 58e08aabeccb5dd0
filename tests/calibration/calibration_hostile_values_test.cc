// The bounds and values of every fitted parameter of the three calibrated
// models against NaN, ±inf, 0, a negative number, 1e308 and 1e-300: each is
// rejected with a message naming the key and the value unless it lies in the
// model's domain (e.g. phi_c in (0, 90) deg: bounds [0, 90] are not valid).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "calibration/calibration_config.h"
#include "calibration/model_parameters.h"
#include "common/config.h"
#include "common/error.h"
#include "tests/common/hostile_values.h"

namespace granasym::calibration {
namespace {

const std::vector<std::pair<std::string, std::string>> kValues = {
    {"nan", "nan"}, {"inf", "inf"},      {"-inf", "-inf"},     {"0", "0"},
    {"-1", "-1"},   {"1e308", "1e+308"}, {"1e-300", "1e-300"},
};

std::string Config(ModelKind kind, const std::string& parameter, const std::string& field,
                   const std::string& value) {
  return "[model]\nkind = \"" + std::string(ToString(kind)) + "\"\n[parameters." + parameter +
         "]\n" + field + " = " + value + "\n[[dataset]]\nname = \"d\"\ncsv = \"states.csv\"\n";
}

std::string ErrorOf(const std::string& text) {
  try {
    ReadCalibrationConfig(ConfigTable::ParseString(text, "hostile_calibration.toml"));
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(CalibrationHostileValues, EveryParameterValueAndBoundOutsideTheDomainIsRejected) {
  int cases = 0;
  for (ModelKind kind :
       {ModelKind::kHypoplasticClay, ModelKind::kModifiedCamClay, ModelKind::kHypoplasticSand}) {
    const ModelParameters defaults = ModelParameters::Defaults(kind);
    for (const ParameterSpec& spec : defaults.specs()) {
      for (const std::string field : {"value", "lower", "upper"}) {
        for (const auto& [literal, spelling] : granasym::testing::HostileNumbers()) {
          ++cases;
          const std::string message = ErrorOf(Config(kind, spec.name, field, literal));
          const std::string what =
              std::string(ToString(kind)) + " " + spec.name + "." + field + " = " + literal;
          // Valid: inside the domain, and consistent with the default bounds.
          const double number = std::stod(literal);
          const double lower = field == "lower" ? number : spec.lower;
          const double upper = field == "upper" ? number : spec.upper;
          const bool valid = spec.domain.Contains(number) &&
                             (number == 0 || std::abs(number) >= 1e-100) &&
                             std::abs(number) <= 1e100 && lower < upper &&
                             (field != "value" || (number >= lower && number <= upper));
          granasym::testing::ExpectOutcome(what, valid, message, "hostile_calibration.toml",
                                           "parameters." + spec.name + ".", spelling);
        }
      }
    }
  }
  EXPECT_EQ(cases, 3 * 7 * (5 + 5 + 8));
}

TEST(CalibrationHostileValues, ThePapersExamplesOfBadBoundsAreRejected) {
  // λ* from −1, and φ_c over [0°, 90°] (a fit there converged to 89.96°).
  EXPECT_NE(ErrorOf(Config(ModelKind::kHypoplasticClay, "lambda_star", "lower", "-1"))
                .find("'parameters.lambda_star.lower' = -1"),
            std::string::npos);
  const std::string both =
      "[model]\nkind = \"hypoplastic_clay\"\n[parameters.phi_c_deg]\nlower = 0.0\nupper = "
      "90.0\n[[dataset]]\ncsv = \"s.csv\"\n";
  EXPECT_NE(ErrorOf(both).find("'parameters.phi_c_deg.lower' = 0 is out of range: must be in "
                               "(0, 90)"),
            std::string::npos)
      << ErrorOf(both);
}

}  // namespace
}  // namespace granasym::calibration
