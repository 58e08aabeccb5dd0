// The tables of the three models' parameters, and how a [model] table and a
// parameter vector make each model.
#include "constitutive/model_traits.h"

#include <fmt/format.h>

#include <cmath>

#include "common/error.h"
#include "common/state_measures.h"
#include "constitutive/hypoplastic_clay.h"
#include "constitutive/hypoplastic_sand.h"
#include "constitutive/modified_cam_clay.h"

namespace granasym {

namespace {

// ---------------------------------------------------------------- the keys
//
// Every key of a [model] table, once. Ranges are the models' own conditions
// and sane magnitudes; calibration bounds its fits with the same ones. Written
// as aggregates {min, max, min_inclusive, max_inclusive} so that the tables
// are constant-initialized. Modified Cam clay's `form` key (log_log |
// semi_log) is an enumeration, named by EnumNames<CompressionForm>.
namespace parameter {

constexpr Range kVoidRatio = {0.0, 20.0, false, true};
constexpr Range kSlope = {0.0, 2.0, false, true};  // λ*, κ*, λ, κ
constexpr Range kMinimumMeanStressRange = {0.0, 1e3, false, true};

// Shared by the models (the clay models' NCL; φ_c of all three).
constexpr ParameterTraits kPhiC = {
    "phi_c_deg", "φ_c", "deg", {0.0, 90.0, false, false}, "critical state friction angle"};
constexpr ParameterTraits kLambdaStar = {"lambda_star", "λ*", "1", kSlope,
                                         "slope of the isotropic NCL in ln(1+e)-ln p"};
constexpr ParameterTraits kKappaStar = {"kappa_star", "κ*", "1", kSlope,
                                        "slope of isotropic unloading in ln(1+e)-ln p"};
constexpr ParameterTraits kNIntercept = {
    "n_intercept", "N", "1", {0.0, 10.0, false, true}, "ln(1+e) on the NCL at p_r = 1 kPa"};
constexpr ParameterTraits kReferencePressure = {"reference_pressure_kpa",
                                                "p_r",
                                                "kPa",
                                                kStressKpa,
                                                "reference pressure of the NCL (default 1 kPa)",
                                                true};
constexpr ParameterTraits kMinimumMeanStress = {
    "minimum_mean_stress_kpa",
    "p_min",
    "kPa",
    kMinimumMeanStressRange,
    "below this mean stress a state is outside the model's domain (default 1e-9 kPa)",
    true};

// Hypoplastic clay.
constexpr ParameterTraits kBulkShearRatio = {
    "r", "r", "1", {0.0, 100.0, false, true}, "bulk/shear stiffness ratio K/G on the NCL"};

// Modified Cam clay.
constexpr ParameterTraits kPoissonRatio = {"poisson_ratio",
                                           "ν",
                                           "1",
                                           {-1.0, 0.5, false, false},
                                           "Poisson ratio of the elastic law (default 0.25)",
                                           true};
constexpr ParameterTraits kCriticalStateRatio = {
    "critical_state_ratio",
    "M",
    "1",
    {0.0, 3.0, false, false},
    "q/p at the critical state in compression: instead of phi_c_deg"};
constexpr ParameterTraits kLambda = {"lambda", "λ", "1", kSlope,
                                     "slope of the NCL in e-ln p (form = \"semi_log\")"};
constexpr ParameterTraits kKappa = {"kappa", "κ", "1", kSlope,
                                    "slope of unloading in e-ln p (form = \"semi_log\")"};
constexpr ParameterTraits kVoidRatioIntercept = {"e_n", "e_N", "1", kVoidRatio,
                                                 "e on the NCL at p_r (form = \"semi_log\")"};
constexpr ParameterTraits kShearModulus = {"shear_modulus_kpa",
                                           "G",
                                           "kPa",
                                           {0.0, 1e9, false, true},
                                           "constant shear modulus: instead of poisson_ratio"};
constexpr ParameterTraits kYieldTolerance = {
    "yield_tolerance",
    "tol_f",
    "1",
    {0.0, 1e-2, false, false},
    "on the yield surface when f >= -tol_f (M p_c)^2 (default 1e-9)",
    true};
constexpr ParameterTraits kRateFormBand = {
    "rate_form_band",
    "b_f",
    "1",
    {0.0, 1e-2, false, false},
    "rate form: plastic when f >= -b_f (M p_c)^2 (default 1e-4)",
    true};

// Hypoplastic sand.
constexpr ParameterTraits kGranularHardness = {
    "h_s_kpa", "h_s", "kPa", {0.0, 1e9, false, true}, "granular hardness of Bauer's law"};
constexpr ParameterTraits kBauerExponent = {
    "n", "n", "1", {0.0, 1.0, false, false}, "exponent of Bauer's law"};
constexpr ParameterTraits kDensestVoidRatio = {"e_d0", "e_d0", "1", kVoidRatio,
                                               "densest void ratio at p = 0"};
constexpr ParameterTraits kCriticalVoidRatio = {"e_c0", "e_c0", "1", kVoidRatio,
                                                "critical void ratio at p = 0"};
constexpr ParameterTraits kLoosestVoidRatio = {"e_i0", "e_i0", "1", kVoidRatio,
                                               "loosest void ratio at p = 0 (isotropic NCL)"};
constexpr ParameterTraits kPyknotropyExponent = {
    "alpha", "α", "1", {0.0, 10.0, false, true}, "pyknotropy exponent of f_d"};
constexpr ParameterTraits kStiffnessExponent = {
    "beta", "β", "1", {0.0, 10.0, false, true}, "stiffness exponent of f_e"};

}  // namespace parameter

// ---------------------------------------------------------------- reading

// Reads the keys of one [model] table.
class KeyReader {
 public:
  explicit KeyReader(const ConfigTable& table) : table_(table) {}

  double operator()(const ParameterTraits& p) const { return table_.GetDouble(p.key, p.range); }
  // An optional key: `fallback` (the model's default) when absent.
  double operator()(const ParameterTraits& p, double fallback) const {
    return table_.GetDouble(p.key, fallback, p.range);
  }
  bool Has(const ParameterTraits& p) const { return table_.Has(p.key); }
  template <typename E>
  E Enum(const char* key, E fallback) const {
    return table_.GetEnum(key, fallback);
  }

  // `smaller` < `larger`: else an error at the key read last, `at_larger`
  // or not, whose message names both keys and values.
  void RequireOrder(const ParameterTraits& smaller, double smaller_value,
                    const ParameterTraits& larger, double larger_value, bool at_larger) const {
    if (smaller_value < larger_value) return;
    if (at_larger) {
      table_.Fail(larger.key, fmt::format("{} = {} must be greater than {} = {}", larger.key,
                                          larger_value, smaller.key, smaller_value));
    }
    table_.Fail(smaller.key, fmt::format("{} = {} must be smaller than {} = {}", smaller.key,
                                         smaller_value, larger.key, larger_value));
  }
  // Exactly one of two alternative keys.
  void RequireOneOf(const ParameterTraits& blamed, const ParameterTraits& other) const {
    if (Has(blamed) == Has(other)) {
      table_.Fail(blamed.key, fmt::format("give exactly one of {} ({}) and {}", blamed.key,
                                          blamed.symbol, other.key));
    }
  }
  // A failed consistency check of several keys together.
  [[noreturn]] void FailParameters(const std::string& why) const {
    throw InputError(fmt::format("{}: [{}]: the parameters are not consistent: {}", table_.origin(),
                                 table_.KeyName(""), why));
  }

 private:
  const ConfigTable& table_;
};

// ---------------------------------------------------------------- hypoplastic clay

HypoplasticClay::Parameters ClayParameters(const std::vector<double>& v) {
  HypoplasticClay::Parameters p;
  p.critical_friction_angle = v[kCriticalFrictionAngle] * kDegree;
  p.lambda_star = v[kLambdaStar];
  p.kappa_star = v[kKappaStar];
  p.n_intercept = v[kNIntercept];
  p.bulk_shear_ratio = v[kShearParameter];
  return p;
}

std::unique_ptr<ConstitutiveModel> MakeHypoplasticClay(const std::vector<double>& v,
                                                       std::string* why) {
  const HypoplasticClay::Parameters p = ClayParameters(v);
  if (!p.IsValid(why)) return nullptr;
  return std::make_unique<HypoplasticClay>(p);
}

std::unique_ptr<ConstitutiveModel> ReadHypoplasticClay(const ConfigTable& table) {
  const KeyReader read(table);
  std::vector<double> v(kNumClayParameters);
  v[kCriticalFrictionAngle] = read(parameter::kPhiC);
  v[kLambdaStar] = read(parameter::kLambdaStar);
  v[kKappaStar] = read(parameter::kKappaStar);
  read.RequireOrder(parameter::kKappaStar, v[kKappaStar], parameter::kLambdaStar, v[kLambdaStar],
                    false);
  v[kNIntercept] = read(parameter::kNIntercept);
  v[kShearParameter] = read(parameter::kBulkShearRatio);
  HypoplasticClay::Parameters p = ClayParameters(v);
  p.reference_pressure = read(parameter::kReferencePressure, p.reference_pressure);
  p.minimum_mean_stress = read(parameter::kMinimumMeanStress, p.minimum_mean_stress);
  std::string why;
  if (!p.IsValid(&why)) read.FailParameters(why);
  return std::make_unique<HypoplasticClay>(p);
}

std::vector<ExportedParameters> HypoplasticClayExports(const std::vector<double>& v) {
  const double phi = v[kCriticalFrictionAngle];
  const double lambda = v[kLambdaStar], kappa = v[kKappaStar];
  const double n = v[kNIntercept], r = v[kShearParameter];
  // Mašín's clay hypoplasticity UMAT (Abaqus, 2005 form) reads props 1-5 as
  // φ_c, λ*, κ*, N, r (then the intergranular-strain parameters, not fitted here).
  // The soilmodels.com UMAT/PLAXIS UDSM form puts the tensile shift p_t second.
  return {{"UMAT clay hypoplasticity (Masin 2005), props 1-5",
           {{parameter::kPhiC.key, phi},
            {parameter::kLambdaStar.key, lambda},
            {parameter::kKappaStar.key, kappa},
            {"N", n},
            {parameter::kBulkShearRatio.key, r}}},
          {"PLAXIS UDSM / soilmodels.com UMAT (p_t second), parameters 1-6",
           {{parameter::kPhiC.key, phi},
            {"p_t_kpa", 0.0},
            {parameter::kLambdaStar.key, lambda},
            {parameter::kKappaStar.key, kappa},
            {"N", n},
            {parameter::kBulkShearRatio.key, r}}}};
}

ModelTraits HypoplasticClayTraits() {
  // Bounds wide enough for clays and for DEM sphere packings (small λ*).
  // Parameters: {key, start from, identified by, typical, lower, upper}.
  return {ModelKind::kHypoplasticClay,
          "hypoplastic clay",
          {{parameter::kPhiC, ParameterStart::kCslStressRatio, Identification::kOffIsotropicAxis,
            25.0, 5.0, 50.0},
           {parameter::kLambdaStar, ParameterStart::kNclSlope, Identification::kTwoMeanStresses,
            0.1, 1e-3, 0.5},
           // κ* acts on the asymptotes only through the OCR of non-isotropic states.
           {parameter::kKappaStar, ParameterStart::kUnloadingSlope,
            Identification::kOffIsotropicAxis, 0.02, 1e-4, 0.2},
           {parameter::kNIntercept, ParameterStart::kNclIntercept, Identification::kAnyState, 1.0,
            0.05, 4.0},
           {parameter::kBulkShearRatio, ParameterStart::kTypical,
            Identification::kTwoOffAxisDirections, 0.4, 0.01, 3.0}},
          {parameter::kReferencePressure, parameter::kMinimumMeanStress},
          /*linear_ncl=*/true,
          /*critical_state_ocr=*/"2",
          /*integrator_tolerance=*/1e-8,
          ReadHypoplasticClay,
          MakeHypoplasticClay,
          HypoplasticClayExports};
}

// ---------------------------------------------------------------- Modified Cam clay

std::unique_ptr<ConstitutiveModel> MakeModifiedCamClay(const std::vector<double>& v,
                                                       std::string* why) {
  ModifiedCamClay::Parameters p;
  const double phi = v[kCriticalFrictionAngle] * kDegree;
  if (!(phi > 0 && phi < 0.5 * kPi)) {
    *why = fmt::format("{} = {} must be {}", parameter::kPhiC.key, v[kCriticalFrictionAngle],
                       parameter::kPhiC.range.Describe());
    return nullptr;
  }
  p.critical_state_ratio = CriticalStateRatio(phi);
  p.lambda = v[kLambdaStar];
  p.kappa = v[kKappaStar];
  p.n_intercept = v[kNIntercept];
  p.poisson_ratio = v[kShearParameter];
  if (!p.IsValid(why)) return nullptr;
  return std::make_unique<ModifiedCamClay>(p);
}

// The form (log-log: λ*, κ*, N; semi-log: λ, κ, e_N), M or φ_c, and ν or G.
std::unique_ptr<ConstitutiveModel> ReadModifiedCamClay(const ConfigTable& table) {
  const KeyReader read(table);
  ModifiedCamClay::Parameters p;
  p.form = read.Enum("form", ModifiedCamClay::CompressionForm::kLogLog);
  read.RequireOneOf(parameter::kCriticalStateRatio, parameter::kPhiC);
  p.critical_state_ratio = read.Has(parameter::kCriticalStateRatio)
                               ? read(parameter::kCriticalStateRatio)
                               : CriticalStateRatio(read(parameter::kPhiC) * kDegree);
  const bool log_log = p.form == ModifiedCamClay::CompressionForm::kLogLog;
  const ParameterTraits& lambda = log_log ? parameter::kLambdaStar : parameter::kLambda;
  const ParameterTraits& kappa = log_log ? parameter::kKappaStar : parameter::kKappa;
  p.lambda = read(lambda);
  p.kappa = read(kappa);
  read.RequireOrder(kappa, p.kappa, lambda, p.lambda, false);
  p.n_intercept = read(log_log ? parameter::kNIntercept : parameter::kVoidRatioIntercept);
  if (read.Has(parameter::kShearModulus)) {
    p.elasticity = ModifiedCamClay::Elasticity::kConstantShearModulus;
    p.shear_modulus = read(parameter::kShearModulus);
  } else {
    p.poisson_ratio = read(parameter::kPoissonRatio, p.poisson_ratio);
  }
  p.reference_pressure = read(parameter::kReferencePressure, p.reference_pressure);
  p.yield_tolerance = read(parameter::kYieldTolerance, p.yield_tolerance);
  p.rate_form_band = read(parameter::kRateFormBand, p.rate_form_band);
  std::string why;
  if (!p.IsValid(&why)) read.FailParameters(why);
  return std::make_unique<ModifiedCamClay>(p);
}

std::vector<ExportedParameters> ModifiedCamClayExports(const std::vector<double>& v) {
  const double lambda = v[kLambdaStar], kappa = v[kKappaStar];
  const double n = v[kNIntercept], nu = v[kShearParameter];
  const double m = CriticalStateRatio(v[kCriticalFrictionAngle] * kDegree);
  // PLAXIS' Modified Cam-Clay takes λ, κ of the e-ln p form; at the NCL
  // state with 1 + e = exp(N) (p = 1 kPa) they are λ*(1+e), κ*(1+e).
  return {{"Modified Cam clay (ln(1+e)-ln p form)",
           {{"M", m},
            {parameter::kLambdaStar.key, lambda},
            {parameter::kKappaStar.key, kappa},
            {"N", n},
            {"nu", nu}}},
          {"PLAXIS Modified Cam-Clay (nu_ur, kappa, lambda, M at 1+e = exp N)",
           {{"nu_ur", nu},
            {parameter::kKappa.key, kappa * std::exp(n)},
            {parameter::kLambda.key, lambda * std::exp(n)},
            {"M", m}}}};
}

ModelTraits ModifiedCamClayTraits() {
  // The parameter vector is the log-log form with Poisson-ratio elasticity;
  // its other keys give the semi-log form, M and a constant G instead.
  return {ModelKind::kModifiedCamClay,
          "Modified Cam clay",
          {{parameter::kPhiC, ParameterStart::kCslStressRatio, Identification::kOffIsotropicAxis,
            25.0, 5.0, 50.0},
           {parameter::kLambdaStar, ParameterStart::kNclSlope, Identification::kTwoMeanStresses,
            0.1, 1e-3, 0.5},
           {parameter::kKappaStar, ParameterStart::kUnloadingSlope,
            Identification::kOffIsotropicAxis, 0.02, 1e-4, 0.2},
           {parameter::kNIntercept, ParameterStart::kNclIntercept, Identification::kAnyState, 1.0,
            0.05, 4.0},
           {parameter::kPoissonRatio, ParameterStart::kTypical,
            Identification::kTwoOffAxisDirections, 0.25, 0.0, 0.49}},
          {parameter::kCriticalStateRatio, parameter::kLambda, parameter::kKappa,
           parameter::kVoidRatioIntercept, parameter::kShearModulus, parameter::kReferencePressure,
           parameter::kYieldTolerance, parameter::kRateFormBand},
          /*linear_ncl=*/true,
          /*critical_state_ocr=*/"2^(1 - kappa*/lambda*)",
          // Its rate form has kinks at the yield surface: at 1e-8 ERK 5 is
          // slower than RKF23 at equal error on some paths (element_driver.h).
          /*integrator_tolerance=*/1e-9,
          ReadModifiedCamClay,
          MakeModifiedCamClay,
          ModifiedCamClayExports};
}

// ---------------------------------------------------------------- hypoplastic sand

HypoplasticSand::Parameters SandParameters(const std::vector<double>& v) {
  HypoplasticSand::Parameters p;
  p.critical_friction_angle = v[kSandCriticalFrictionAngle] * kDegree;
  p.granular_hardness = v[kSandGranularHardness];
  p.compression_exponent = v[kSandExponent];
  p.densest_void_ratio0 = v[kSandDensestVoidRatio];
  p.critical_void_ratio0 = v[kSandCriticalVoidRatio];
  p.loosest_void_ratio0 = v[kSandLoosestVoidRatio];
  p.pyknotropy_exponent = v[kSandPyknotropyExponent];
  p.stiffness_exponent = v[kSandStiffnessExponent];
  return p;
}

std::unique_ptr<ConstitutiveModel> MakeHypoplasticSand(const std::vector<double>& v,
                                                       std::string* why) {
  const HypoplasticSand::Parameters p = SandParameters(v);
  for (double value : v) {
    if (!std::isfinite(value)) {
      *why = "a parameter is not finite";
      return nullptr;
    }
  }
  if (!p.IsValid(why)) return nullptr;
  return std::make_unique<HypoplasticSand>(p);
}

std::unique_ptr<ConstitutiveModel> ReadHypoplasticSand(const ConfigTable& table) {
  const KeyReader read(table);
  std::vector<double> v(kNumSandParameters);
  v[kSandCriticalFrictionAngle] = read(parameter::kPhiC);
  v[kSandGranularHardness] = read(parameter::kGranularHardness);
  v[kSandExponent] = read(parameter::kBauerExponent);
  v[kSandDensestVoidRatio] = read(parameter::kDensestVoidRatio);
  v[kSandCriticalVoidRatio] = read(parameter::kCriticalVoidRatio);
  v[kSandLoosestVoidRatio] = read(parameter::kLoosestVoidRatio);
  // Bauer's lines must not cross: e_d < e_c < e_i at every p.
  read.RequireOrder(parameter::kDensestVoidRatio, v[kSandDensestVoidRatio],
                    parameter::kCriticalVoidRatio, v[kSandCriticalVoidRatio], true);
  read.RequireOrder(parameter::kCriticalVoidRatio, v[kSandCriticalVoidRatio],
                    parameter::kLoosestVoidRatio, v[kSandLoosestVoidRatio], true);
  v[kSandPyknotropyExponent] = read(parameter::kPyknotropyExponent);
  v[kSandStiffnessExponent] = read(parameter::kStiffnessExponent);
  HypoplasticSand::Parameters p = SandParameters(v);
  p.minimum_mean_stress = read(parameter::kMinimumMeanStress, p.minimum_mean_stress);
  // What remains is the sign of the f_b denominator, which α sets for given φ_c and e's.
  std::string why;
  if (!p.IsValid(&why)) read.FailParameters(why);
  return std::make_unique<HypoplasticSand>(p);
}

std::vector<ExportedParameters> HypoplasticSandExports(const std::vector<double>& v) {
  // The soilmodels.com UMAT / PLAXIS UDSM of sand hypoplasticity reads
  // φ_c, p_t, h_s, n, e_d0, e_c0, e_i0, α, β (then the intergranular strain).
  ExportedParameters order{
      "UMAT / PLAXIS UDSM sand hypoplasticity (von Wolffersdorff), parameters 1-9", {}};
  const std::vector<FittedParameter>& parameters = Traits(ModelKind::kHypoplasticSand).parameters;
  for (size_t i = 0; i < parameters.size(); ++i) {
    order.values.emplace_back(parameters[i].traits.key, v[i]);
    if (i == kSandCriticalFrictionAngle) order.values.emplace_back("p_t_kpa", 0.0);
  }
  return {order};
}

ModelTraits HypoplasticSandTraits() {
  // Typical values (Herle & Gudehus 1999) and bounds wide enough for DEM
  // sphere packings (small compressibility: large h_s). The model is not
  // homogeneous in p: what the data determine is judged from the Jacobian.
  const Identification by = Identification::kJacobian;
  return {ModelKind::kHypoplasticSand,
          "hypoplastic sand",
          {{parameter::kPhiC, ParameterStart::kCslStressRatio, by, 30.0, 5.0, 50.0},
           {parameter::kGranularHardness, ParameterStart::kBauerNcl, by, 1e5, 1e2, 1e9},
           {parameter::kBauerExponent, ParameterStart::kTypical, by, 0.4, 0.05, 0.95},
           {parameter::kDensestVoidRatio, ParameterStart::kDensestFraction, by, 0.5, 0.05, 3.0},
           {parameter::kCriticalVoidRatio, ParameterStart::kCslVoidRatio, by, 0.8, 0.1, 4.0},
           {parameter::kLoosestVoidRatio, ParameterStart::kBauerNcl, by, 0.95, 0.1, 5.0},
           {parameter::kPyknotropyExponent, ParameterStart::kTypical, by, 0.15, 0.01, 1.0},
           {parameter::kStiffnessExponent, ParameterStart::kTypical, by, 1.0, 0.05, 5.0}},
          {parameter::kMinimumMeanStress},
          /*linear_ncl=*/false,
          // e_c/e_i is constant, but the lines are not parallel in ln(1+e)-ln p.
          /*critical_state_ocr=*/"",
          /*integrator_tolerance=*/1e-8,
          ReadHypoplasticSand,
          MakeHypoplasticSand,
          HypoplasticSandExports};
}

}  // namespace

const ModelTraits& Traits(ModelKind kind) {
  static const ModelTraits clay = HypoplasticClayTraits();
  static const ModelTraits cam_clay = ModifiedCamClayTraits();
  static const ModelTraits sand = HypoplasticSandTraits();
  switch (kind) {
    case ModelKind::kHypoplasticClay:
      return clay;
    case ModelKind::kModifiedCamClay:
      return cam_clay;
    case ModelKind::kHypoplasticSand:
      return sand;
  }
  GRANASYM_CHECK(false) << "no traits for model kind " << static_cast<int>(kind);
  return clay;
}

}  // namespace granasym
