// Modified Cam clay stress-point algorithms: Sloan's modified Euler with
// yield-surface intersection and drift correction, and the implicit return
// mapping with its consistent tangent.
#include "constitutive/cam_clay_stress_point.h"

#include <fmt/format.h>

#include <cmath>

#include "common/error.h"
#include "constitutive/autodiff.h"
#include "constitutive/eigen.h"

namespace granasym {

bool CamClayStressPoint::Options::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (!(tolerance > 0 && tolerance < 0.1)) {
    return fail(fmt::format("tolerance = {} must be in (0, 0.1)", tolerance));
  }
  if (!(max_substeps > 0)) return fail(fmt::format("max_substeps = {} must be > 0", max_substeps));
  if (!(newton_tolerance > 0 && newton_tolerance < 1e-3)) {
    return fail(fmt::format("newton_tolerance = {} must be in (0, 1e-3)", newton_tolerance));
  }
  if (!(max_iterations > 0)) {
    return fail(fmt::format("max_iterations = {} must be > 0", max_iterations));
  }
  return true;
}

CamClayStressPoint::CamClayStressPoint(const ModifiedCamClay& model, const Options& options)
    : model_(model), options_(options) {
  std::string why;
  GRANASYM_CHECK(options.IsValid(&why)) << why;
}

CamClayStressPoint::Summary CamClayStressPoint::Update(const Vector6& strain_increment,
                                                       ModelState* state, Matrix6* tangent) const {
  std::string why;
  Summary summary;
  if (!strain_increment.allFinite()) {
    summary.message = "strain increment is not finite";
    return summary;
  }
  if (!model_.IsAdmissible(*state, &why)) {
    summary.message = "start state: " + why;
    return summary;
  }
  const ModelState start = *state;
  summary = options_.method == Method::kModifiedEuler
                ? UpdateModifiedEuler(strain_increment, state, tangent)
                : UpdateReturnMapping(strain_increment, state, tangent);
  if (summary.success && !model_.IsAdmissible(*state, &why)) {
    summary.success = false;
    summary.message = "end state: " + why;
  }
  if (!summary.success) *state = start;
  return summary;
}

ModelState CamClayStressPoint::ElasticPath(const ModelState& state, const Vector6& strain_increment,
                                           double fraction) const {
  const ModifiedCamClay::Parameters& c = model_.parameters();
  const Vector6 increment = fraction * strain_increment;
  const double trace = Trace<double>(strain_increment);  // tension positive
  const Vector6 deviatoric = Deviator<double>(increment);
  const double p0 = MeanStress(state.stress);
  const Vector6 s0 = Deviator<double>(state.stress);
  const double shear_factor =
      3.0 * (1.0 - 2.0 * c.poisson_ratio) / (2.0 * (1.0 + c.poisson_ratio));  // G/K
  double p = p0;
  Vector6 s = s0;
  if (c.form == ModifiedCamClay::CompressionForm::kLogLog) {
    // p = p0 exp(−α trΔε/κ*); ∫_0^α p dα' = p0 α expm1(x)/x with x = −α trΔε/κ*.
    const double x = -fraction * trace / c.kappa;
    p = p0 * std::exp(x);
    if (c.elasticity == ModifiedCamClay::Elasticity::kPoissonRatio) {
      const double mean_over_path = std::abs(x) > 1e-12 ? p0 * std::expm1(x) / x : p0;
      s = s0 + 2.0 * shear_factor / c.kappa * mean_over_path * deviatoric;
    }
  } else {
    // 1+e = (1+e0) exp(α' trΔε), d ln p = −(1+e) trΔε dα'/κ.
    const double one_plus_e0 = 1.0 + state.void_ratio;
    auto log_p = [&](double a) {
      return std::abs(trace) > 0 ? std::log(p0) - one_plus_e0 * std::expm1(a * trace) / c.kappa
                                 : std::log(p0);
    };
    p = std::exp(log_p(fraction));
    if (c.elasticity == ModifiedCamClay::Elasticity::kPoissonRatio) {
      // ∫ (1+e) p dα' / α by composite Simpson on a smooth integrand.
      constexpr int kIntervals = 64;
      double integral = 0.0;
      for (int i = 0; i <= kIntervals; ++i) {
        const double a = fraction * i / kIntervals;
        const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
        integral += weight * one_plus_e0 * std::exp(a * trace) * std::exp(log_p(a));
      }
      integral /= 3.0 * kIntervals;  // mean over [0, α]
      s = s0 + 2.0 * shear_factor / c.kappa * integral * deviatoric;
    }
  }
  if (c.elasticity == ModifiedCamClay::Elasticity::kConstantShearModulus) {
    s = s0 + 2.0 * c.shear_modulus * deviatoric;
  }
  ModelState out = state;
  out.stress = s;
  for (int i = 0; i < 3; ++i) out.stress[i] -= p;
  out.void_ratio = std::expm1(std::log1p(state.void_ratio) + fraction * trace);
  return out;
}

double CamClayStressPoint::ScaledYield(const ModelState& state) const {
  const double m2 =
      model_.parameters().critical_state_ratio * model_.parameters().critical_state_ratio;
  return model_.YieldFunction(state.stress, state.internal[0]) /
         (m2 * state.internal[0] * state.internal[0]);
}

bool CamClayStressPoint::CorrectDrift(ModelState* s) const {
  const double m2 =
      model_.parameters().critical_state_ratio * model_.parameters().critical_state_ratio;
  const double yield_tolerance = model_.parameters().yield_tolerance;
  for (int iteration = 0; iteration < 20; ++iteration) {
    const double f = model_.YieldFunction(s->stress, s->internal[0]);
    const double p_c = s->internal[0];
    if (std::abs(f) <= yield_tolerance * m2 * p_c * p_c) return true;
    const Vector6 n = model_.YieldGradient(s->stress, p_c);
    const Matrix6 elastic = model_.ElasticStiffness(s->stress, s->void_ratio);
    double lambda, kappa;
    model_.CompressionSlopes(s->void_ratio, &lambda, &kappa);
    const double p = MeanStress(s->stress);
    const double hardening = p_c * m2 * (2.0 * p - p_c) / (lambda - kappa);
    const Vector6 elastic_n = elastic * n;
    const double denominator = Contract<double>(n, elastic_n) + m2 * p * hardening;
    ModelState corrected = *s;
    if (denominator > 0) {
      const double multiplier = f / denominator;
      corrected.stress -= multiplier * elastic_n;
      corrected.internal[0] += multiplier * hardening;
    }
    const double f_new = model_.YieldFunction(corrected.stress, corrected.internal[0]);
    if (!(denominator > 0) || !(std::abs(f_new) < std::abs(f)) || !(corrected.internal[0] > 0)) {
      // Normal correction of the stress alone.
      corrected = *s;
      corrected.stress -= f / Contract<double>(n, n) * n;
    }
    *s = corrected;
  }
  const double p_c = s->internal[0];
  return std::abs(model_.YieldFunction(s->stress, p_c)) <= 10 * yield_tolerance * m2 * p_c * p_c;
}

double CamClayStressPoint::ElasticFraction(const ModelState& current,
                                           const Vector6& strain_increment) const {
  const double yield_tolerance = model_.parameters().yield_tolerance;
  const Vector6 n = model_.YieldGradient(current.stress, current.internal[0]);
  const Matrix6 elastic = model_.ElasticStiffness(current.stress, current.void_ratio);
  const bool on_surface = ScaledYield(current) >= -yield_tolerance;
  if (on_surface && Contract<double>(n, elastic * strain_increment) >= 0) return 0.0;
  double lo = 0.0, hi = 1.0;
  if (on_surface) {
    // Elastic unloading then reloading: bracket the second crossing.
    constexpr int kSamples = 32;
    double previous = 0.0;
    bool found = false;
    for (int i = 1; i <= kSamples && !found; ++i) {
      const double a = static_cast<double>(i) / kSamples;
      if (ScaledYield(ElasticPath(current, strain_increment, a)) < -yield_tolerance) {
        previous = a;
        for (int j = i + 1; j <= kSamples; ++j) {
          const double b = static_cast<double>(j) / kSamples;
          if (ScaledYield(ElasticPath(current, strain_increment, b)) > 0) {
            lo = previous;
            hi = b;
            found = true;
            break;
          }
          previous = b;
        }
        break;
      }
    }
    if (!found) lo = hi = 0.0;
  }
  if (!(hi > lo)) return lo;
  // Pegasus iteration on f(α) along the exact elastic path.
  double f_lo = ScaledYield(ElasticPath(current, strain_increment, lo));
  double f_hi = ScaledYield(ElasticPath(current, strain_increment, hi));
  double a = hi;
  for (int iteration = 0; iteration < 100; ++iteration) {
    a = hi - f_hi * (hi - lo) / (f_hi - f_lo);
    const double f_a = ScaledYield(ElasticPath(current, strain_increment, a));
    if (std::abs(f_a) <= yield_tolerance) break;
    if ((f_a < 0) == (f_hi < 0)) {
      f_lo = f_lo * f_hi / (f_hi + f_a);
    } else {
      lo = hi;
      f_lo = f_hi;
    }
    hi = a;
    f_hi = f_a;
  }
  return a;
}

bool CamClayStressPoint::IntegratePlastic(const Vector6& plastic_increment, ModelState* current,
                                          Summary* summary) const {
  double done = 0.0, step = 1.0;
  std::string why;
  while (done < 1.0) {
    if (summary->substeps + summary->rejected_substeps >= options_.max_substeps) {
      summary->message = fmt::format("more than {} substeps", options_.max_substeps);
      return false;
    }
    const Vector6 d = step * plastic_increment;
    ModelRate first, second;
    bool ok = model_.Rate(*current, d, &first, nullptr, &why);
    ModelState predictor = *current;
    double error = 0.0;
    ModelState corrector = *current;
    if (ok) {
      predictor.stress += first.stress_rate;
      predictor.internal += first.internal_rate;
      predictor.void_ratio = std::expm1(std::log1p(current->void_ratio) + Trace<double>(d));
      ok = model_.Rate(predictor, d, &second, nullptr, &why);
    }
    if (ok) {
      corrector.stress += 0.5 * (first.stress_rate + second.stress_rate);
      corrector.internal += 0.5 * (first.internal_rate + second.internal_rate);
      corrector.void_ratio = predictor.void_ratio;
      const double stress_error = 0.5 *
                                  FrobeniusNorm<double>(second.stress_rate - first.stress_rate) /
                                  FrobeniusNorm<double>(corrector.stress);
      const double hardening_error =
          0.5 * std::abs(second.internal_rate[0] - first.internal_rate[0]) / corrector.internal[0];
      error = std::max(stress_error, hardening_error);
      ok = std::isfinite(error) && model_.IsAdmissible(corrector, &why);
    }
    if (!ok || error > options_.tolerance) {
      ++summary->rejected_substeps;
      step *= ok ? std::max(0.9 * std::sqrt(options_.tolerance / error), 0.1) : 0.25;
      if (step < 1e-14) {
        summary->message = "substep below 1e-14 of the increment" + (why.empty() ? "" : ": " + why);
        return false;
      }
      continue;
    }
    *current = corrector;
    if (!CorrectDrift(current)) {
      summary->message = "drift correction did not converge";
      return false;
    }
    ++summary->substeps;
    done += step;
    const double growth =
        error > 0 ? std::min(0.9 * std::sqrt(options_.tolerance / error), 1.1) : 1.1;
    step = std::min(step * std::max(growth, 0.1), 1.0 - done);
  }
  return true;
}

CamClayStressPoint::Summary CamClayStressPoint::UpdateModifiedEuler(const Vector6& strain_increment,
                                                                    ModelState* state,
                                                                    Matrix6* tangent) const {
  Summary summary;
  const double yield_tolerance = model_.parameters().yield_tolerance;
  ModelState current = *state;
  if (ScaledYield(current) > yield_tolerance && !CorrectDrift(&current)) {
    summary.message = "start state outside the yield surface and drift correction failed";
    return summary;
  }
  const ModelState trial = ElasticPath(current, strain_increment, 1.0);
  if (ScaledYield(trial) > yield_tolerance) {
    // Elastic up to the yield surface, then elastoplastic.
    const double fraction = ElasticFraction(current, strain_increment);
    current = ElasticPath(current, strain_increment, fraction);
    summary.plastic = true;
    if (!IntegratePlastic((1.0 - fraction) * strain_increment, &current, &summary)) {
      return summary;
    }
  } else {
    current = trial;
  }
  *state = current;
  if (tangent != nullptr) {
    ModelRate rate;
    std::string why;
    if (!model_.Rate(current, strain_increment, &rate, tangent, &why)) {
      summary.message = "tangent at the end state: " + why;
      return summary;
    }
  }
  summary.success = true;
  return summary;
}

namespace {

struct ReturnData {
  ModifiedCamClay::Parameters parameters;
  Vector6 deviator_start;
  double mean_stress_start;
  double log_preconsolidation_start;
  double log_volume_start;
  double scale;  // (M p_c,n)² for f, p_n for the stress rows
};

// Residual R(x; Δε) of the implicit update, x = [σ (6), ln p_c, Δλ].
template <typename S>
Eigen::Matrix<S, 8, 1> ReturnResidual(const ReturnData& data, const Vec6<S>& stress,
                                      const S& log_preconsolidation, const S& multiplier,
                                      const Vec6<S>& strain_increment) {
  using std::exp;
  const ModifiedCamClay::Parameters& c = data.parameters;
  const double m2 = c.critical_state_ratio * c.critical_state_ratio;
  const S preconsolidation = exp(log_preconsolidation);
  const S p = -Trace(stress) / 3.0;
  const Vec6<S> s = Deviator(stress);
  Vec6<S> n = 3.0 * s;
  for (int i = 0; i < 3; ++i) n[i] -= m2 * (2.0 * p - preconsolidation) / 3.0;
  const Vec6<S> elastic_strain = strain_increment - multiplier * n;
  const S log_volume = data.log_volume_start + Trace(strain_increment);
  const S plastic_volumetric = multiplier * m2 * (2.0 * p - preconsolidation);  // compression +
  // Volume measure v = ln(1+e) (log-log) or e (semi-log), split into elastic and
  // plastic parts: p = p_n exp(−Δv^e/κ), p_c = p_{c,n} exp(−Δv^p/(λ−κ)); exact on the NCL.
  S volume_change, plastic_volume_change;
  S kappa_star(c.kappa);
  if (c.form == ModifiedCamClay::CompressionForm::kSemiLog) {
    const S one_plus_e = exp(log_volume);
    volume_change = std::exp(data.log_volume_start) * (exp(Trace(strain_increment)) - 1.0);
    plastic_volume_change = -one_plus_e * plastic_volumetric;
    kappa_star = c.kappa / one_plus_e;
  } else {
    volume_change = Trace(strain_increment);
    plastic_volume_change = -plastic_volumetric;
  }
  const S p_target =
      data.mean_stress_start * exp(-(volume_change - plastic_volume_change) / c.kappa);
  const S shear = c.elasticity == ModifiedCamClay::Elasticity::kPoissonRatio
                      ? S(p_target / kappa_star *
                          (3.0 * (1.0 - 2.0 * c.poisson_ratio) / (2.0 * (1.0 + c.poisson_ratio))))
                      : S(c.shear_modulus);
  const Vec6<S> s_target = data.deviator_start.cast<S>() + 2.0 * shear * Deviator(elastic_strain);
  Eigen::Matrix<S, 8, 1> residual;
  for (int i = 0; i < 6; ++i) {
    S target = s_target[i];
    if (i < 3) target -= p_target;
    residual[i] = (stress[i] - target) / data.mean_stress_start;
  }
  residual[6] = log_preconsolidation - data.log_preconsolidation_start +
                plastic_volume_change / (c.lambda - c.kappa);
  residual[7] = (1.5 * Contract(s, s) + m2 * p * (p - preconsolidation)) / data.scale;
  return residual;
}

}  // namespace

CamClayStressPoint::Summary CamClayStressPoint::UpdateReturnMapping(const Vector6& strain_increment,
                                                                    ModelState* state,
                                                                    Matrix6* tangent) const {
  Summary summary;
  const ModifiedCamClay::Parameters& c = model_.parameters();
  const double m2 = c.critical_state_ratio * c.critical_state_ratio;
  ReturnData data;
  data.parameters = c;
  data.deviator_start = Deviator<double>(state->stress);
  data.mean_stress_start = MeanStress(state->stress);
  data.log_preconsolidation_start = std::log(state->internal[0]);
  data.log_volume_start = std::log1p(state->void_ratio);
  data.scale = m2 * state->internal[0] * state->internal[0];

  constexpr int kSize = 14;  // x (8) and Δε (6)
  using Ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, kSize, 1>>;
  auto evaluate = [&](const Eigen::Matrix<double, 8, 1>& x, Eigen::Matrix<double, 8, 1>* residual,
                      Eigen::Matrix<double, 8, 8>* d_x, Eigen::Matrix<double, 8, 6>* d_strain) {
    Vec6<Ad> stress, increment;
    for (int i = 0; i < 6; ++i) {
      stress[i] = autodiff::Variable<kSize>(x[i], i);
      increment[i] = autodiff::Variable<kSize>(strain_increment[i], 8 + i);
    }
    const Ad log_pc = autodiff::Variable<kSize>(x[6], 6);
    const Ad multiplier = autodiff::Variable<kSize>(x[7], 7);
    const Eigen::Matrix<Ad, 8, 1> r =
        ReturnResidual<Ad>(data, stress, log_pc, multiplier, increment);
    for (int i = 0; i < 8; ++i) {
      (*residual)[i] = r[i].value();
      d_x->row(i) = r[i].derivatives().head<8>().transpose();
      if (d_strain != nullptr) d_strain->row(i) = r[i].derivatives().tail<6>().transpose();
    }
  };

  // Elastic trial: Δλ = 0 makes the stress rows explicit.
  Eigen::Matrix<double, 8, 1> x;
  {
    Vec6<double> zero_stress = state->stress;
    const Eigen::Matrix<double, 8, 1> r = ReturnResidual<double>(
        data, zero_stress, data.log_preconsolidation_start, 0.0, strain_increment);
    // r_σ = (σ − target)/p_n, so the trial stress is σ − p_n r_σ.
    for (int i = 0; i < 6; ++i) x[i] = state->stress[i] - data.mean_stress_start * r[i];
    x[6] = data.log_preconsolidation_start;
    x[7] = 0.0;
  }
  Vector6 trial_stress = x.head<6>();
  const bool elastic =
      model_.YieldFunction(trial_stress, state->internal[0]) <= c.yield_tolerance * data.scale;
  Eigen::Matrix<double, 8, 1> residual;
  Eigen::Matrix<double, 8, 8> d_x;
  Eigen::Matrix<double, 8, 6> d_strain;
  if (elastic) {
    evaluate(x, &residual, &d_x, &d_strain);
  } else {
    summary.plastic = true;
    bool converged = false;
    for (int iteration = 0; iteration < options_.max_iterations; ++iteration) {
      evaluate(x, &residual, &d_x, nullptr);
      ++summary.iterations;
      if (!residual.allFinite()) break;
      if (residual.cwiseAbs().maxCoeff() <= options_.newton_tolerance) {
        converged = true;
        break;
      }
      Eigen::PartialPivLU<Eigen::Matrix<double, 8, 8>> lu(d_x);
      const Eigen::Matrix<double, 8, 1> step = -lu.solve(residual);
      if (!step.allFinite()) break;
      double fraction = 1.0;
      const double norm = residual.norm();
      for (int search = 0; search < 20; ++search) {
        Eigen::Matrix<double, 8, 1> candidate = x + fraction * step;
        Eigen::Matrix<double, 8, 1> candidate_residual;
        Eigen::Matrix<double, 8, 8> unused;
        evaluate(candidate, &candidate_residual, &unused, nullptr);
        if (candidate_residual.allFinite() && candidate_residual.norm() < norm) {
          x = candidate;
          break;
        }
        fraction *= 0.5;
        if (search == 19) x = candidate;
      }
    }
    if (!converged) {
      summary.message =
          fmt::format("return mapping did not converge in {} iterations (residual {:.3g})",
                      options_.max_iterations, residual.cwiseAbs().maxCoeff());
      return summary;
    }
    if (!(x[7] >= 0)) {
      summary.message =
          fmt::format("return mapping gave a negative plastic multiplier {:.3g}", x[7]);
      return summary;
    }
    evaluate(x, &residual, &d_x, &d_strain);
  }
  ModelState end = *state;
  end.stress = x.head<6>();
  end.internal[0] = std::exp(x[6]);
  end.void_ratio = std::expm1(data.log_volume_start + Trace<double>(strain_increment));
  if (tangent != nullptr) {
    // dx/dΔε = −(∂R/∂x)⁻¹ ∂R/∂Δε; elastically only the stress rows are unknown.
    if (elastic) {
      Eigen::Matrix<double, 6, 6> block = d_x.topLeftCorner<6, 6>();
      *tangent = -block.partialPivLu().solve(d_strain.topRows<6>());
    } else {
      const Eigen::Matrix<double, 8, 6> dx = -d_x.partialPivLu().solve(d_strain);
      *tangent = dx.topRows<6>();
    }
  }
  *state = end;
  summary.substeps = 1;
  summary.success = true;
  return summary;
}

}  // namespace granasym
