// Mašín (2005) hypoplastic model for clays and its asymptotic state boundary
// surface; equations exactly as in SPEC §6.1 (tension positive).
#include "constitutive/hypoplastic_clay.h"

#include <fmt/format.h>

#include <cmath>

#include "common/error.h"
#include "constitutive/asymptotic_states.h"
#include "constitutive/autodiff.h"
#include "constitutive/eigen.h"
#include "constitutive/stress_direction.h"

namespace granasym {

namespace {

struct Constants {
  double a, alpha, c1, c2, barotropy_denominator, lambda_star, n_intercept, reference_pressure,
      sin2_phi, minimum_mean_stress;
};

template <typename S>
struct TermsT {
  S barotropy, pyknotropy;
  Mat6<S> linear;
  Vec6<S> nonlinear;
};

bool Fail(std::string* why, const std::string& message) {
  if (why != nullptr) *why = message;
  return false;
}

// T must be negative definite: p > p_min and all principal stresses compressive
// (Sylvester's criterion on −T). At σ_r → 0 (limit d) the model's Y is singular.
bool CheckCompressive(const Vector6& t, double minimum_mean_stress, std::string* why) {
  if (!t.allFinite()) return Fail(why, "stress is not finite");
  const double p = MeanStress(t);
  if (!(p > minimum_mean_stress)) {
    return Fail(why, fmt::format("mean stress p = {:.6g} kPa is not above the minimum {:.3g} kPa",
                                 p, minimum_mean_stress));
  }
  const double minor1 = -t[0];
  const double minor2 = t[0] * t[1] - t[3] * t[3];
  const double minor3 = -Determinant<double>(t);
  if (!(minor1 > 0 && minor2 > 0 && minor3 > 0)) {
    return Fail(why,
                fmt::format("stress has a principal value ≥ 0 (tension) at p = {:.6g} kPa", p));
  }
  return true;
}

template <typename S>
bool ComputeTerms(const Constants& c, const Vec6<S>& t, const S& log_1pe, TermsT<S>* out,
                  std::string* why) {
  using std::exp;
  using std::pow;
  using std::sqrt;
  const double sqrt3 = std::sqrt(3.0);
  const S trace = Trace(t);
  const S p = -trace / 3.0;
  StressDirection<S> direction;
  if (!ComputeStressDirection(t, &direction, why)) return false;
  const Vec6<S>& t_hat = direction.t_hat;
  const Vec6<S>& t_star = direction.t_star;
  const S& f = direction.lode_factor;

  const S equivalent_pressure =
      c.reference_pressure * exp((c.n_intercept - log_1pe) / c.lambda_star);
  out->pyknotropy = pow(2.0 * p / equivalent_pressure, c.alpha);
  out->barotropy = 3.0 * p / (c.lambda_star * c.barotropy_denominator);
  out->linear = 3.0 * (c.c1 * Mat6<S>::Identity() + (c.c2 * c.a * c.a) * DyadMatrix(t_hat, t_hat));

  const S i1 = trace;
  const S i2 = 0.5 * (Contract(t, t) - i1 * i1);
  const S i3 = Determinant(t);
  const double y_isotropic = sqrt3 * c.a / (3.0 + c.a * c.a);
  const S y =
      (y_isotropic - 1.0) * (i1 * i2 + 9.0 * i3) * (1.0 - c.sin2_phi) / (8.0 * i3 * c.sin2_phi) +
      y_isotropic;
  const S t_hat2 = Contract(t_hat, t_hat);
  const S f_over_a = f / c.a;
  const Vec6<S> m =
      -(c.a / f) *
      (t_hat + t_star - t_hat * ((6.0 * t_hat2 - 1.0) / (3.0 * (f_over_a * f_over_a + t_hat2))));
  const S m_norm = FrobeniusNorm(m);
  if (!(autodiff::Value(m_norm) > 0)) return Fail(why, "flow direction m vanishes");
  out->nonlinear = out->linear * (-(y / m_norm) * m);
  return true;
}

template <typename S>
Vec6<S> RateFromTerms(const TermsT<S>& terms, const Vec6<S>& d) {
  using std::sqrt;
  const S d2 = Contract(d, d);
  S d_norm(0.0);
  if (autodiff::Value(d2) > 0) d_norm = sqrt(d2);
  return terms.barotropy * (terms.linear * d) +
         (terms.barotropy * terms.pyknotropy * d_norm) * terms.nonlinear;
}

}  // namespace

bool HypoplasticClay::Parameters::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) { return Fail(why, message); };
  if (!(critical_friction_angle > 0 && critical_friction_angle < kPi / 2)) {
    return fail(fmt::format("critical_friction_angle = {} rad must be in (0, π/2)",
                            critical_friction_angle));
  }
  if (!(lambda_star > 0)) return fail(fmt::format("lambda_star = {} must be > 0", lambda_star));
  if (!(kappa_star > 0 && kappa_star < lambda_star)) {
    return fail(
        fmt::format("kappa_star = {} must be in (0, lambda_star = {})", kappa_star, lambda_star));
  }
  if (!std::isfinite(n_intercept)) return fail("n_intercept must be finite");
  if (!(bulk_shear_ratio > 0)) {
    return fail(fmt::format("bulk_shear_ratio r = {} must be > 0", bulk_shear_ratio));
  }
  if (!(reference_pressure > 0)) {
    return fail(fmt::format("reference_pressure = {} kPa must be > 0", reference_pressure));
  }
  if (!(minimum_mean_stress > 0)) {
    return fail(fmt::format("minimum_mean_stress = {} kPa must be > 0", minimum_mean_stress));
  }
  const double s = std::sin(critical_friction_angle);
  const double a = std::sqrt(3.0) * (3.0 - s) / (2.0 * std::sqrt(2.0) * s);
  const double alpha = std::log((lambda_star - kappa_star) / (lambda_star + kappa_star) *
                                (3.0 + a * a) / (std::sqrt(3.0) * a)) /
                       std::log(2.0);
  const double denominator = 3.0 + a * a - std::pow(2.0, alpha) * std::sqrt(3.0) * a;
  if (!(denominator > 0)) {
    return fail(
        fmt::format("3 + a² − 2^α √3 a = {} ≤ 0 for critical_friction_angle = {} rad, "
                    "lambda_star = {}, kappa_star = {}: f_s would not be positive",
                    denominator, critical_friction_angle, lambda_star, kappa_star));
  }
  return true;
}

HypoplasticClay::HypoplasticClay(const Parameters& parameters) : parameters_(parameters) {
  std::string why;
  GRANASYM_CHECK(parameters.IsValid(&why)) << why;
  const double s = std::sin(parameters.critical_friction_angle);
  const double sqrt3 = std::sqrt(3.0);
  a_ = sqrt3 * (3.0 - s) / (2.0 * std::sqrt(2.0) * s);
  const double lambda = parameters.lambda_star;
  const double kappa = parameters.kappa_star;
  alpha_ = std::log((lambda - kappa) / (lambda + kappa) * (3.0 + a_ * a_) / (sqrt3 * a_)) /
           std::log(2.0);
  barotropy_denominator_ = 3.0 + a_ * a_ - std::pow(2.0, alpha_) * sqrt3 * a_;
  c1_ = 2.0 * barotropy_denominator_ / (9.0 * parameters.bulk_shear_ratio);
  c2_ = 1.0 + 3.0 * (1.0 - c1_) / (a_ * a_);
}

namespace {
Constants MakeConstants(const HypoplasticClay::Parameters& p, double a, double alpha, double c1,
                        double c2, double denominator) {
  const double s = std::sin(p.critical_friction_angle);
  return {a,
          alpha,
          c1,
          c2,
          denominator,
          p.lambda_star,
          p.n_intercept,
          p.reference_pressure,
          s * s,
          p.minimum_mean_stress};
}
}  // namespace

bool HypoplasticClay::IsAdmissible(const ModelState& state, std::string* why) const {
  if (!CheckCompressive(state.stress, parameters_.minimum_mean_stress, why)) return false;
  if (!(state.void_ratio > 0 && std::isfinite(state.void_ratio))) {
    return Fail(why, fmt::format("void ratio e = {:.6g} must be > 0", state.void_ratio));
  }
  return true;
}

bool HypoplasticClay::IsAdmissibleStart(const ModelState& state, std::string* why) const {
  if (!IsAdmissible(state, why)) return false;
  const double ocr = EquivalentPressure(state.void_ratio) / MeanStress(state.stress);
  if (!(ocr >= 1 - 1e-9)) {
    return Fail(why, fmt::format("OCR = {:.6g} is below 1: the state lies looser than the "
                                 "normal compression line, outside the state boundary surface",
                                 ocr));
  }
  return true;
}

bool HypoplasticClay::EvaluateTerms(const ModelState& state, Terms* terms, std::string* why) const {
  if (!IsAdmissible(state, why)) return false;
  const Constants c = MakeConstants(parameters_, a_, alpha_, c1_, c2_, barotropy_denominator_);
  TermsT<double> t;
  if (!ComputeTerms<double>(c, state.stress, std::log1p(state.void_ratio), &t, why)) return false;
  terms->barotropy = t.barotropy;
  terms->pyknotropy = t.pyknotropy;
  terms->linear = t.linear;
  terms->nonlinear = t.nonlinear;
  if (!terms->linear.allFinite() || !terms->nonlinear.allFinite() ||
      !std::isfinite(terms->pyknotropy)) {
    return Fail(why, "model terms are not finite");
  }
  return true;
}

bool HypoplasticClay::Rate(const ModelState& state, const Vector6& stretching, ModelRate* rate,
                           Matrix6* tangent, std::string* why) const {
  Terms terms;
  if (!EvaluateTerms(state, &terms, why)) return false;
  const double d_norm = FrobeniusNorm<double>(stretching);
  const double nonlinear_factor = terms.barotropy * terms.pyknotropy;
  rate->stress_rate =
      terms.barotropy * (terms.linear * stretching) + (nonlinear_factor * d_norm) * terms.nonlinear;
  rate->void_ratio_rate = (1.0 + state.void_ratio) * Trace<double>(stretching);
  rate->internal_rate.resize(0);
  if (tangent != nullptr) {
    *tangent = terms.barotropy * terms.linear;
    if (d_norm > 0) {
      *tangent += (nonlinear_factor / d_norm) * DyadMatrix<double>(terms.nonlinear, stretching);
    }
  }
  return true;
}

bool HypoplasticClay::Jacobian(const ModelState& state, const Vector6& stretching,
                               RateJacobian* jacobian, std::string* why) const {
  if (!IsAdmissible(state, why)) return false;
  const Constants c = MakeConstants(parameters_, a_, alpha_, c1_, c2_, barotropy_denominator_);
  using S = autodiff::StateScalar;
  return autodiff::StressRateJacobian(
      state, stretching,
      [&c](const Vec6<S>& t, const S& log_1pe, const Vec6<S>& d, Vec6<S>* rate, std::string* w) {
        TermsT<S> terms;
        if (!ComputeTerms<S>(c, t, log_1pe, &terms, w)) return false;
        *rate = RateFromTerms(terms, d);
        return true;
      },
      jacobian, why);
}

double HypoplasticClay::EquivalentPressure(double void_ratio) const {
  return parameters_.reference_pressure *
         std::exp((parameters_.n_intercept - std::log1p(void_ratio)) / parameters_.lambda_star);
}

double HypoplasticClay::VoidRatioForOcr(double mean_stress, double ocr) const {
  return std::expm1(parameters_.n_intercept -
                    parameters_.lambda_star *
                        std::log(ocr * mean_stress / parameters_.reference_pressure));
}

ModelState HypoplasticClay::MakeState(const Vector6& stress, double void_ratio) const {
  ModelState state;
  state.stress = stress;
  state.void_ratio = void_ratio;
  return state;
}

bool HypoplasticClay::AsymptoteForStress(const Vector6& stress, Asymptote* asymptote,
                                         std::string* why) const {
  // f_s 𝔸⁻¹ depends on the stress direction only; evaluate at e with p_e = p.
  const ModelState state = MakeState(stress, VoidRatioForOcr(MeanStress(stress), 1.0));
  Terms terms;
  if (!EvaluateTerms(state, &terms, why)) return false;
  const Matrix6 a_matrix =
      terms.barotropy * terms.linear +
      (1.0 / parameters_.lambda_star) * DyadMatrix<double>(stress, IdentityVoigt());
  Eigen::PartialPivLU<Matrix6> lu(a_matrix);
  const Vector6 solution = lu.solve(terms.nonlinear);  // 𝔸⁻¹:N
  const double solution_norm = FrobeniusNorm<double>(solution);
  if (!solution.allFinite() || !(solution_norm > 0)) {
    return Fail(why, "𝔸 is singular at this stress direction");
  }
  asymptote->pyknotropy_sbs = 1.0 / (terms.barotropy * solution_norm);
  asymptote->stretching_direction = -solution / solution_norm;
  asymptote->ocr = 2.0 * std::pow(asymptote->pyknotropy_sbs, -1.0 / alpha_);
  return true;
}

void HypoplasticClay::SignConstraints(Vector6* stress_codes,
                                      Eigen::VectorXd* internal_codes) const {
  *stress_codes << -2, -2, -2, 0, 0, 0;
  internal_codes->resize(0);
}

bool HypoplasticClay::AsymptoteOfStressDirection(double psi_sigma, double* psi_epsilon,
                                                 double* ln_ocr, std::string* why) const {
  AsymptoticState state;
  if (!AnalyticAsymptoteForStress(*this, psi_sigma, &state, why)) return false;
  *psi_epsilon = state.psi_epsilon;
  *ln_ocr = std::log(state.ocr);
  return true;
}

bool HypoplasticClay::ScaleState(double factor, ModelState* state) const {
  state->stress *= factor;
  state->void_ratio =
      std::expm1(std::log1p(state->void_ratio) - parameters_.lambda_star * std::log(factor));
  return true;
}

std::string HypoplasticClay::Describe() const {
  return fmt::format(
      "hypoplastic_clay phi_c={:.6g} deg lambda*={:.6g} kappa*={:.6g} N={:.6g} r={:.6g} p_r={:.6g} "
      "kPa (a={:.6g}, alpha={:.6g})",
      parameters_.critical_friction_angle / kDegree, parameters_.lambda_star,
      parameters_.kappa_star, parameters_.n_intercept, parameters_.bulk_shear_ratio,
      parameters_.reference_pressure, a_, alpha_);
}

HypoplasticClay::Parameters HypoplasticClay::Parameters::LondonClay() {
  Parameters p;
  p.critical_friction_angle = 22.6 * kDegree;
  p.lambda_star = 0.11;
  p.kappa_star = 0.016;
  p.n_intercept = 1.375;
  p.bulk_shear_ratio = 0.4;
  return p;
}

}  // namespace granasym
