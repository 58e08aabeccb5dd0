// von Wolffersdorff (1996) hypoplastic model for sands; equations exactly as in
// hypoplastic_sand.h (tension positive), written once for double and for the
// automatic-differentiation scalar.
#include "constitutive/hypoplastic_sand.h"

#include <fmt/format.h>

#include <cmath>

#include "common/error.h"
#include "constitutive/autodiff.h"
#include "constitutive/stress_direction.h"

namespace granasym {

namespace {

struct Constants {
  double a, barotropy_denominator, granular_hardness, compression_exponent, densest_void_ratio0,
      critical_void_ratio0, loosest_void_ratio0, pyknotropy_exponent, stiffness_exponent;
};

template <typename S>
struct TermsT {
  S barotropy, density, pyknotropy, lode_factor;
  Mat6<S> linear;
  Vec6<S> nonlinear;
};

bool Fail(std::string* why, const std::string& message) {
  if (why != nullptr) *why = message;
  return false;
}

template <typename S>
bool ComputeTerms(const Constants& c, const Vec6<S>& t, const S& log_1pe, TermsT<S>* out,
                  std::string* why) {
  using std::exp;
  using std::pow;
  using std::sqrt;
  const S trace = Trace(t);
  const S p = -trace / 3.0;
  StressDirection<S> direction;
  if (!ComputeStressDirection(t, &direction, why)) return false;
  const Vec6<S>& t_hat = direction.t_hat;
  const Vec6<S>& t_star = direction.t_star;
  const S& f = direction.lode_factor;

  // Bauer's law and the density factors.
  const S pressure_ratio = 3.0 * p / c.granular_hardness;  // 3p/h_s
  const S bauer = exp(-pow(pressure_ratio, c.compression_exponent));
  const S e_i = c.loosest_void_ratio0 * bauer;
  const S e_c = c.critical_void_ratio0 * bauer;
  const S e_d = c.densest_void_ratio0 * bauer;
  const S e = exp(log_1pe) - 1.0;
  if (!(autodiff::Value(e) > autodiff::Value(e_d))) {
    return Fail(why,
                fmt::format("void ratio e = {:.9g} is not above e_d = {:.9g} at p = {:.6g} kPa "
                            "(f_d is not real)",
                            autodiff::Value(e), autodiff::Value(e_d), autodiff::Value(p)));
  }
  out->density = pow(e_c / e, c.stiffness_exponent);
  out->pyknotropy = pow((e - e_d) / (e_c - e_d), c.pyknotropy_exponent);
  out->barotropy = (c.granular_hardness / c.compression_exponent) * ((1.0 + e_i) / e_i) *
                   std::pow(c.loosest_void_ratio0 / c.critical_void_ratio0, c.stiffness_exponent) *
                   pow(pressure_ratio, 1.0 - c.compression_exponent) / c.barotropy_denominator;
  out->lode_factor = f;

  const S t_hat2 = Contract(t_hat, t_hat);
  out->linear = (f * f * Mat6<S>::Identity() + (c.a * c.a) * DyadMatrix(t_hat, t_hat)) / t_hat2;
  out->nonlinear = (c.a * f / t_hat2) * (t_hat + t_star);
  return true;
}

template <typename S>
Vec6<S> RateFromTerms(const TermsT<S>& terms, const Vec6<S>& d) {
  using std::sqrt;
  const S d2 = Contract(d, d);
  S d_norm(0.0);
  if (autodiff::Value(d2) > 0) d_norm = sqrt(d2);
  return (terms.barotropy * terms.density) *
         (terms.linear * d + (terms.pyknotropy * d_norm) * terms.nonlinear);
}

Constants MakeConstants(const HypoplasticSand::Parameters& p, double a, double denominator) {
  return {a,
          denominator,
          p.granular_hardness,
          p.compression_exponent,
          p.densest_void_ratio0,
          p.critical_void_ratio0,
          p.loosest_void_ratio0,
          p.pyknotropy_exponent,
          p.stiffness_exponent};
}

double ParameterA(double critical_friction_angle) {
  const double s = std::sin(critical_friction_angle);
  return std::sqrt(3.0) * (3.0 - s) / (2.0 * std::sqrt(2.0) * s);
}

double BarotropyDenominator(const HypoplasticSand::Parameters& p, double a) {
  return 3.0 + a * a -
         a * std::sqrt(3.0) *
             std::pow((p.loosest_void_ratio0 - p.densest_void_ratio0) /
                          (p.critical_void_ratio0 - p.densest_void_ratio0),
                      p.pyknotropy_exponent);
}

}  // namespace

bool HypoplasticSand::Parameters::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) { return Fail(why, message); };
  if (!(critical_friction_angle > 0 && critical_friction_angle < kPi / 2)) {
    return fail(fmt::format("critical_friction_angle = {} rad must be in (0, π/2)",
                            critical_friction_angle));
  }
  if (!(granular_hardness > 0 && std::isfinite(granular_hardness))) {
    return fail(fmt::format("granular_hardness h_s = {} kPa must be > 0", granular_hardness));
  }
  if (!(compression_exponent > 0 && compression_exponent < 1)) {
    return fail(fmt::format("compression_exponent n = {} must be in (0, 1)", compression_exponent));
  }
  if (!(densest_void_ratio0 > 0 && std::isfinite(densest_void_ratio0))) {
    return fail(fmt::format("densest_void_ratio0 e_d0 = {} must be > 0", densest_void_ratio0));
  }
  if (!(critical_void_ratio0 > densest_void_ratio0 && std::isfinite(critical_void_ratio0))) {
    return fail(
        fmt::format("critical_void_ratio0 e_c0 = {} must be above densest_void_ratio0 e_d0 = {}",
                    critical_void_ratio0, densest_void_ratio0));
  }
  if (!(loosest_void_ratio0 > critical_void_ratio0 && std::isfinite(loosest_void_ratio0))) {
    return fail(
        fmt::format("loosest_void_ratio0 e_i0 = {} must be above critical_void_ratio0 e_c0 = {}",
                    loosest_void_ratio0, critical_void_ratio0));
  }
  if (!(pyknotropy_exponent > 0 && std::isfinite(pyknotropy_exponent))) {
    return fail(fmt::format("pyknotropy_exponent alpha = {} must be > 0", pyknotropy_exponent));
  }
  if (!(stiffness_exponent > 0 && std::isfinite(stiffness_exponent))) {
    return fail(fmt::format("stiffness_exponent beta = {} must be > 0", stiffness_exponent));
  }
  if (!(minimum_mean_stress > 0)) {
    return fail(fmt::format("minimum_mean_stress = {} kPa must be > 0", minimum_mean_stress));
  }
  const double a = ParameterA(critical_friction_angle);
  const double denominator = BarotropyDenominator(*this, a);
  if (!(denominator > 0)) {
    return fail(fmt::format(
        "pyknotropy_exponent alpha = {}: 3 + a² − a√3 ((e_i0 − e_d0)/(e_c0 − e_d0))^α = {:.6g} ≤ 0 "
        "for critical_friction_angle = {} rad, e_d0 = {}, e_c0 = {}, e_i0 = {}: f_b would not be "
        "positive",
        pyknotropy_exponent, denominator, critical_friction_angle, densest_void_ratio0,
        critical_void_ratio0, loosest_void_ratio0));
  }
  return true;
}

HypoplasticSand::Parameters HypoplasticSand::Parameters::HochstettenSand() {
  Parameters p;
  p.critical_friction_angle = 33.0 * kDegree;
  p.granular_hardness = 1.0e6;  // 1000 MPa
  p.compression_exponent = 0.25;
  p.densest_void_ratio0 = 0.55;
  p.critical_void_ratio0 = 0.95;
  p.loosest_void_ratio0 = 1.05;
  p.pyknotropy_exponent = 0.25;
  p.stiffness_exponent = 1.5;
  return p;
}

HypoplasticSand::HypoplasticSand(const Parameters& parameters) : parameters_(parameters) {
  std::string why;
  GRANASYM_CHECK(parameters.IsValid(&why)) << why;
  a_ = ParameterA(parameters.critical_friction_angle);
  barotropy_denominator_ = BarotropyDenominator(parameters, a_);
}

HypoplasticSand::LimitVoidRatios HypoplasticSand::LimitVoidRatiosAt(double mean_stress) const {
  const double bauer = std::exp(-std::pow(3.0 * mean_stress / parameters_.granular_hardness,
                                          parameters_.compression_exponent));
  return {parameters_.loosest_void_ratio0 * bauer, parameters_.critical_void_ratio0 * bauer,
          parameters_.densest_void_ratio0 * bauer};
}

bool HypoplasticSand::IsAdmissible(const ModelState& state, std::string* why) const {
  const Vector6& t = state.stress;
  if (!t.allFinite()) return Fail(why, "stress is not finite");
  const double p = MeanStress(t);
  if (!(p > parameters_.minimum_mean_stress)) {
    return Fail(why, fmt::format("mean stress p = {:.6g} kPa is not above the minimum {:.3g} kPa",
                                 p, parameters_.minimum_mean_stress));
  }
  // All principal stresses compressive: Sylvester's criterion on −T.
  const double minor1 = -t[0];
  const double minor2 = t[0] * t[1] - t[3] * t[3];
  const double minor3 = -Determinant<double>(t);
  if (!(minor1 > 0 && minor2 > 0 && minor3 > 0)) {
    return Fail(why, fmt::format("stress has a principal value ≥ 0 (tension) at p = {:.6g} kPa "
                                 "(T11 = {:.6g}, T22 = {:.6g}, T33 = {:.6g} kPa, tension positive)",
                                 p, t[0], t[1], t[2]));
  }
  if (!std::isfinite(state.void_ratio)) return Fail(why, "void ratio is not finite");
  const LimitVoidRatios limits = LimitVoidRatiosAt(p);
  if (!(state.void_ratio > limits.densest)) {
    return Fail(why, fmt::format("void ratio e = {:.9g} is not above the densest e_d = {:.9g} at "
                                 "p = {:.6g} kPa (f_d is not real below e_d)",
                                 state.void_ratio, limits.densest, p));
  }
  return true;
}

bool HypoplasticSand::IsAdmissibleStart(const ModelState& state, std::string* why) const {
  if (!IsAdmissible(state, why)) return false;
  const double p = MeanStress(state.stress);
  const double loosest = LimitVoidRatiosAt(p).loosest;
  if (!(state.void_ratio <= loosest * (1 + 1e-12))) {
    return Fail(why, fmt::format("void ratio e = {:.9g} is above the loosest e_i = {:.9g} at "
                                 "p = {:.6g} kPa: no sand state is looser",
                                 state.void_ratio, loosest, p));
  }
  return true;
}

bool HypoplasticSand::EvaluateTerms(const ModelState& state, Terms* terms, std::string* why) const {
  if (!IsAdmissible(state, why)) return false;
  const Constants c = MakeConstants(parameters_, a_, barotropy_denominator_);
  TermsT<double> t;
  if (!ComputeTerms<double>(c, state.stress, std::log1p(state.void_ratio), &t, why)) return false;
  terms->barotropy = t.barotropy;
  terms->density = t.density;
  terms->pyknotropy = t.pyknotropy;
  terms->lode_factor = t.lode_factor;
  terms->linear = t.linear;
  terms->nonlinear = t.nonlinear;
  if (!terms->linear.allFinite() || !terms->nonlinear.allFinite() ||
      !std::isfinite(terms->barotropy * terms->density * terms->pyknotropy)) {
    return Fail(why, "model terms are not finite");
  }
  return true;
}

bool HypoplasticSand::Rate(const ModelState& state, const Vector6& stretching, ModelRate* rate,
                           Matrix6* tangent, std::string* why) const {
  Terms terms;
  if (!EvaluateTerms(state, &terms, why)) return false;
  const double d_norm = FrobeniusNorm<double>(stretching);
  const double factor = terms.barotropy * terms.density;
  rate->stress_rate =
      factor * (terms.linear * stretching + (terms.pyknotropy * d_norm) * terms.nonlinear);
  rate->void_ratio_rate = (1.0 + state.void_ratio) * Trace<double>(stretching);
  rate->internal_rate.resize(0);
  if (tangent != nullptr) {
    *tangent = factor * terms.linear;
    if (d_norm > 0) {
      *tangent +=
          (factor * terms.pyknotropy / d_norm) * DyadMatrix<double>(terms.nonlinear, stretching);
    }
  }
  return true;
}

bool HypoplasticSand::Jacobian(const ModelState& state, const Vector6& stretching,
                               RateJacobian* jacobian, std::string* why) const {
  if (!IsAdmissible(state, why)) return false;
  const Constants c = MakeConstants(parameters_, a_, barotropy_denominator_);
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

double HypoplasticSand::EquivalentPressure(double void_ratio) const {
  if (!(void_ratio < parameters_.loosest_void_ratio0)) return 0.0;
  return parameters_.granular_hardness / 3.0 *
         std::pow(std::log(parameters_.loosest_void_ratio0 / void_ratio),
                  1.0 / parameters_.compression_exponent);
}

double HypoplasticSand::VoidRatioForOcr(double mean_stress, double ocr) const {
  return LimitVoidRatiosAt(ocr * mean_stress).loosest;
}

ModelState HypoplasticSand::MakeState(const Vector6& stress, double void_ratio) const {
  ModelState state;
  state.stress = stress;
  state.void_ratio = void_ratio;
  return state;
}

void HypoplasticSand::SignConstraints(Vector6* stress_codes,
                                      Eigen::VectorXd* internal_codes) const {
  *stress_codes << -2, -2, -2, 0, 0, 0;
  internal_codes->resize(0);
}

std::string HypoplasticSand::Describe() const {
  const Parameters& p = parameters_;
  return fmt::format(
      "hypoplastic_sand phi_c={:.6g} deg h_s={:.6g} kPa n={:.6g} e_d0={:.6g} e_c0={:.6g} "
      "e_i0={:.6g} alpha={:.6g} beta={:.6g} (a={:.6g})",
      p.critical_friction_angle / kDegree, p.granular_hardness, p.compression_exponent,
      p.densest_void_ratio0, p.critical_void_ratio0, p.loosest_void_ratio0, p.pyknotropy_exponent,
      p.stiffness_exponent, a_);
}

}  // namespace granasym
