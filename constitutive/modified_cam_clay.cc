// Modified Cam clay in rate form with the continuum elastoplastic tangent
// (SPEC §6.2); the same templated code gives the exact Jacobian.
#include "constitutive/modified_cam_clay.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.h"
#include "constitutive/autodiff.h"

namespace granasym {

namespace {

bool Fail(std::string* why, const std::string& message) {
  if (why != nullptr) *why = message;
  return false;
}

// Whether the rate form flows plastically (Parameters::rate_form_band), from
// f (kPa²), (M p_c)² = `scale` and the loading n:𝔼:D + β f ‖D‖: on the
// plastic branch whenever loading > 0 (elsewhere its multiplier would be
// negative: the elastic rate, so that the branch's rate is continuous), on
// the elastic one never, and where the state decides (kAutoBranch) when
// it also lies on or within the band, f ≥ −band·scale.
bool FlowsPlastically(int branch, double f, double scale, double loading, double band) {
  if (branch == ModifiedCamClay::kElasticBranch) return false;
  if (!(loading > 0)) return false;
  return branch == ModifiedCamClay::kPlasticBranch || f >= -band * scale;
}

// Tension-positive stress rate and ṗ_c of the rate form.
template <typename S>
bool CamClayRate(const ModifiedCamClay::Parameters& c, int branch, const Vec6<S>& t,
                 const S& log_1pe, const S& preconsolidation, const Vec6<S>& d,
                 Vec6<S>* stress_rate, S* preconsolidation_rate, std::string* why) {
  using std::exp;
  using std::sqrt;
  const double m2 = c.critical_state_ratio * c.critical_state_ratio;
  const S p = -Trace(t) / 3.0;
  const Vec6<S> s = Deviator(t);
  const S q2 = 1.5 * Contract(s, s);
  S lambda(c.lambda), kappa(c.kappa);
  if (c.form == ModifiedCamClay::CompressionForm::kSemiLog) {
    const S one_plus_e = exp(log_1pe);
    lambda = c.lambda / one_plus_e;
    kappa = c.kappa / one_plus_e;
  }
  const S bulk = p / kappa;
  const S shear =
      c.elasticity == ModifiedCamClay::Elasticity::kPoissonRatio
          ? S(bulk * (3.0 * (1.0 - 2.0 * c.poisson_ratio) / (2.0 * (1.0 + c.poisson_ratio))))
          : S(c.shear_modulus);
  auto elastic = [&](const Vec6<S>& x) -> Vec6<S> {
    Vec6<S> out = (2.0 * shear) * x;
    const S volumetric = (bulk - 2.0 * shear / 3.0) * Trace(x);
    for (int i = 0; i < 3; ++i) out[i] += volumetric;
    return out;
  };
  const Vec6<S> trial = elastic(d);
  const S f = q2 + m2 * p * (p - preconsolidation);
  Vec6<S> n = 3.0 * s;
  for (int i = 0; i < 3; ++i) n[i] -= m2 * (2.0 * p - preconsolidation) / 3.0;
  const S n_trial = Contract(n, trial);
  const double scale = m2 * autodiff::Value(preconsolidation) * autodiff::Value(preconsolidation);
  const S d2 = Contract(d, d);
  S d_norm(0.0);
  if (autodiff::Value(d2) > 0) d_norm = sqrt(d2);
  const S loading = n_trial + c.drift_stabilization * f * d_norm;
  if (FlowsPlastically(branch, autodiff::Value(f), scale, autodiff::Value(loading),
                       c.rate_form_band)) {
    const S hardening = preconsolidation * m2 * (2.0 * p - preconsolidation) / (lambda - kappa);
    const S denominator = Contract(n, elastic(n)) + m2 * p * hardening;
    if (!(autodiff::Value(denominator) > 0)) {
      return Fail(why, "plastic denominator n:𝔼:n + H ≤ 0 (softening beyond the elastic limit)");
    }
    const S multiplier = loading / denominator;
    *stress_rate = trial - multiplier * elastic(n);
    *preconsolidation_rate = multiplier * hardening;
  } else {
    *stress_rate = trial;
    *preconsolidation_rate = S(0.0);
  }
  return true;
}

}  // namespace

bool ModifiedCamClay::Parameters::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) { return Fail(why, message); };
  if (!(critical_state_ratio > 0 && critical_state_ratio < 3.0)) {
    return fail(fmt::format("critical_state_ratio M = {} must be in (0, 3)", critical_state_ratio));
  }
  if (!(lambda > 0)) return fail(fmt::format("lambda = {} must be > 0", lambda));
  if (!(kappa > 0 && kappa < lambda)) {
    return fail(fmt::format("kappa = {} must be in (0, lambda = {})", kappa, lambda));
  }
  if (!std::isfinite(n_intercept)) return fail("n_intercept must be finite");
  if (elasticity == Elasticity::kPoissonRatio && !(poisson_ratio > -1.0 && poisson_ratio < 0.5)) {
    return fail(fmt::format("poisson_ratio = {} must be in (−1, 0.5)", poisson_ratio));
  }
  if (elasticity == Elasticity::kConstantShearModulus && !(shear_modulus > 0)) {
    return fail(fmt::format("shear_modulus = {} kPa must be > 0", shear_modulus));
  }
  if (!(reference_pressure > 0)) {
    return fail(fmt::format("reference_pressure = {} kPa must be > 0", reference_pressure));
  }
  if (!(minimum_mean_stress > 0)) {
    return fail(fmt::format("minimum_mean_stress = {} kPa must be > 0", minimum_mean_stress));
  }
  if (!(yield_tolerance > 0 && yield_tolerance < 1e-2)) {
    return fail(fmt::format("yield_tolerance = {} must be in (0, 0.01)", yield_tolerance));
  }
  if (!(rate_form_band > 0 && rate_form_band < 1e-2)) {
    return fail(fmt::format("rate_form_band = {} must be in (0, 0.01)", rate_form_band));
  }
  if (!(drift_stabilization >= 0)) {
    return fail(fmt::format("drift_stabilization = {} must be >= 0", drift_stabilization));
  }
  return true;
}

ModifiedCamClay::ModifiedCamClay(const Parameters& parameters) : parameters_(parameters) {
  std::string why;
  GRANASYM_CHECK(parameters.IsValid(&why)) << why;
}

bool ModifiedCamClay::IsAdmissible(const ModelState& state, std::string* why) const {
  if (!state.stress.allFinite()) return Fail(why, "stress is not finite");
  const double p = MeanStress(state.stress);
  if (!(p > parameters_.minimum_mean_stress)) {
    return Fail(why, fmt::format("mean stress p = {:.6g} kPa is not above the minimum {:.3g} kPa",
                                 p, parameters_.minimum_mean_stress));
  }
  if (state.internal.size() != 1 || !(state.internal[0] > 0) || !std::isfinite(state.internal[0])) {
    return Fail(why, "preconsolidation pressure p_c must be one positive number");
  }
  if (!(state.void_ratio > 0 && std::isfinite(state.void_ratio))) {
    return Fail(why, fmt::format("void ratio e = {:.6g} must be > 0", state.void_ratio));
  }
  return true;
}

bool ModifiedCamClay::IsAdmissibleStart(const ModelState& state, std::string* why) const {
  if (!IsAdmissible(state, why)) return false;
  const double p_c = state.internal[0];
  const double f = YieldFunction(state.stress, p_c);
  const double m = parameters_.critical_state_ratio;
  if (f > parameters_.yield_tolerance * m * m * p_c * p_c) {
    return Fail(why, fmt::format("the state lies outside the yield surface (p_c = {:.6g} kPa from "
                                 "the elastic line, f = {:.6g} kPa²); raise OCR or lower psi_sigma",
                                 p_c, f));
  }
  return true;
}

bool ModifiedCamClay::AsymptoteOfStressDirection(double psi_sigma, double* psi_epsilon,
                                                 double* ln_ocr, std::string* why) const {
  if (parameters_.form != CompressionForm::kLogLog ||
      parameters_.elasticity != Elasticity::kPoissonRatio) {
    return Fail(why,
                "closed-form asymptotic states need the log-log form and Poisson-ratio elasticity");
  }
  const double m = parameters_.critical_state_ratio;
  const double lambda = parameters_.lambda, kappa = parameters_.kappa;
  const double nu = parameters_.poisson_ratio;
  const double eta = 3.0 * std::tan(psi_sigma) / std::sqrt(2.0);
  const double c = 2.0 * (1.0 + nu) / (9.0 * (1.0 - 2.0 * nu));
  const double m2_minus = m * m - eta * eta;
  const double rate_v = lambda * m2_minus;
  const double rate_s = eta * (kappa * c * m2_minus + 2.0 * (lambda - kappa));
  *psi_epsilon = std::atan2(3.0 / std::sqrt(2.0) * rate_s, rate_v);
  *ln_ocr = (1.0 - kappa / lambda) * std::log1p(eta * eta / (m * m));
  return true;
}

bool ModifiedCamClay::Rate(const ModelState& state, const Vector6& stretching, ModelRate* rate,
                           Matrix6* tangent, std::string* why) const {
  if (!IsAdmissible(state, why)) return false;
  const double log_1pe = std::log1p(state.void_ratio);
  double preconsolidation_rate = 0.0;
  if (!CamClayRate<double>(parameters_, state.branch, state.stress, log_1pe, state.internal[0],
                           stretching, &rate->stress_rate, &preconsolidation_rate, why)) {
    return false;
  }
  rate->void_ratio_rate = (1.0 + state.void_ratio) * Trace<double>(stretching);
  rate->internal_rate.resize(1);
  rate->internal_rate[0] = preconsolidation_rate;
  if (tangent != nullptr) {
    const Matrix6 elastic = ElasticStiffness(state.stress, state.void_ratio);
    *tangent = elastic;
    const double p_c = state.internal[0];
    const Vector6 n = YieldGradient(state.stress, p_c);
    Vector6 weighted_n = n;
    weighted_n.tail<3>() *= 2.0;
    const Eigen::Matrix<double, 1, 6> n_elastic = weighted_n.transpose() * elastic;
    const double n_trial = n_elastic.dot(stretching);
    const double m2 = parameters_.critical_state_ratio * parameters_.critical_state_ratio;
    const double f = YieldFunction(state.stress, p_c);
    const double d_norm = FrobeniusNorm<double>(stretching);
    const double loading = n_trial + parameters_.drift_stabilization * f * d_norm;
    if (FlowsPlastically(state.branch, f, m2 * p_c * p_c, loading, parameters_.rate_form_band)) {
      double lambda, kappa;
      CompressionSlopes(state.void_ratio, &lambda, &kappa);
      const double p = MeanStress(state.stress);
      const double hardening = p_c * m2 * (2.0 * p - p_c) / (lambda - kappa);
      const double denominator = n_elastic.dot(n) + m2 * p * hardening;
      Eigen::Matrix<double, 1, 6> d_loading = n_elastic;
      if (d_norm > 0) {
        Vector6 weighted = stretching / d_norm;
        weighted.tail<3>() *= 2.0;
        d_loading += parameters_.drift_stabilization * f * weighted.transpose();
      }
      *tangent -= (elastic * n) * d_loading / denominator;
    }
  }
  if (!rate->stress_rate.allFinite() || !std::isfinite(preconsolidation_rate)) {
    return Fail(why, "rate is not finite");
  }
  return true;
}

bool ModifiedCamClay::Jacobian(const ModelState& state, const Vector6& stretching,
                               RateJacobian* jacobian, std::string* why) const {
  if (!IsAdmissible(state, why)) return false;
  constexpr int kSize = 14;  // stress (6), ln(1+e), p_c, stretching (6)
  using Ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, kSize, 1>>;
  Vec6<Ad> t, d;
  for (int i = 0; i < 6; ++i) {
    t[i] = autodiff::Variable<kSize>(state.stress[i], i);
    d[i] = autodiff::Variable<kSize>(stretching[i], 8 + i);
  }
  const Ad log_1pe = autodiff::Variable<kSize>(std::log1p(state.void_ratio), 6);
  const Ad preconsolidation = autodiff::Variable<kSize>(state.internal[0], 7);
  Vec6<Ad> stress_rate;
  Ad preconsolidation_rate;
  if (!CamClayRate<Ad>(parameters_, state.branch, t, log_1pe, preconsolidation, d, &stress_rate,
                       &preconsolidation_rate, why)) {
    return false;
  }
  jacobian->d_state.resize(7, 8);
  jacobian->d_stretching.resize(7, 6);
  for (int i = 0; i < 7; ++i) {
    const Eigen::Matrix<double, kSize, 1> derivatives =
        i < 6 ? stress_rate[i].derivatives() : preconsolidation_rate.derivatives();
    jacobian->d_state.row(i) = derivatives.head<8>().transpose();
    jacobian->d_stretching.row(i) = derivatives.tail<6>().transpose();
  }
  if (!jacobian->d_state.allFinite() || !jacobian->d_stretching.allFinite()) {
    return Fail(why, "Jacobian is not finite");
  }
  return true;
}

double ModifiedCamClay::YieldFunction(const Vector6& stress, double preconsolidation) const {
  const double p = MeanStress(stress);
  const double q = DeviatorStress(stress);
  const double m = parameters_.critical_state_ratio;
  return q * q + m * m * p * (p - preconsolidation);
}

Vector6 ModifiedCamClay::YieldGradient(const Vector6& stress, double preconsolidation) const {
  const double m2 = parameters_.critical_state_ratio * parameters_.critical_state_ratio;
  const double p = MeanStress(stress);
  Vector6 n = 3.0 * Deviator<double>(stress);
  for (int i = 0; i < 3; ++i) n[i] -= m2 * (2.0 * p - preconsolidation) / 3.0;
  return n;
}

double ModifiedCamClay::YieldGradientPreconsolidation(const Vector6& stress) const {
  const double m = parameters_.critical_state_ratio;
  return -m * m * MeanStress(stress);
}

bool ModifiedCamClay::OnYieldSurface(const Vector6& stress, double preconsolidation) const {
  const double m = parameters_.critical_state_ratio;
  return YieldFunction(stress, preconsolidation) >=
         -parameters_.yield_tolerance * m * m * preconsolidation * preconsolidation;
}

void ModifiedCamClay::CompressionSlopes(double void_ratio, double* lambda_star,
                                        double* kappa_star) const {
  const double divisor = parameters_.form == CompressionForm::kSemiLog ? 1.0 + void_ratio : 1.0;
  *lambda_star = parameters_.lambda / divisor;
  *kappa_star = parameters_.kappa / divisor;
}

Matrix6 ModifiedCamClay::ElasticStiffness(const Vector6& stress, double void_ratio) const {
  double lambda, kappa;
  CompressionSlopes(void_ratio, &lambda, &kappa);
  const double bulk = MeanStress(stress) / kappa;
  const double shear = parameters_.elasticity == Elasticity::kPoissonRatio
                           ? bulk * 3.0 * (1.0 - 2.0 * parameters_.poisson_ratio) /
                                 (2.0 * (1.0 + parameters_.poisson_ratio))
                           : parameters_.shear_modulus;
  return 2.0 * shear * Matrix6::Identity() +
         (bulk - 2.0 * shear / 3.0) * DyadMatrix<double>(IdentityVoigt(), IdentityVoigt());
}

double ModifiedCamClay::EquivalentPressure(double void_ratio) const {
  const double distance = parameters_.form == CompressionForm::kLogLog
                              ? parameters_.n_intercept - std::log1p(void_ratio)
                              : parameters_.n_intercept - void_ratio;
  return parameters_.reference_pressure * std::exp(distance / parameters_.lambda);
}

double ModifiedCamClay::VoidRatioForOcr(double mean_stress, double ocr) const {
  const double log_pressure = std::log(ocr * mean_stress / parameters_.reference_pressure);
  if (parameters_.form == CompressionForm::kLogLog) {
    return std::expm1(parameters_.n_intercept - parameters_.lambda * log_pressure);
  }
  return parameters_.n_intercept - parameters_.lambda * log_pressure;
}

double ModifiedCamClay::PreconsolidationFromElasticLine(double mean_stress,
                                                        double void_ratio) const {
  const double lambda = parameters_.lambda;
  const double kappa = parameters_.kappa;
  const double volume =
      parameters_.form == CompressionForm::kLogLog ? std::log1p(void_ratio) : void_ratio;
  const double log_ratio = std::log(mean_stress / parameters_.reference_pressure);
  // volume = N − λ ln(p_c/p_r) + κ ln(p_c/p_r) − κ ln(p/p_r)
  return parameters_.reference_pressure *
         std::exp((parameters_.n_intercept - volume - kappa * log_ratio) / (lambda - kappa));
}

ModelState ModifiedCamClay::MakeState(const Vector6& stress, double void_ratio) const {
  ModelState state;
  state.stress = stress;
  state.void_ratio = void_ratio;
  state.internal.resize(1);
  state.internal[0] = PreconsolidationFromElasticLine(MeanStress(stress), void_ratio);
  return state;
}

namespace {

// f/(M p_c)² and the loading n:𝔼:D + β f ‖D‖ over (M p_c)² ‖D‖ at a state.
void YieldMeasures(const ModifiedCamClay& model, const ModelState& state, const Vector6& stretching,
                   double* f_scaled, double* loading_scaled) {
  const ModifiedCamClay::Parameters& c = model.parameters();
  const double p_c = state.internal.size() == 1 ? state.internal[0] : 0.0;
  const double scale = c.critical_state_ratio * c.critical_state_ratio * p_c * p_c;
  const double d_norm = FrobeniusNorm<double>(stretching);
  if (!(scale > 0) || !(d_norm > 0) || !state.stress.allFinite()) {
    *f_scaled = *loading_scaled = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  const double f = model.YieldFunction(state.stress, p_c);
  Vector6 n = model.YieldGradient(state.stress, p_c);
  n.tail<3>() *= 2.0;  // Voigt: the shear components count twice in n:𝔼:D
  const double n_trial = n.dot(model.ElasticStiffness(state.stress, state.void_ratio) * stretching);
  *f_scaled = f / scale;
  *loading_scaled = (n_trial + c.drift_stabilization * f * d_norm) / (scale * d_norm);
}

}  // namespace

int ModifiedCamClay::Branch(const ModelState& state, const Vector6& stretching) const {
  double f = 0, loading = 0;
  YieldMeasures(*this, state, stretching, &f, &loading);
  return f >= -parameters_.rate_form_band && loading > 0 ? kPlasticBranch : kElasticBranch;
}

void ModifiedCamClay::Switches(const ModelState& state, const Vector6& stretching,
                               double* values) const {
  double f = 0, loading = 0;
  YieldMeasures(*this, state, stretching, &f, &loading);
  if (std::isnan(f)) {
    values[0] = 1.0;
  } else if (state.branch == kPlasticBranch) {
    values[0] = loading;  // unloading ends the plastic branch
  } else {
    // Reaching the band while loading ends the elastic branch.
    values[0] = -std::min(f + parameters_.rate_form_band, loading);
  }
}

void ModifiedCamClay::SignConstraints(Vector6* stress_codes,
                                      Eigen::VectorXd* internal_codes) const {
  stress_codes->setZero();
  *internal_codes = Eigen::VectorXd::Constant(1, 2.0);
}

bool ModifiedCamClay::ScaleState(double factor, ModelState* state) const {
  // K = p/κ* and G ∝ p make the log-log form homogeneous; a constant G or the
  // semi-log form's 1/(1+e) break it.
  if (parameters_.form != CompressionForm::kLogLog ||
      parameters_.elasticity != Elasticity::kPoissonRatio) {
    return false;
  }
  state->stress *= factor;
  state->internal *= factor;
  state->void_ratio =
      std::expm1(std::log1p(state->void_ratio) - parameters_.lambda * std::log(factor));
  return true;
}

double ModifiedCamClay::critical_friction_angle() const {
  const double m = parameters_.critical_state_ratio;
  return std::asin(3.0 * m / (6.0 + m));
}

std::string ModifiedCamClay::Describe() const {
  return fmt::format(
      "modified_cam_clay form={} M={:.6g} lambda={:.6g} kappa={:.6g} N={:.6g} {} p_r={:.6g} kPa",
      ToString(parameters_.form), parameters_.critical_state_ratio, parameters_.lambda,
      parameters_.kappa, parameters_.n_intercept,
      parameters_.elasticity == Elasticity::kPoissonRatio
          ? fmt::format("nu={:.6g}", parameters_.poisson_ratio)
          : fmt::format("G={:.6g} kPa", parameters_.shear_modulus),
      parameters_.reference_pressure);
}

ModifiedCamClay::Parameters ModifiedCamClay::Parameters::LondonClayNcl() {
  Parameters p;
  p.critical_state_ratio = 0.9;
  p.lambda = 0.11;
  p.kappa = 0.016;
  p.n_intercept = 1.375;
  p.poisson_ratio = 0.25;
  return p;
}

}  // namespace granasym
