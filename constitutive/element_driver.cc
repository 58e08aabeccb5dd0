// The mixed-control element-test driver: stages, stops by root finding,
// records, and the Cam clay strain-increment path.
#include "constitutive/element_driver.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/stopwatch.h"
#include "constitutive/eigen.h"
#include "constitutive/model_traits.h"

namespace granasym {

namespace {

// Layout of the ODE state y.
constexpr int kStress = 0;     // T, tension positive (6)
constexpr int kLogVolume = 6;  // ln(1 + e)
constexpr int kStrain = 7;     // ∫D dt, tension positive (6)
constexpr int kPath = 13;      // ∫‖D‖ dt
constexpr int kInternal = 14;  // model internal variables

bool Fail(std::string* why, const std::string& message) {
  if (why != nullptr) *why = message;
  return false;
}

}  // namespace

LoadingStage LoadingStage::Proportional(double psi_epsilon, double stretching_rate,
                                        double duration) {
  LoadingStage stage;
  stage.name = fmt::format("proportional psi_epsilon={:.6g} deg", psi_epsilon / kDegree);
  const AxisymmetricRate rate = AxisymmetricRate::FromAngle(psi_epsilon, stretching_rate);
  stage.rate = {rate.axial, rate.radial, rate.radial, 0, 0, 0};
  stage.duration = duration;
  return stage;
}

LoadingStage LoadingStage::ConstantRadialStress(double axial_rate, double duration) {
  LoadingStage stage;
  stage.name = "constant radial stress";
  stage.control[1] = stage.control[2] = ComponentControl::kStressRate;
  stage.rate = {axial_rate, 0, 0, 0, 0, 0};
  stage.duration = duration;
  return stage;
}

LoadingStage LoadingStage::Isochoric(double axial_rate, double duration) {
  LoadingStage stage;
  stage.name = "isochoric";
  stage.rate = {axial_rate, -0.5 * axial_rate, -0.5 * axial_rate, 0, 0, 0};
  stage.duration = duration;
  return stage;
}

LoadingStage LoadingStage::Oedometric(double axial_rate, double duration) {
  LoadingStage stage;
  stage.name = "oedometric";
  stage.rate = {axial_rate, 0, 0, 0, 0, 0};
  stage.duration = duration;
  return stage;
}

LoadingStage LoadingStage::IsotropicToMeanStress(double target_mean_stress,
                                                 double stretching_rate) {
  LoadingStage stage;
  stage.name = fmt::format("isotropic to p={:.6g} kPa", target_mean_stress);
  stage.rate = {stretching_rate, 0, 0, 0, 0, 0};
  stage.isotropic_target = target_mean_stress;
  // Generous duration: the stop fires long before for any realistic model.
  stage.duration = 50.0 / stretching_rate;
  stage.stops.push_back({StopKind::kMeanStress, target_mean_stress});
  return stage;
}

namespace {
// Resolves the direction of an isotropic stage from the current mean stress.
LoadingStage ResolveStage(const LoadingStage& stage, double mean_stress) {
  if (!(stage.isotropic_target > 0)) return stage;
  const bool loading = stage.isotropic_target > mean_stress;
  LoadingStage resolved = LoadingStage::Proportional(loading ? 0.0 : kPi, stage.rate[0], 0.0);
  resolved.name = fmt::format("isotropic {} to p={:.6g} kPa", loading ? "loading" : "unloading",
                              stage.isotropic_target);
  resolved.duration = stage.duration;
  resolved.stops = stage.stops;
  resolved.output_points = stage.output_points;
  return resolved;
}
}  // namespace

Vector6 AxisymmetricStressTensor(double mean_stress, double psi_sigma) {
  const double q = 3.0 * mean_stress * std::tan(psi_sigma) / std::sqrt(2.0);
  const SymTensor compression{
      mean_stress + 2.0 * q / 3.0, mean_stress - q / 3.0, mean_stress - q / 3.0, 0, 0, 0};
  return ToVector(FlipSign(compression));
}

namespace {
ModelState CheckedInitialState(const ConstitutiveModel& model, double mean_stress, double psi_sigma,
                               double void_ratio) {
  if (!(mean_stress > 0)) {
    throw InputError(fmt::format("initial mean stress p = {} kPa must be > 0", mean_stress));
  }
  if (!(std::abs(psi_sigma) < kPi / 2)) {
    throw InputError(
        fmt::format("initial psi_sigma = {} deg must be in (−90, 90)", psi_sigma / kDegree));
  }
  ModelState state = model.MakeState(AxisymmetricStressTensor(mean_stress, psi_sigma), void_ratio);
  std::string why;
  if (!model.IsAdmissibleStart(state, &why)) {
    throw InputError(fmt::format(
        "initial state p = {} kPa, psi_sigma = {} deg, e = {} is outside the model's domain: {}",
        mean_stress, psi_sigma / kDegree, void_ratio, why));
  }
  return state;
}
}  // namespace

ModelState InitialStateFromVoidRatio(const ConstitutiveModel& model, double mean_stress,
                                     double psi_sigma, double void_ratio) {
  return CheckedInitialState(model, mean_stress, psi_sigma, void_ratio);
}

ModelState InitialStateFromOcr(const ConstitutiveModel& model, double mean_stress, double psi_sigma,
                               double ocr) {
  if (!(ocr > 0)) throw InputError(fmt::format("initial OCR = {} must be > 0", ocr));
  return CheckedInitialState(model, mean_stress, psi_sigma,
                             model.VoidRatioForOcr(mean_stress, ocr));
}

IntegratorOptions DefaultIntegratorOptions(ModelKind model) {
  IntegratorOptions options;
  options.kind = IntegratorKind::kArkodeErk;
  options.arkode_order = 5;
  options.relative_tolerance = options.absolute_tolerance = Traits(model).integrator_tolerance;
  return options;
}

bool HasStressPointMethod(const ConstitutiveModel& model) {
  return dynamic_cast<const ModifiedCamClay*>(&model) != nullptr;
}

namespace {

// `options` with tolerances left at 0 replaced by those of `defaults`.
IntegratorOptions WithDefaultTolerances(IntegratorOptions options,
                                        const IntegratorOptions& defaults) {
  if (options.relative_tolerance == 0.0) options.relative_tolerance = defaults.relative_tolerance;
  if (options.absolute_tolerance == 0.0) options.absolute_tolerance = defaults.absolute_tolerance;
  return options;
}

}  // namespace

bool ElementTestOptions::IsValid(std::string* why) const {
  std::string inner;
  // Zero tolerances mean "the model's default", valid for every model: the
  // integrator's own defaults stand in for it here.
  if (!WithDefaultTolerances(integrator, IntegratorOptions()).IsValid(&inner)) {
    return Fail(why, "integrator." + inner);
  }
  if (!stress_point.IsValid(&inner)) return Fail(why, "stress_point." + inner);
  if (!(control_tolerance > 0 && control_tolerance < 1e-3)) {
    return Fail(why, fmt::format("control_tolerance = {} must be in (0, 1e-3)", control_tolerance));
  }
  if (!(limit_point_condition > 0 && limit_point_condition < 0.1)) {
    return Fail(
        why, fmt::format("limit_point_condition = {} must be in (0, 0.1)", limit_point_condition));
  }
  if (!(control_max_iterations > 0)) {
    return Fail(why,
                fmt::format("control_max_iterations = {} must be > 0", control_max_iterations));
  }
  if (!(max_strain_increment > 0 && max_strain_increment <= 0.1)) {
    return Fail(why,
                fmt::format("max_strain_increment = {} must be in (0, 0.1]", max_strain_increment));
  }
  if (!(stop_location_tolerance > 0 && stop_location_tolerance < 1e-2)) {
    return Fail(why, fmt::format("stop_location_tolerance = {} must be in (0, 0.01)",
                                 stop_location_tolerance));
  }
  return true;
}

std::string ElementTestSummary::Report() const {
  std::string line = fmt::format("{} after {} stage(s): {} steps ({} rejected), {} RHS, {:.3g} s",
                                 ToString(termination), stages.size(), totals.steps,
                                 totals.rejected_steps, totals.rhs_evaluations, totals.wall_time_s);
  if (!message.empty()) line += " — " + message;
  return line;
}

AxisymmetricStress RecordStress(const ElementTestRecord& record) {
  return AxisymmetricFromTensor(record.stress);
}

AxisymmetricRate RecordStretching(const ElementTestRecord& record) {
  return {record.stretching[0], 0.5 * (record.stretching[1] + record.stretching[2])};
}

namespace {

// IntegrationSummary::root_index of a stage that ended at a limit point.
constexpr int kLimitPointStop = -2;

// Smallest stress scale of the error control, as a fraction of ‖T‖
// (StageOde::StateScales).
constexpr double kCutoffScaleFloor = 1e-2;

// The ODE of one stage under mixed control.
class StageOde : public OdeSystem {
 public:
  StageOde(const ConstitutiveModel& model, const LoadingStage& stage,
           const ElementTestOptions& options, double stress_scale)
      : model_(model),
        stage_(stage),
        options_(options),
        stress_scale_(stress_scale),
        switch_offsets_(model.num_switches(), 0.0),
        switch_disabled_(model.num_switches(), false) {
    // Internally tension positive: one sign flip of the whole rate vector.
    prescribed_ = ToVector(FlipSign(stage.rate));
    for (int i = 0; i < 6; ++i) {
      (stage.control[i] == ComponentControl::kStressRate ? unknown_ : known_).push_back(i);
    }
    warm_start_.setZero();
  }

  int dimension() const override { return kInternal + model_.num_internal(); }

  void ComponentScales(double* scale) const override {
    for (int i = 0; i < dimension(); ++i) scale[i] = 1.0;
    for (int i = 0; i < 6; ++i) scale[kStress + i] = stress_scale_;
    for (int i = kInternal; i < dimension(); ++i) scale[i] = stress_scale_;
  }

  // Stresses (and stress-like internal variables) scale with the current
  // ‖T‖: the models are homogeneous in stress, and a fixed scale from the
  // stage start would let the absolute tolerance swamp p after unloading by
  // orders of magnitude (path fuzzing: extension beyond the limit d took p
  // from 4 to 1e-6 kPa with errors larger than p, and states far outside the SBS).
  // Near the tension cutoff they scale with the smallest principal
  // compression σ_min instead, as √3 σ_min = ‖σ_min 1‖ (so isotropic states
  // keep ‖T‖) and not below 1 % of ‖T‖: the rate depends on the direction of
  // T, whose distance from the edge of the compressive cone is σ_min, and an
  // error that is small against ‖T‖ can cross it (path fuzzing: oedometric
  // unloading of hypoplastic clay to σ_a = 2 kPa at σ_r = 90 kPa, BDF at rtol
  // 4.8e-4 — σ_a wandered between 0.07 and 2.6 kPa and ended at 10 or 422 kPa,
  // outside the SBS; the scale on σ_a is now 3.5 kPa instead of 128 kPa).
  void StateScales(const double* y, double* scale) const override {
    ComponentScales(scale);
    const Eigen::Map<const Vector6> stress(y + kStress);
    const double norm = FrobeniusNorm<double>(stress);
    if (!(norm > 0) || !std::isfinite(norm)) return;
    Eigen::Matrix3d compression;
    compression << -stress[0], -stress[3], -stress[4], -stress[3], -stress[1], -stress[5],
        -stress[4], -stress[5], -stress[2];
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal;
    principal.computeDirect(compression, Eigen::EigenvaluesOnly);
    const double stress_scale = std::clamp(std::sqrt(3.0) * principal.eigenvalues().minCoeff(),
                                           kCutoffScaleFloor * norm, norm);
    for (int i = 0; i < 6; ++i) scale[kStress + i] = stress_scale;
    for (int i = kInternal; i < dimension(); ++i) scale[i] = std::max(norm, std::abs(y[i]));
  }

  ModelState StateOf(const double* y) const {
    ModelState state;
    state.stress = Eigen::Map<const Vector6>(y + kStress);
    state.void_ratio = std::expm1(y[kLogVolume]);
    state.internal = Eigen::Map<const Eigen::VectorXd>(y + kInternal, model_.num_internal());
    state.branch = branch_;
    return state;
  }

  // The stretching that satisfies the stage's control at `state`.
  bool SolveStretching(const ModelState& state, Vector6* stretching, ModelRate* rate,
                       Matrix6* tangent_out = nullptr) {
    Vector6 d = warm_start_;
    for (int i : known_) d[i] = prescribed_[i];
    Matrix6 tangent;
    const int n = static_cast<int>(unknown_.size());
    if (n == 0) {
      if (!model_.Rate(state, d, rate, tangent_out, &failure_)) return false;
      *stretching = d;
      return true;
    }
    Eigen::VectorXd residual(n), trial_residual(n);
    auto evaluate = [&](const Vector6& candidate, ModelRate* r, Matrix6* t,
                        Eigen::VectorXd* res) -> bool {
      if (!model_.Rate(state, candidate, r, t, &failure_)) return false;
      for (int k = 0; k < n; ++k)
        (*res)[k] = r->stress_rate[unknown_[k]] - prescribed_[unknown_[k]];
      return true;
    };
    if (!evaluate(d, rate, &tangent, &residual)) return false;
    for (int iteration = 0; iteration < options_.control_max_iterations; ++iteration) {
      const double scale =
          rate->stress_rate.cwiseAbs().maxCoeff() + prescribed_.cwiseAbs().maxCoeff() + 1e-300;
      if (residual.cwiseAbs().maxCoeff() <= options_.control_tolerance * scale) {
        return Accept(d, tangent, stretching, tangent_out);
      }
      Eigen::MatrixXd block(n, n);
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) block(a, b) = tangent(unknown_[a], unknown_[b]);
      }
      Eigen::FullPivLU<Eigen::MatrixXd> lu(block);
      if (!lu.isInvertible()) {
        failure_ = "the tangent block of the stress-controlled components is singular";
        return false;
      }
      const Eigen::VectorXd step = -lu.solve(residual);
      double fraction = 1.0;
      bool improved = false;
      for (int search = 0; search < 30; ++search) {
        Vector6 candidate = d;
        for (int k = 0; k < n; ++k) candidate[unknown_[k]] += fraction * step[k];
        ModelRate candidate_rate;
        Matrix6 candidate_tangent;
        if (evaluate(candidate, &candidate_rate, &candidate_tangent, &trial_residual) &&
            trial_residual.norm() < (1.0 - 1e-4 * fraction) * residual.norm()) {
          d = candidate;
          *rate = candidate_rate;
          tangent = candidate_tangent;
          residual = trial_residual;
          improved = true;
          break;
        }
        fraction *= 0.5;
      }
      if (!improved) break;
    }
    const double scale =
        rate->stress_rate.cwiseAbs().maxCoeff() + prescribed_.cwiseAbs().maxCoeff() + 1e-300;
    if (residual.cwiseAbs().maxCoeff() <= 1e3 * options_.control_tolerance * scale) {
      return Accept(d, tangent, stretching, tangent_out);
    }
    failure_ = fmt::format("mixed control did not converge (residual {:.3g} kPa/s)",
                           residual.cwiseAbs().maxCoeff());
    return false;
  }

  // σ_min(B)/‖∂T̊/∂D‖_F for the block B = ∂T̊_u/∂D_u of the stress-controlled
  // components u, with the sign of det B: how close B is to singular measured
  // against the stiffness as a whole (a 1×1 block is never ill-conditioned by
  // itself). Elasticity alone gives about 2G/3K for all three normal
  // components, more for fewer.
  static double ControllabilityRatio(const Matrix6& tangent, const std::vector<int>& unknown) {
    const int n = static_cast<int>(unknown.size());
    Eigen::MatrixXd block(n, n);
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) block(a, b) = tangent(unknown[a], unknown[b]);
    }
    const double scale = tangent.norm();
    if (!(scale > 0) || !std::isfinite(scale)) return 0.0;
    const double smallest = Eigen::JacobiSVD<Eigen::MatrixXd>(block).singularValues()[n - 1];
    const double ratio = smallest / scale;
    return Eigen::FullPivLU<Eigen::MatrixXd>(block).determinant() > 0 ? ratio : -ratio;
  }

  // A mixed-control solution counts only while the stress-controlled block of
  // the tangent stays regular and keeps the orientation it has in elasticity
  // (det B > 0: every principal block of a positive definite stiffness has
  // it). A rate law that is piecewise smooth and positively homogeneous in D
  // maps the unknown stretchings one to one onto the controlled stress rates
  // only while det B keeps one sign on all its pieces; where B turns singular
  // the controlled path has a limit point (softening, e.g. Cam clay on the
  // dry side, or q → M p, under stress control): the stretching needed grows
  // without bound, and beyond it the prescribed rates have no solution or
  // several (elastic unloading and plastic softening). Near it the
  // integrators see a spike of the rates that they may step through onto a
  // state the path never reaches (path fuzzing: CVODE BDF took a Cam clay
  // state at p = 0.06 kPa through σ_min/σ_max = 2e-6 and ended at e = −0.48,
  // 4 (M p_c)² outside the yield surface). That is a reported failure.
  //
  // The stage stops at the limit (a root, located like any stop, then a
  // failure with the state there); right-hand sides are refused only ten
  // times beyond it, so that steps whose ends straddle it reach the root.
  bool Accept(const Vector6& d, const Matrix6& tangent, Vector6* stretching, Matrix6* tangent_out) {
    last_ratio_ = ControllabilityRatio(tangent, unknown_);
    const double ratio = last_ratio_;
    if (!(ratio > 0.1 * options_.limit_point_condition)) {
      failure_ = fmt::format(
          "limit point of the stress-controlled path: the block of dT/dD for the "
          "stress-controlled components has {} {:.3g} (limit {:.3g}), so the prescribed stress "
          "rates have no unique bounded stretching (softening or a critical state under stress "
          "control)",
          ratio > 0 ? "sigma_min/|dT/dD|" : "a flipped orientation, sigma_min/|dT/dD|",
          std::abs(ratio), 0.1 * options_.limit_point_condition);
      return false;
    }
    *stretching = d;
    warm_start_ = d;
    if (tangent_out != nullptr) *tangent_out = tangent;
    return true;
  }

  bool Rhs(double, const double* y, double* y_dot) override {
    const ModelState state = StateOf(y);
    Vector6 d;
    ModelRate rate;
    if (!SolveStretching(state, &d, &rate)) return false;
    for (int i = 0; i < 6; ++i) y_dot[kStress + i] = rate.stress_rate[i];
    for (int i : unknown_) y_dot[kStress + i] = prescribed_[i];
    y_dot[kLogVolume] = Trace<double>(d);
    for (int i = 0; i < 6; ++i) y_dot[kStrain + i] = d[i];
    y_dot[kPath] = FrobeniusNorm<double>(d);
    for (int i = 0; i < model_.num_internal(); ++i) y_dot[kInternal + i] = rate.internal_rate[i];
    return true;
  }

  bool has_jacobian() const override { return true; }

  bool Jacobian(double, const double* y, double* jacobian) override {
    const int dim = dimension();
    const int num_internal = model_.num_internal();
    const int num_state = 7 + num_internal;  // model state x = [T, ln(1+e), q]
    const ModelState state = StateOf(y);
    Vector6 d;
    ModelRate rate;
    if (!SolveStretching(state, &d, &rate)) return false;
    RateJacobian model_jacobian;
    if (!model_.Jacobian(state, d, &model_jacobian, &failure_)) return false;
    const Eigen::MatrixXd& jx = model_jacobian.d_state;
    const Eigen::MatrixXd& jd = model_jacobian.d_stretching;
    // dD/dx: zero for prescribed components; implicit function theorem for the others.
    Eigen::MatrixXd dd_dx = Eigen::MatrixXd::Zero(6, num_state);
    const int n = static_cast<int>(unknown_.size());
    if (n > 0) {
      Eigen::MatrixXd block(n, n), rhs(n, num_state);
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) block(a, b) = jd(unknown_[a], unknown_[b]);
        rhs.row(a) = jx.row(unknown_[a]);
      }
      Eigen::FullPivLU<Eigen::MatrixXd> lu(block);
      if (!lu.isInvertible()) {
        failure_ = "singular stress-control block in the Jacobian";
        return false;
      }
      const Eigen::MatrixXd solution = -lu.solve(rhs);
      for (int a = 0; a < n; ++a) dd_dx.row(unknown_[a]) = solution.row(a);
    }
    // Rows of y_dot with respect to x, then scattered into y's columns.
    Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(dim, num_state);
    const Eigen::MatrixXd rates = jx + jd * dd_dx;  // (6 + n_int) x num_state
    for (int i = 0; i < 6; ++i) rows.row(kStress + i) = rates.row(i);
    for (int i : unknown_) rows.row(kStress + i).setZero();
    rows.row(kLogVolume) = dd_dx.row(0) + dd_dx.row(1) + dd_dx.row(2);
    for (int i = 0; i < 6; ++i) rows.row(kStrain + i) = dd_dx.row(i);
    const double d_norm = FrobeniusNorm<double>(d);
    if (d_norm > 0) {
      Vector6 weighted = d / d_norm;
      weighted.tail<3>() *= 2.0;
      rows.row(kPath) = weighted.transpose() * dd_dx;
    }
    for (int k = 0; k < num_internal; ++k) rows.row(kInternal + k) = rates.row(6 + k);
    Eigen::Map<Eigen::MatrixXd> out(jacobian, dim, dim);
    out.setZero();
    for (int c = 0; c < num_state; ++c) {
      const int column = c < 7 ? c : kInternal + (c - 7);
      out.col(column) = rows.col(c);
    }
    return out.allFinite();
  }

  bool Constraints(double* codes) const override {
    Vector6 stress_codes;
    Eigen::VectorXd internal_codes;
    model_.SignConstraints(&stress_codes, &internal_codes);
    for (int i = 0; i < dimension(); ++i) codes[i] = 0.0;
    bool any = false;
    for (int i = 0; i < 6; ++i) {
      codes[kStress + i] = stress_codes[i];
      any = any || stress_codes[i] != 0;
    }
    for (int i = 0; i < internal_codes.size(); ++i) {
      codes[kInternal + i] = internal_codes[i];
      any = any || internal_codes[i] != 0;
    }
    return any;
  }

  // The stage's stops, then the model's switches (ModelState kinks).
  int num_stops() const { return static_cast<int>(stage_.stops.size()); }
  int num_roots() const override {
    return num_stops() + model_.num_switches() + (unknown_.empty() ? 0 : 1);
  }
  // The index of the limit-point root (mixed control only), or −1.
  int limit_point_root() const {
    return unknown_.empty() ? -1 : num_stops() + model_.num_switches();
  }

  bool Roots(double t, const double* y, double* g) override {
    for (size_t k = 0; k < stage_.stops.size(); ++k) g[k] = StopFunction(stage_.stops[k], t, y);
    const int num_switches = model_.num_switches();
    if (num_switches > 0) {
      SwitchValues(y, g + num_stops());
      for (int k = 0; k < num_switches; ++k) {
        g[num_stops() + k] = switch_disabled_[k] ? 1.0 : g[num_stops() + k] + switch_offsets_[k];
      }
    }
    if (limit_point_root() >= 0) {
      Vector6 d;
      ModelRate rate;
      const bool solved = SolveStretching(StateOf(y), &d, &rate);
      g[limit_point_root()] = solved ? last_ratio_ - options_.limit_point_condition : -1.0;
    }
    return true;
  }

  // The model's switch functions of the held branch at y, for the stretching
  // there (1 where the stage's control has no solution: no crossing).
  void SwitchValues(const double* y, double* values) {
    const ModelState state = StateOf(y);
    Vector6 d;
    ModelRate rate;
    if (!SolveStretching(state, &d, &rate)) {
      std::fill(values, values + model_.num_switches(), 1.0);
      return;
    }
    model_.Switches(state, d, values);
  }

  // At the start of a piece at y: the branch the model takes there, held
  // until one of its switch functions (positive while it holds) crosses
  // zero. A switch that starts below kSwitchHysteresis (at the crossing that
  // ended the last piece, where root location leaves it within round-off of
  // zero) is lifted to it, so that the restart does not find the same
  // crossing again. With a switch disabled the model decides per evaluation.
  void ChooseBranch(const double* y) {
    const int num_switches = model_.num_switches();
    switch_offsets_.assign(num_switches, 0.0);
    branch_ = kAutoBranch;
    if (num_switches == 0 || std::find(switch_disabled_.begin(), switch_disabled_.end(), true) !=
                                 switch_disabled_.end()) {
      return;
    }
    Vector6 d;
    ModelRate rate;
    if (!SolveStretching(StateOf(y), &d, &rate)) return;
    branch_ = model_.Branch(StateOf(y), d);
    std::vector<double> values(num_switches);
    SwitchValues(y, values.data());
    for (int k = 0; k < num_switches; ++k) {
      if (values[k] < kSwitchHysteresis) switch_offsets_[k] = kSwitchHysteresis - values[k];
    }
  }
  static constexpr double kSwitchHysteresis = 1e-9;

  // A switch that keeps firing (the state slides along it) is ignored for the
  // rest of the stage, and the model decides its branch per evaluation; its
  // own stabilisation takes over there.
  void DisableSwitch(int k) {
    switch_disabled_[k] = true;
    branch_ = kAutoBranch;
  }

  double StopFunction(const StopCondition& stop, double t, const double* y) {
    // Compression-positive measures of the tension-positive state.
    const double p = -(y[kStress] + y[kStress + 1] + y[kStress + 2]) / 3.0;
    const double axial_strain = -y[kStrain];
    const double radial_strain = -0.5 * (y[kStrain + 1] + y[kStrain + 2]);
    switch (stop.kind) {
      case StopKind::kMeanStress:
        return p - stop.value;
      case StopKind::kAxialStrain:
        return axial_strain - stop.value;
      case StopKind::kVolumetricStrain:
        return axial_strain + 2.0 * radial_strain - stop.value;
      case StopKind::kShearStrain:
        return 2.0 * (axial_strain - radial_strain) / 3.0 - stop.value;
      case StopKind::kStrainPath:
        return y[kPath] - stop.value;
      case StopKind::kStressRatio: {
        const Vector6 stress = Eigen::Map<const Vector6>(y + kStress);
        const double q = -(stress[0] - 0.5 * (stress[1] + stress[2]));
        return q / p - stop.value;
      }
      case StopKind::kAsymptote:
        return AsymptoteMeasure(t, y) - stop.value;
    }
    return 1.0;
  }

  // |dψ_σ/ds| + |d ln OCR/ds| along the current path (per unit strain path).
  double AsymptoteMeasure(double t, const double* y) {
    std::vector<double> y_dot(dimension());
    if (!Rhs(t, y, y_dot.data())) return 1.0;  // undefined: not at an asymptote
    const double path_rate = y_dot[kPath];
    if (!(path_rate > 0)) return 1.0;
    const double sa = -y[kStress], sr = -0.5 * (y[kStress + 1] + y[kStress + 2]);
    const double dsa = -y_dot[kStress], dsr = -0.5 * (y_dot[kStress + 1] + y_dot[kStress + 2]);
    const double x = sa + 2.0 * sr, yy = std::sqrt(2.0) * (sa - sr);
    const double dx = dsa + 2.0 * dsr, dy = std::sqrt(2.0) * (dsa - dsr);
    const double psi_rate = (x * dy - yy * dx) / (x * x + yy * yy);
    // d ln p_e/d ln(1+e) by a central difference in v = ln(1+e): exact for NCLs
    // linear in v (−1/λ*), O(h²) accurate otherwise, free of cancellation noise.
    const double v = y[kLogVolume];
    const double h = 1e-3;
    const double dlnpe_dv = (std::log(model_.EquivalentPressure(std::expm1(v + h))) -
                             std::log(model_.EquivalentPressure(std::expm1(v - h)))) /
                            (2.0 * h);
    const double log_ocr_rate = dlnpe_dv * y_dot[kLogVolume] - dx / x;  // d ln p = dx/x
    return (std::abs(psi_rate) + std::abs(log_ocr_rate)) / path_rate;
  }

  const std::string& last_failure() const override { return failure_; }
  const std::vector<int>& unknown() const { return unknown_; }
  const std::vector<int>& known() const { return known_; }
  const Vector6& prescribed() const { return prescribed_; }

 private:
  const ConstitutiveModel& model_;
  const LoadingStage& stage_;
  const ElementTestOptions& options_;
  double stress_scale_;
  Vector6 prescribed_;
  std::vector<int> unknown_, known_;
  Vector6 warm_start_;
  double last_ratio_ = 1.0;  // ControllabilityRatio at the last solution
  std::string failure_;
  std::vector<double> switch_offsets_;
  std::vector<bool> switch_disabled_;
  int branch_ = kAutoBranch;  // held over the current piece (ChooseBranch)
};

ElementTestRecord MakeRecord(const ConstitutiveModel& model, StageOde& ode, double time,
                             const double* y, int stage) {
  ElementTestRecord record;
  const ModelState state = ode.StateOf(y);
  record.time = time;
  record.stress = FlipSign(ToSymTensor(state.stress));
  record.void_ratio = state.void_ratio;
  record.strain = FlipSign(ToSymTensor(Eigen::Map<const Vector6>(y + kStrain)));
  record.strain_path = y[kPath];
  Vector6 d = Vector6::Zero();
  ModelRate rate;
  if (!ode.SolveStretching(state, &d, &rate)) d.setZero();
  record.stretching = FlipSign(ToSymTensor(d));
  record.internal.assign(state.internal.data(), state.internal.data() + state.internal.size());
  record.ocr = OverconsolidationRatio(model, state);
  record.stage = stage;
  return record;
}

std::string DescribeStop(const StopCondition& stop) {
  return fmt::format("{}={:.6g}", ToString(stop.kind), stop.value);
}

// Strain increments of the stress-point method (Cam clay) under mixed
// control: Newton on the unknown components of the strain increment (the
// consistent tangent of the return mapping, forward differences of the
// update itself for modified Euler) with a halving line search.
class StressPointIncrements {
 public:
  // `rate_guess`: the stretching expected, for the first guess of the unknown
  // components (later, those of the last increment).
  StressPointIncrements(const CamClayStressPoint& stress_point, const ElementTestOptions& options,
                        StageOde& ode, const Vector6& rate_guess, IntegrationSummary* counters)
      : stress_point_(stress_point),
        options_(options),
        ode_(ode),
        unknown_(ode.unknown()),
        known_(ode.known()),
        prescribed_(ode.prescribed()),
        n_(static_cast<int>(unknown_.size())),
        unknown_rate_guess_(rate_guess),
        counters_(counters) {}

  // One increment of duration h from y0 into y1; false with the reason.
  bool Take(const std::vector<double>& y0, double h, std::vector<double>* y1, std::string* why) {
    const ModelState start = ode_.StateOf(y0.data());
    Vector6 strain = unknown_rate_guess_ * h;
    for (int i : known_) strain[i] = prescribed_[i] * h;
    ModelState end;
    Eigen::VectorXd residual;
    if (!SolveMixedControl(start, h, &strain, &end, &residual, why)) return false;
    for (int i : unknown_) unknown_rate_guess_[i] = strain[i] / h;
    y1->assign(ode_.dimension(), 0.0);
    for (int i = 0; i < 6; ++i) (*y1)[kStress + i] = end.stress[i];
    for (int i : unknown_) (*y1)[kStress + i] = y0[kStress + i] + prescribed_[i] * h;
    (*y1)[kLogVolume] = y0[kLogVolume] + Trace<double>(strain);
    for (int i = 0; i < 6; ++i) (*y1)[kStrain + i] = y0[kStrain + i] + strain[i];
    (*y1)[kPath] = y0[kPath] + FrobeniusNorm<double>(strain);
    for (int i = 0; i < end.internal.size(); ++i) (*y1)[kInternal + i] = end.internal[i];
    return true;
  }

 private:
  // The update of `start` by the strain increment `trial` and the residual
  // of the stress-controlled components.
  bool Solve(const ModelState& start, double h, const Vector6& trial, ModelState* out,
             Matrix6* tangent, Eigen::VectorXd* residual, std::string* why) {
    *out = start;
    const CamClayStressPoint::Summary update = stress_point_.Update(trial, out, tangent);
    ++counters_->rhs_evaluations;
    counters_->nonlinear_iterations += update.iterations;
    counters_->rejected_steps += update.rejected_substeps;
    if (!update.success) {
      *why = update.message;
      return false;
    }
    residual->resize(n_);
    for (int k = 0; k < n_; ++k) {
      const int i = unknown_[k];
      (*residual)[k] = out->stress[i] - start.stress[i] - prescribed_[i] * h;
    }
    return true;
  }

  // The strain increment whose stress-controlled components follow their
  // prescribed rates: Newton on the unknown components from `strain`.
  bool SolveMixedControl(const ModelState& start, double h, Vector6* strain, ModelState* end,
                         Eigen::VectorXd* residual, std::string* why) {
    const bool consistent =
        stress_point_.options().method == CamClayStressPoint::Method::kReturnMapping;
    Matrix6 tangent;
    if (!Solve(start, h, *strain, end, n_ > 0 && consistent ? &tangent : nullptr, residual, why)) {
      return false;
    }
    for (int iteration = 0; n_ > 0; ++iteration) {
      const double scale =
          std::max((end->stress - start.stress).cwiseAbs().maxCoeff(), 1e-12 * start.stress.norm());
      if (residual->cwiseAbs().maxCoeff() <= options_.control_tolerance * 10 * scale) break;
      if (iteration == options_.control_max_iterations) {
        *why = fmt::format(
            "mixed control of the strain increment did not converge (residual "
            "{:.3g} kPa)",
            residual->cwiseAbs().maxCoeff());
        return false;
      }
      Eigen::MatrixXd block(n_, n_);
      if (consistent) {
        for (int a = 0; a < n_; ++a) {
          for (int b = 0; b < n_; ++b) block(a, b) = tangent(unknown_[a], unknown_[b]);
        }
      } else {
        // Modified Euler: forward differences of the update itself.
        for (int b = 0; b < n_; ++b) {
          Vector6 perturbed = *strain;
          const double step = 1e-7 * std::max(FrobeniusNorm<double>(*strain), 1e-9);
          perturbed[unknown_[b]] += step;
          ModelState unused;
          Eigen::VectorXd perturbed_residual;
          if (!Solve(start, h, perturbed, &unused, nullptr, &perturbed_residual, why)) {
            return false;
          }
          block.col(b) = (perturbed_residual - *residual) / step;
        }
      }
      const Eigen::VectorXd correction = -block.fullPivLu().solve(*residual);
      double fraction = 1.0;
      bool improved = false;
      for (int search = 0; search < 20; ++search) {
        Vector6 candidate = *strain;
        for (int k = 0; k < n_; ++k) candidate[unknown_[k]] += fraction * correction[k];
        ModelState candidate_end;
        Eigen::VectorXd candidate_residual;
        Matrix6 candidate_tangent;
        if (Solve(start, h, candidate, &candidate_end, consistent ? &candidate_tangent : nullptr,
                  &candidate_residual, why) &&
            candidate_residual.norm() < residual->norm()) {
          *strain = candidate;
          *end = candidate_end;
          *residual = candidate_residual;
          if (consistent) tangent = candidate_tangent;
          improved = true;
          break;
        }
        fraction *= 0.5;
      }
      if (!improved) {
        *why = "mixed control of the strain increment stalled";
        return false;
      }
    }
    return true;
  }

  const CamClayStressPoint& stress_point_;
  const ElementTestOptions& options_;
  StageOde& ode_;
  const std::vector<int>& unknown_;
  const std::vector<int>& known_;
  const Vector6& prescribed_;
  const int n_;  // unknown components
  Vector6 unknown_rate_guess_;
  IntegrationSummary* counters_;
};

// The crossing of stop `crossed` inside the increment of duration h from
// (t, y), whose end is `y_end`: bisection on the fraction of the increment
// to stop_location_tolerance; `*y` becomes the state just past the crossing.
// Returns the fraction reached.
double LocateStop(StressPointIncrements& increments, StageOde& ode,
                  const ElementTestOptions& options, double t, double h, int crossed,
                  double g_crossed_before, const std::vector<double>& y_end,
                  std::vector<double>* y) {
  double lo = 0.0, hi = 1.0;
  std::vector<double> y_hi = y_end, y_mid;
  std::string why;
  while ((hi - lo) > options.stop_location_tolerance) {
    const double mid = 0.5 * (lo + hi);
    if (!increments.Take(*y, mid * h, &y_mid, &why)) break;
    std::vector<double> g(ode.num_roots());
    ode.Roots(t + mid * h, y_mid.data(), g.data());
    if ((g[crossed] < 0) == (g_crossed_before < 0) && g[crossed] != 0) {
      lo = mid;
    } else {
      hi = mid;
      y_hi = y_mid;
    }
  }
  *y = y_hi;
  return hi;
}

// Cam clay stress-point stage: strain increments of at most
// max_strain_increment, each halved on failure, records at the stage's
// output times, and stops located by bisection.
IntegrationSummary RunStressPointStage(const CamClayStressPoint& stress_point,
                                       const ElementTestOptions& options, StageOde& ode,
                                       const LoadingStage& stage, std::vector<double>* y,
                                       const std::function<void(double, const double*)>& observer) {
  Stopwatch stopwatch;
  IntegrationSummary summary;
  summary.termination = TerminationType::kReachedEnd;

  // Time per increment from the strain rate (known and, estimated, unknown parts).
  Vector6 rate_estimate;
  ModelRate rate;
  if (!ode.SolveStretching(ode.StateOf(y->data()), &rate_estimate, &rate)) {
    summary.termination = TerminationType::kFailure;
    summary.message = "initial stretching: " + ode.last_failure();
    return summary;
  }
  const double stretching_norm = FrobeniusNorm<double>(rate_estimate);
  double dt = stretching_norm > 0 ? options.max_strain_increment / stretching_norm
                                  : stage.duration / 1000.0;
  StressPointIncrements increments(stress_point, options, ode, rate_estimate, &summary);

  const int num_roots = ode.num_roots();
  std::vector<double> g_old(num_roots), g_new(num_roots);
  ode.Roots(0.0, y->data(), g_old.data());
  const double output_interval = stage.duration / std::max(1, stage.output_points);
  double next_output = output_interval;
  double t = 0.0;
  std::vector<double> y_new;
  std::string why;
  double h_current = dt;
  while (t < stage.duration * (1.0 - 1e-14)) {
    // Path fuzzing: near a limit point every increment but a vanishing one
    // can fail, and the stage crept on for ever; the step limit ends it.
    if (summary.steps >= options.integrator.max_steps) {
      summary.termination = TerminationType::kFailure;
      summary.message =
          fmt::format("more than integrator.max_steps = {} increments at t = {:.6g} s",
                      options.integrator.max_steps, t);
      break;
    }
    double h = std::min(h_current, stage.duration - t);
    // A failed increment (non-smooth transition, no convergence) is halved.
    bool ok = increments.Take(*y, h, &y_new, &why);
    for (int halving = 0; !ok && halving < 30; ++halving) {
      ++summary.rejected_steps;
      h *= 0.5;
      ok = increments.Take(*y, h, &y_new, &why);
    }
    if (!ok) {
      summary.termination = TerminationType::kFailure;
      summary.message = fmt::format("increment at t = {:.6g} s failed: {}", t, why);
      break;
    }
    h_current = std::min(dt, 2.0 * h);
    ++summary.steps;
    ode.Roots(t + h, y_new.data(), g_new.data());
    int crossed = -1;
    // Stops only: the increments handle the model's switches themselves.
    for (int k = 0; k < ode.num_stops(); ++k) {
      if ((g_old[k] < 0 && g_new[k] >= 0) || (g_old[k] > 0 && g_new[k] <= 0)) {
        crossed = k;
        break;
      }
    }
    if (crossed >= 0) {
      t += LocateStop(increments, ode, options, t, h, crossed, g_old[crossed], y_new, y) * h;
      summary.termination = TerminationType::kRootFound;
      summary.root_index = crossed;
      break;
    }
    // Records at the output times inside this increment, evenly spaced in the
    // stage as with the rate integrators: a partial increment from its start
    // (the path itself keeps the increments it chose).
    while (next_output < std::min(t + h, stage.duration) * (1.0 - 1e-12)) {
      std::vector<double> y_output;
      std::string output_why;
      const double fraction = next_output - t;
      if (fraction > 0 && increments.Take(*y, fraction, &y_output, &output_why)) {
        observer(next_output, y_output.data());
      }
      next_output += output_interval;
    }
    *y = y_new;
    t += h;
    g_old = g_new;
    if (t >= next_output * (1.0 - 1e-12) && t < stage.duration * (1.0 - 1e-14)) {
      observer(t, y->data());
      while (next_output <= t * (1.0 + 1e-12)) next_output += output_interval;
    }
  }
  summary.final_time = t;
  summary.wall_time_s = stopwatch.Seconds();
  return summary;
}

// The ODE state y of a model state (kStress, kLogVolume, kInternal; strains
// and strain path 0).
std::vector<double> OdeStateOf(const ModelState& state, int num_internal) {
  std::vector<double> y(kInternal + num_internal, 0.0);
  for (int i = 0; i < 6; ++i) y[kStress + i] = state.stress[i];
  y[kLogVolume] = std::log1p(state.void_ratio);
  for (int i = 0; i < num_internal; ++i) y[kInternal + i] = state.internal[i];
  return y;
}

// A stage with the rate integrator, in pieces: each piece holds the branch
// the model takes at its start (ConstitutiveModel::Branch), a root of that
// branch's switches ends it, and the next starts there on the branch the
// state then takes. Each switch stops the integration at most
// kMaxSwitchStops times per stage: more means the state slides along it
// (seen in path fuzzing at the Cam clay critical state), where restarts only
// cost, and the model then decides its branch per evaluation. A limit point of a stress-controlled
// stage ends it as a failure. `stage_summary` sums the pieces as they end (it keeps them when a
// piece throws).
void IntegrateInPieces(Integrator& integrator, StageOde& ode, const LoadingStage& stage,
                       const ElementTestOptions& options, int num_switches, std::vector<double>* y,
                       const Integrator::Observer& observer, IntegrationSummary* stage_summary) {
  std::vector<double> output_times;
  for (int i = 1; i < stage.output_points; ++i) {
    output_times.push_back(stage.duration * i / stage.output_points);
  }
  constexpr int kMaxSwitchStops = 20;
  constexpr int kMaxSwitches = 10000;
  std::vector<int> switch_stops(num_switches, 0);
  double start = 0.0;
  for (int piece = 0;; ++piece) {
    ode.ChooseBranch(y->data());
    const IntegrationSummary part =
        integrator.Integrate(ode, start, stage.duration, y->data(), output_times, observer);
    if (piece == 0) {
      *stage_summary = part;
    } else {
      stage_summary->Accumulate(part);
      stage_summary->termination = part.termination;
      stage_summary->message = part.message;
      stage_summary->root_index = part.root_index;
      stage_summary->final_time = part.final_time;
    }
    if (part.termination == TerminationType::kRootFound &&
        part.root_index == ode.limit_point_root()) {
      const ModelState there = ode.StateOf(y->data());
      stage_summary->termination = TerminationType::kFailure;
      stage_summary->root_index = kLimitPointStop;
      stage_summary->message = fmt::format(
          "limit point of the stress-controlled path at t = {:.9g} s (p = {:.6g} kPa, "
          "q = {:.6g} kPa, e = {:.6g}): the block of dT/dD for the stress-controlled "
          "components reached sigma_min/|dT/dD| = {:.3g} (limit_point_condition), so the "
          "prescribed stress rates have no unique bounded stretching beyond it (softening, "
          "or a critical state under stress control)",
          part.final_time, MeanStress(there.stress), DeviatorStress(there.stress), there.void_ratio,
          options.limit_point_condition);
      break;
    }
    const bool switched =
        part.termination == TerminationType::kRootFound && part.root_index >= ode.num_stops();
    if (!switched) break;
    if (piece == kMaxSwitches) {
      stage_summary->termination = TerminationType::kFailure;
      stage_summary->root_index = -1;
      stage_summary->message = fmt::format(
          "more than {} crossings of the model's switching surfaces (chattering at t = "
          "{:.6g})",
          kMaxSwitches, part.final_time);
      break;
    }
    start = part.final_time;
    const int which = part.root_index - ode.num_stops();
    if (++switch_stops[which] >= kMaxSwitchStops) ode.DisableSwitch(which);
    stage_summary->root_index = -1;
    stage_summary->termination = TerminationType::kReachedEnd;
  }
}

// One stage by either method; an asymptote stop that already holds ends it
// at once, and a RuntimeError (a failed library call) is a failure.
IntegrationSummary RunStage(const ConstitutiveModel& model, const ElementTestOptions& options,
                            Integrator* integrator, const CamClayStressPoint* stress_point,
                            StageOde& ode, const LoadingStage& stage, std::vector<double>* y,
                            const Integrator::Observer& observer) {
  IntegrationSummary stage_summary;
  int satisfied = -1;
  for (size_t s = 0; s < stage.stops.size() && satisfied < 0; ++s) {
    if (stage.stops[s].kind == StopKind::kAsymptote &&
        ode.StopFunction(stage.stops[s], 0.0, y->data()) <= 0) {
      satisfied = static_cast<int>(s);
    }
  }
  try {
    if (satisfied >= 0) {
      stage_summary.termination = TerminationType::kRootFound;
      stage_summary.root_index = satisfied;
    } else if (integrator) {
      IntegrateInPieces(*integrator, ode, stage, options, model.num_switches(), y, observer,
                        &stage_summary);
    } else {
      stage_summary = RunStressPointStage(*stress_point, options, ode, stage, y, observer);
    }
  } catch (const RuntimeError& error) {
    stage_summary.termination = TerminationType::kFailure;
    stage_summary.message = error.what();
  }
  return stage_summary;
}

// The report of a stage: its name, counters and the stop that ended it.
StageSummary ReportStage(const LoadingStage& stage, const IntegrationSummary& stage_summary) {
  StageSummary stage_report;
  stage_report.name = stage.name;
  stage_report.integration = stage_summary;
  if (stage_summary.root_index >= 0 &&
      stage_summary.root_index < static_cast<int>(stage.stops.size())) {
    stage_report.stop = DescribeStop(stage.stops[stage_summary.root_index]);
  } else {
    stage_report.stop = stage_summary.root_index == kLimitPointStop ? "limit_point" : "duration";
  }
  return stage_report;
}

// Whether a stage ended well at a finite state inside the model's domain;
// else (a success so far) its message says why the final state is invalid.
bool StageEndValid(const ConstitutiveModel& model, StageOde& ode, const std::vector<double>& y,
                   IntegrationSummary* stage_summary) {
  bool valid = stage_summary->success();
  if (valid) {
    std::string why;
    for (double value : y) valid = valid && std::isfinite(value);
    valid = valid && model.IsAdmissible(ode.StateOf(y.data()), &why);
    if (!valid && stage_summary->success()) {
      stage_summary->message = "final state invalid: " + why;
    }
  }
  return valid;
}

}  // namespace

ElementTest::ElementTest(const ConstitutiveModel& model, const ElementTestOptions& options)
    : model_(model), options_(options) {
  std::string why;
  GRANASYM_CHECK(options.IsValid(&why)) << why;
  options_.integrator =
      WithDefaultTolerances(options.integrator, DefaultIntegratorOptions(model.kind()));
  GRANASYM_CHECK(options.method == DriveMethod::kRateIntegration || HasStressPointMethod(model))
      << "the stress-point method exists for Modified Cam clay only";
}

ElementTestResult ElementTest::Run(const ModelState& initial,
                                   const std::vector<LoadingStage>& stages) const {
  ElementTestResult result;
  ElementTestSummary& summary = result.summary;
  result.final_state = initial;
  std::string why;
  if (!model_.IsAdmissible(initial, &why)) {
    summary.termination = TerminationType::kFailure;
    summary.message = "initial state: " + why;
    return result;
  }
  summary.termination = TerminationType::kReachedEnd;
  summary.message.clear();
  std::vector<double> y = OdeStateOf(initial, model_.num_internal());

  std::unique_ptr<Integrator> integrator;
  std::unique_ptr<CamClayStressPoint> stress_point;
  if (options_.method == DriveMethod::kRateIntegration) {
    integrator = Integrator::Create(options_.integrator);
  } else {
    stress_point = std::make_unique<CamClayStressPoint>(
        dynamic_cast<const ModifiedCamClay&>(model_), options_.stress_point);
  }

  double time = 0.0;
  for (size_t k = 0; k < stages.size(); ++k) {
    const double mean_stress = MeanStress(Eigen::Map<const Vector6>(y.data()));
    const LoadingStage stage = ResolveStage(stages[k], mean_stress);
    const int stage_index = static_cast<int>(k);
    const double stress_scale = std::max(mean_stress, 1e-6);
    StageOde ode(model_, stage, options_, stress_scale);
    if (k == 0) result.history.push_back(MakeRecord(model_, ode, 0.0, y.data(), stage_index));
    const Integrator::Observer observer = [&](double t, const double* state) {
      result.history.push_back(MakeRecord(model_, ode, time + t, state, stage_index));
    };
    const std::vector<double> y_start = y;
    IntegrationSummary stage_summary =
        RunStage(model_, options_, integrator.get(), stress_point.get(), ode, stage, &y, observer);
    summary.stages.push_back(ReportStage(stage, stage_summary));
    summary.totals.Accumulate(stage_summary);
    if (!StageEndValid(model_, ode, y, &stage_summary)) {
      // The records of the valid part of the stage stay. A limit point ends
      // the path at a valid state, recorded as the last one (e.g. the peak
      // of a stress-controlled test); otherwise the state goes back to the
      // start of the stage, the last state known to be valid.
      bool at_limit_point = stage_summary.root_index == kLimitPointStop;
      for (double value : y) at_limit_point = at_limit_point && std::isfinite(value);
      if (at_limit_point && model_.IsAdmissible(ode.StateOf(y.data()), &why)) {
        time += stage_summary.final_time;
        result.history.push_back(MakeRecord(model_, ode, time, y.data(), stage_index));
        result.final_state = ode.StateOf(y.data());
      } else {
        y = y_start;
      }
      summary.termination = TerminationType::kFailure;
      summary.message =
          fmt::format("stage {} ({}): {}", k, stage.name,
                      stage_summary.message.empty() ? "failed" : stage_summary.message);
      summary.stages.back().integration.termination = TerminationType::kFailure;
      break;
    }
    time += stage_summary.final_time;
    result.history.push_back(MakeRecord(model_, ode, time, y.data(), stage_index));
    result.final_state = ode.StateOf(y.data());
    summary.termination = stage_summary.termination;
  }
  if (summary.success()) summary.termination = TerminationType::kReachedEnd;
  summary.totals.final_time = time;
  return result;
}

}  // namespace granasym
