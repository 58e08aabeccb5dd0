// The models' traits: consistent tables, a [model] table and a parameter
// vector that make the same model, and the facts that differ by model.
#include "constitutive/model_traits.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "common/error.h"
#include "common/state_measures.h"
#include "constitutive/element_driver.h"
#include "constitutive/model_config.h"
#include "constitutive/modified_cam_clay.h"
#include "tests/common/enum_spellings.h"

namespace granasym {
namespace {

std::vector<double> TypicalValues(const ModelTraits& traits) {
  std::vector<double> values;
  for (const FittedParameter& p : traits.parameters) values.push_back(p.typical);
  return values;
}

// A [model] table with the typical value of every parameter.
std::string TypicalModelTable(const ModelTraits& traits) {
  std::string text = std::string("[model]\nkind = \"") + ToString(traits.kind) + "\"\n";
  for (const FittedParameter& p : traits.parameters) {
    text += std::string(p.traits.key) + " = " + std::to_string(p.typical) + "\n";
  }
  return text;
}

TEST(ModelTraits, EveryModelHasOneTableOfItsOwnKind) {
  for (ModelKind kind : EnumValues<ModelKind>()) {
    const ModelTraits& traits = Traits(kind);
    EXPECT_EQ(traits.kind, kind);
    EXPECT_FALSE(std::string(traits.title).empty());
    EXPECT_EQ(traits.parameters.size(), traits.linear_ncl ? static_cast<size_t>(kNumClayParameters)
                                                          : static_cast<size_t>(kNumSandParameters))
        << ToString(kind);
    EXPECT_TRUE(traits.read != nullptr && traits.make != nullptr &&
                traits.export_orders != nullptr);
  }
}

TEST(ModelTraits, KeysAreUniqueAndEveryEntryIsComplete) {
  for (ModelKind kind : EnumValues<ModelKind>()) {
    const ModelTraits& traits = Traits(kind);
    std::set<std::string> keys;
    std::vector<ParameterTraits> all;
    for (const FittedParameter& p : traits.parameters) all.push_back(p.traits);
    all.insert(all.end(), traits.other_keys.begin(), traits.other_keys.end());
    for (const ParameterTraits& p : all) {
      EXPECT_TRUE(keys.insert(p.key).second) << ToString(kind) << " repeats " << p.key;
      EXPECT_FALSE(std::string(p.symbol).empty()) << p.key;
      EXPECT_FALSE(std::string(p.description).empty()) << p.key;
      EXPECT_TRUE(std::string(p.unit) == "1" || std::string(p.unit) == "deg" ||
                  std::string(p.unit) == "kPa")
          << p.key << ": " << p.unit;
      // Units in the key where the quantity has one.
      if (std::string(p.unit) != "1") {
        EXPECT_NE(std::string(p.key).find(std::string("_") +
                                          (p.unit == std::string("deg") ? "deg" : "kpa")),
                  std::string::npos)
            << p.key;
      }
    }
  }
}

TEST(ModelTraits, CalibrationStartsAndBoundsLieInTheValidRange) {
  for (ModelKind kind : EnumValues<ModelKind>()) {
    for (const FittedParameter& p : Traits(kind).parameters) {
      EXPECT_LT(p.lower, p.upper) << p.traits.key;
      EXPECT_GE(p.typical, p.lower) << p.traits.key;
      EXPECT_LE(p.typical, p.upper) << p.traits.key;
      EXPECT_TRUE(p.traits.range.Contains(p.lower)) << p.traits.key;
      EXPECT_TRUE(p.traits.range.Contains(p.upper)) << p.traits.key;
    }
  }
}

// The two ways to a model, a [model] table and a parameter vector, agree.
TEST(ModelTraits, AModelTableAndTheParameterVectorMakeTheSameModel) {
  for (ModelKind kind : EnumValues<ModelKind>()) {
    const ModelTraits& traits = Traits(kind);
    const ConfigTable root = ConfigTable::ParseString(TypicalModelTable(traits), "typical.toml");
    const std::unique_ptr<ConstitutiveModel> read = ReadModel(root.GetTable("model"));
    EXPECT_NO_THROW(root.CheckNoUnknownKeys()) << ToString(kind);
    std::string why;
    // std::to_string writes 6 decimals: the typical values are exact in it.
    const std::unique_ptr<ConstitutiveModel> made = traits.make(TypicalValues(traits), &why);
    ASSERT_TRUE(made) << ToString(kind) << ": " << why;
    EXPECT_EQ(read->kind(), kind);
    EXPECT_EQ(read->Describe(), made->Describe());
  }
}

TEST(ModelTraits, InvalidVectorsMakeNoModelAndSayWhy) {
  for (ModelKind kind : EnumValues<ModelKind>()) {
    const ModelTraits& traits = Traits(kind);
    std::vector<double> values = TypicalValues(traits);
    values[0] = 95.0;  // φ_c beyond 90°
    std::string why;
    EXPECT_FALSE(traits.make(values, &why)) << ToString(kind);
    EXPECT_FALSE(why.empty()) << ToString(kind);
  }
  std::vector<double> clay = TypicalValues(Traits(ModelKind::kModifiedCamClay));
  clay[kKappaStar] = clay[kLambdaStar];
  std::string why;
  EXPECT_FALSE(Traits(ModelKind::kModifiedCamClay).make(clay, &why));
  EXPECT_NE(why.find("kappa"), std::string::npos) << why;
}

TEST(ModelTraits, TheExportsListEveryParameterValue) {
  for (ModelKind kind : EnumValues<ModelKind>()) {
    const ModelTraits& traits = Traits(kind);
    const std::vector<double> values = TypicalValues(traits);
    for (const ExportedParameters& order : traits.export_orders(values)) {
      EXPECT_FALSE(order.program.empty());
      EXPECT_GE(order.values.size(), traits.parameters.size() - 1) << order.program;
    }
  }
  // Sand: the UMAT order, φ_c, p_t, then the rest of the vector.
  const std::vector<double> sand = TypicalValues(Traits(ModelKind::kHypoplasticSand));
  const ExportedParameters umat = Traits(ModelKind::kHypoplasticSand).export_orders(sand).front();
  ASSERT_EQ(umat.values.size(), 9u);
  EXPECT_EQ(umat.values[0].first, "phi_c_deg");
  EXPECT_EQ(umat.values[1].first, "p_t_kpa");
  EXPECT_EQ(umat.values[2].first, "h_s_kpa");
  EXPECT_EQ(umat.values[8].first, "beta");
  EXPECT_DOUBLE_EQ(umat.values[8].second, sand[kSandStiffnessExponent]);
}

TEST(ModelTraits, TheDefaultIntegratorTakesTheModelsTolerance) {
  for (ModelKind kind : EnumValues<ModelKind>()) {
    const IntegratorOptions options = DefaultIntegratorOptions(kind);
    EXPECT_EQ(options.relative_tolerance, Traits(kind).integrator_tolerance);
    EXPECT_EQ(options.absolute_tolerance, Traits(kind).integrator_tolerance);
  }
}

TEST(ModelTraits, RolesAreSpelledAsInTheirTables) {
  ExpectSpellings<ParameterStart>({{ParameterStart::kTypical, "typical"},
                                   {ParameterStart::kCslStressRatio, "csl_stress_ratio"},
                                   {ParameterStart::kNclSlope, "ncl_slope"},
                                   {ParameterStart::kUnloadingSlope, "unloading_slope"},
                                   {ParameterStart::kNclIntercept, "ncl_intercept"},
                                   {ParameterStart::kBauerNcl, "bauer_ncl"},
                                   {ParameterStart::kCslVoidRatio, "csl_void_ratio"},
                                   {ParameterStart::kDensestFraction, "densest_fraction"}});
  ExpectSpellings<Identification>(
      {{Identification::kAnyState, "any_state"},
       {Identification::kTwoMeanStresses, "two_mean_stresses"},
       {Identification::kOffIsotropicAxis, "off_isotropic_axis"},
       {Identification::kTwoOffAxisDirections, "two_off_axis_directions"},
       {Identification::kJacobian, "jacobian"}});
}

// The models with a linear NCL have closed-form asymptotes by stress
// direction; the sand has none.
TEST(ModelTraits, ClosedFormAsymptotesExistExactlyForTheLinearNclModels) {
  for (ModelKind kind : EnumValues<ModelKind>()) {
    const ModelTraits& traits = Traits(kind);
    std::string why;
    const std::unique_ptr<ConstitutiveModel> model = traits.make(TypicalValues(traits), &why);
    ASSERT_TRUE(model) << why;
    double psi_epsilon = 0.0, ln_ocr = 0.0;
    EXPECT_EQ(model->AsymptoteOfStressDirection(0.1, &psi_epsilon, &ln_ocr, &why),
              traits.linear_ncl)
        << ToString(kind) << ": " << why;
  }
}

// On the critical state line: isochoric stretching (ψ_ε = 90°) and
// OCR_c = 2^(1 − κ*/λ*) (SPEC §6.2); on the isotropic axis the NCL itself.
TEST(ModifiedCamClay, ClosedFormAsymptotesMeetTheCriticalStateAndTheNcl) {
  const ModifiedCamClay model(ModifiedCamClay::Parameters::LondonClayNcl());
  const double m = model.parameters().critical_state_ratio;
  const double psi_c = std::atan(std::sqrt(2.0) / 3.0 * m);
  double psi_epsilon = 0.0, ln_ocr = 0.0;
  std::string why;
  ASSERT_TRUE(model.AsymptoteOfStressDirection(psi_c, &psi_epsilon, &ln_ocr, &why)) << why;
  EXPECT_NEAR(psi_epsilon, 0.5 * kPi, 1e-12);
  EXPECT_NEAR(ln_ocr, (1.0 - 0.016 / 0.11) * std::log(2.0), 1e-12);
  ASSERT_TRUE(model.AsymptoteOfStressDirection(0.0, &psi_epsilon, &ln_ocr, &why)) << why;
  EXPECT_NEAR(psi_epsilon, 0.0, 1e-15);
  EXPECT_NEAR(ln_ocr, 0.0, 1e-15);
  ModifiedCamClay::Parameters semi_log = ModifiedCamClay::Parameters::LondonClayNcl();
  semi_log.form = ModifiedCamClay::CompressionForm::kSemiLog;
  semi_log.n_intercept = 2.0;
  EXPECT_FALSE(
      ModifiedCamClay(semi_log).AsymptoteOfStressDirection(psi_c, &psi_epsilon, &ln_ocr, &why));
  EXPECT_NE(why.find("log-log"), std::string::npos) << why;
}

// A start outside the Cam clay yield surface is refused, with p_c and f.
TEST(ModifiedCamClay, AStartOutsideTheYieldSurfaceIsNotAdmissible) {
  const ModifiedCamClay model(ModifiedCamClay::Parameters::LondonClayNcl());
  try {
    InitialStateFromOcr(model, 100.0, 30.0 * kDegree, 1.0);
    FAIL() << "accepted a start outside the yield surface";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("outside the yield surface"), std::string::npos) << message;
    EXPECT_NE(message.find("p_c ="), std::string::npos) << message;
    EXPECT_NE(message.find("raise OCR"), std::string::npos) << message;
  }
  EXPECT_NO_THROW(InitialStateFromOcr(model, 100.0, 0.0, 1.0));
}

}  // namespace
}  // namespace granasym
