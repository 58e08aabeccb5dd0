#include "dem/asymptote_detector.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "common/canonical_text.h"
#include "common/config.h"
#include "common/state_measures.h"

namespace granasym::dem {
namespace {

bool UsesLnpWindow(PathKind kind) {
  return kind == PathKind::kCompression || kind == PathKind::kExtension;
}

// Least-squares slope of y(x) over samples [begin, end). The sums are taken
// about the first sample, so that x without spread (constant p) gives
// sxx == 0 exactly instead of a slope of rounding noise.
template <typename X, typename Y>
double Slope(const std::vector<AsymptoteDetector::Sample>& samples, size_t begin, size_t end, X x,
             Y y) {
  const double x0 = x(samples[begin]), y0 = y(samples[begin]);
  double mean_x = 0, mean_y = 0;
  const double n = static_cast<double>(end - begin);
  for (size_t k = begin; k < end; ++k) {
    mean_x += x(samples[k]) - x0;
    mean_y += y(samples[k]) - y0;
  }
  mean_x /= n;
  mean_y /= n;
  double sxy = 0, sxx = 0;
  for (size_t k = begin; k < end; ++k) {
    const double dx = x(samples[k]) - x0 - mean_x;
    sxy += dx * (y(samples[k]) - y0 - mean_y);
    sxx += dx * dx;
  }
  return sxx > 0 ? sxy / sxx : 0.0;
}

// ψ_ε of the strain increment between samples a and b (rad).
double IncrementPsi(const AsymptoteDetector::Sample& a, const AsymptoteDetector::Sample& b) {
  return AxisymmetricRate{b.eps_a - a.eps_a, b.eps_r - a.eps_r}.psi();
}

}  // namespace

PathKind StrainPathKind(double psi_epsilon_deg) {
  const double magnitude = std::abs(psi_epsilon_deg);
  if (std::abs(magnitude - 90.0) <= 1e-6) return PathKind::kIsochoric;
  return magnitude < 90.0 ? PathKind::kCompression : PathKind::kExtension;
}

AsymptoteCriterion AsymptoteCriterion::For(PathKind kind) {
  AsymptoteCriterion c;
  c.kind = kind;
  if (UsesLnpWindow(kind)) {
    c.window_strain = 0.3;
    // ψ_σ of a few thousand spheres fluctuates by about ±1° on the NCL.
    c.psi_tolerance_deg = 1.0;
  }
  if (kind == PathKind::kExtension) {
    // Along the extension paths of the paper's programme (3000 spheres,
    // ψ_ε = 100° from NC 100, 500 and 1000 kPa, 3 replicates, p between the
    // floor and 45 kPa) ψ_σ scatters about its trend with a standard
    // deviation of 1.3-1.6° (2.7-3° near the floor) and a lag-one
    // autocorrelation of 0.4-0.75 between output rows 0.002 apart; the fitted
    // change across a window of 0.3 strain then has a standard error of about
    // 0.85°. Twice that accepts a stationary state; the 1° of the compression
    // paths would reject one window in four of it (docs/guide/scenes.md, "Extension
    // asymptotic states").
    c.psi_tolerance_deg = 2.0;
    // At the paper's rate these states are dense flows whose p barely moves
    // while ln(1+e) rises (ψ_ε = 100° from NC 500 kPa: p 1.6-2.9 kPa over
    // 0.2 of strain), so the relative change of d ln(1+e)/d ln p divides by a
    // rate of ln p near zero and means nothing. Since ln(1+e) rises at the
    // rate ψ_ε imposes, a stationary slope is a stationary rate of ln p: the
    // criterion is the change of that rate between the half-windows, in ln p
    // over half a window. Measured on the same paths, ln p scatters about its
    // trend by 0.13-0.19 (lag-one autocorrelation 0.70-0.83), a standard
    // error of the change of about 0.25 at 3000 spheres; 0.4 accepts a
    // stationary state most of the time, and the transients (the fall from
    // the NC state, p levelling off) change ψ_σ by far more than 2° anyway.
    c.lnp_tolerance = 0.4;
  }
  return c;
}

std::string AsymptoteCriterion::Describe() const {
  const std::string samples = fmt::format(" (samples every {:g} of strain)", sample_strain);
  switch (kind) {
    case PathKind::kIsochoric:
      return fmt::format(
          "isochoric: over the last {:g} of accumulated strain{}: fitted change of ln p < {:g} "
          "and of psi_sigma < {:g} deg",
          window_strain, samples, lnp_tolerance, psi_tolerance_deg);
    case PathKind::kCompression:
      return fmt::format(
          "compression: over the last {:g} of |delta ln p| (at most {:g} of accumulated "
          "strain){}: fitted change of psi_sigma < {:g} deg, and the slopes d ln(1+e)/d ln p of "
          "the two half-windows differ by < {:g} of their mean{}",
          window_lnp, window_strain, samples, psi_tolerance_deg, slope_tolerance,
          transient_strain > 0
              ? fmt::format("; no window before {:g} of accumulated strain", transient_strain)
              : "");
    case PathKind::kExtension:
      return fmt::format(
          "extension: over the last {:g} of |delta ln p| (at most {:g} of accumulated "
          "strain){}: fitted change of psi_sigma < {:g} deg, and the fitted rates of ln p of the "
          "two half-windows differ by < {:g} of ln p over half the window; windows with p >= {:g} "
          "kPa only, the last that held is kept{}",
          window_lnp, window_strain, samples, psi_tolerance_deg, lnp_tolerance, floor_kpa,
          transient_strain > 0
              ? fmt::format("; no window before {:g} of accumulated strain", transient_strain)
              : "");
    case PathKind::kStressControlled:
      return fmt::format(
          "stress_controlled: over the last {:g} of accumulated strain{}: psi_epsilon of the "
          "strain increments of the two half-windows differs by < {:g} deg, fitted change of "
          "ln(1+e) < {:g} and of psi_sigma < {:g} deg",
          window_strain, samples, psi_epsilon_tolerance_deg, lnv_tolerance, psi_tolerance_deg);
  }
  return "unknown path kind";
}

AsymptoteCriterion AsymptoteCriterion::Parse(const ConfigTable& a, PathKind kind) {
  AsymptoteCriterion c = For(kind);
  c.sample_strain = a.GetDouble("sample_strain", c.sample_strain, {0.0, 1.0, false, true});
  c.window_strain = a.GetDouble("window_strain", c.window_strain, {0.0, 100.0, false, true});
  c.psi_tolerance_deg =
      a.GetDouble("psi_tolerance_deg", c.psi_tolerance_deg, {0.0, 90.0, false, true});
  switch (kind) {
    case PathKind::kIsochoric:
      c.lnp_tolerance = a.GetDouble("lnp_tolerance", c.lnp_tolerance, {0.0, 10.0, false, true});
      break;
    case PathKind::kCompression:
      c.window_lnp = a.GetDouble("window_lnp", c.window_lnp, {0.0, 20.0, false, true});
      c.slope_tolerance =
          a.GetDouble("slope_tolerance", c.slope_tolerance, {0.0, 10.0, false, true});
      c.transient_strain =
          a.GetDouble("transient_strain", c.transient_strain, {0.0, 100.0, true, true});
      break;
    case PathKind::kExtension:
      c.window_lnp = a.GetDouble("window_lnp", c.window_lnp, {0.0, 20.0, false, true});
      c.transient_strain =
          a.GetDouble("transient_strain", c.transient_strain, {0.0, 100.0, true, true});
      c.lnp_tolerance = a.GetDouble("lnp_tolerance", c.lnp_tolerance, {0.0, 10.0, false, true});
      c.floor_kpa = a.GetDouble("floor_kpa", c.floor_kpa, {0.0, 1e6, false, true});
      break;
    case PathKind::kStressControlled:
      c.psi_epsilon_tolerance_deg = a.GetDouble(
          "psi_epsilon_tolerance_deg", c.psi_epsilon_tolerance_deg, {0.0, 90.0, false, true});
      c.lnv_tolerance = a.GetDouble("lnv_tolerance", c.lnv_tolerance, {0.0, 1.0, false, true});
      break;
  }
  if (c.window_strain < AsymptoteDetector::kMinSamples * c.sample_strain) {
    a.Fail("window_strain",
           fmt::format("= {:g} must be at least {} times sample_strain ({:g})", c.window_strain,
                       AsymptoteDetector::kMinSamples, c.sample_strain));
  }
  return c;
}

void AsymptoteCriterion::Canonical(CanonicalText& text, const std::string& prefix) const {
  text.Add(prefix + "kind", ToString(kind));
  text.Add(prefix + "sample_strain", sample_strain);
  text.Add(prefix + "window_strain", window_strain);
  text.Add(prefix + "psi_tolerance_deg", psi_tolerance_deg);
  switch (kind) {
    case PathKind::kIsochoric:
      text.Add(prefix + "lnp_tolerance", lnp_tolerance);
      break;
    case PathKind::kCompression:
      text.Add(prefix + "window_lnp", window_lnp);
      text.Add(prefix + "slope_tolerance", slope_tolerance);
      if (transient_strain > 0) text.Add(prefix + "transient_strain", transient_strain);
      break;
    case PathKind::kExtension:
      text.Add(prefix + "window_lnp", window_lnp);
      text.Add(prefix + "lnp_tolerance", lnp_tolerance);
      text.Add(prefix + "floor_kpa", floor_kpa);
      if (transient_strain > 0) text.Add(prefix + "transient_strain", transient_strain);
      break;
    case PathKind::kStressControlled:
      text.Add(prefix + "psi_epsilon_tolerance_deg", psi_epsilon_tolerance_deg);
      text.Add(prefix + "lnv_tolerance", lnv_tolerance);
      break;
  }
}

void AsymptoteDetector::Add(const Sample& sample) {
  if (!std::isfinite(sample.log_p)) {
    samples_.clear();
    return;
  }
  samples_.push_back(sample);
  // Keep a little more than one window (a window in ln p is at most
  // window_strain long).
  size_t first = 0;
  while (first < samples_.size() &&
         samples_.back().strain - samples_[first].strain > 1.5 * criterion_.window_strain) {
    ++first;
  }
  if (first > 0) samples_.erase(samples_.begin(), samples_.begin() + static_cast<long>(first));
}

size_t AsymptoteDetector::WindowBegin() const {
  const size_t none = samples_.size();
  if (samples_.size() < kMinSamples) return none;
  const Sample& last = samples_.back();
  const double window = criterion_.window_strain;
  const bool by_lnp = UsesLnpWindow(criterion_.kind);
  // Walk back to the first sample that completes the window.
  for (size_t k = samples_.size() - 1; k-- > 0;) {
    const double span = last.strain - samples_[k].strain;
    const bool full_strain = span >= window * (1 - 1e-9);
    const bool full_lnp =
        by_lnp && std::abs(last.log_p - samples_[k].log_p) >= criterion_.window_lnp;
    if (full_strain || full_lnp) {
      if (criterion_.transient_strain > 0 && samples_[k].strain < criterion_.transient_strain) {
        return none;  // a window of a continued path starts at a negative strain
      }
      return samples_.size() - k >= kMinSamples ? k : none;
    }
  }
  return none;
}

bool AsymptoteDetector::ready() const { return WindowBegin() < samples_.size(); }

AsymptoteDetector::Result AsymptoteDetector::Evaluate() const {
  Result result;
  const size_t begin = WindowBegin();
  const size_t end = samples_.size();
  if (begin >= end) return result;
  const Sample& first = samples_[begin];
  const Sample& last = samples_.back();
  const double window = last.strain - first.strain;
  const double mid_strain = first.strain + 0.5 * window;
  size_t middle = begin;
  while (middle < end && samples_[middle].strain < mid_strain) ++middle;
  if (middle - begin < 3 || end - middle < 3) return result;
  result.window_strain = window;
  result.window_lnp = std::abs(last.log_p - first.log_p);
  result.window_start_time = first.time;
  result.window_end_time = last.time;
  result.window_end_strain = last.strain;
  double min_log_p = first.log_p, max_log_p = first.log_p;
  for (size_t k = begin; k < end; ++k) {
    min_log_p = std::min(min_log_p, samples_[k].log_p);
    max_log_p = std::max(max_log_p, samples_[k].log_p);
  }
  result.p_min_kpa = std::exp(min_log_p);
  result.p_max_kpa = std::exp(max_log_p);
  result.below_floor =
      criterion_.kind == PathKind::kExtension && result.p_min_kpa < criterion_.floor_kpa;

  auto strain = [](const Sample& s) { return s.strain; };
  auto psi = [](const Sample& s) { return s.psi_sigma; };
  auto log_p = [](const Sample& s) { return s.log_p; };
  auto log_v = [](const Sample& s) { return s.log_volume; };
  // The state: means over the window of ψ_σ, ln p and ln(1+e) (so that a
  // state on a line in ln(1+e)–ln p stays on it: p is the geometric mean).
  const double n = static_cast<double>(end - begin);
  double mean_log_p = 0, mean_log_v = 0;
  for (size_t k = begin; k < end; ++k) {
    const Sample& s = samples_[k];
    result.psi_sigma += s.psi_sigma / n;
    mean_log_p += s.log_p / n;
    mean_log_v += s.log_volume / n;
    result.q_over_p += 3.0 / std::sqrt(2.0) * std::tan(s.psi_sigma) / n;
  }
  result.mean_stress_kpa = std::exp(mean_log_p);
  result.void_ratio = std::expm1(mean_log_v);
  result.psi_epsilon = IncrementPsi(first, last);
  result.psi_change_deg = std::abs(Slope(samples_, begin, end, strain, psi)) * window / kDegree;
  result.slope_lnp = Slope(samples_, begin, end, strain, log_p);
  result.lnp_change = std::abs(result.slope_lnp) * window;
  result.slope_lnv_lnp = Slope(samples_, begin, end, log_p, log_v);
  const double lnv_slope = Slope(samples_, begin, end, strain, log_v);
  result.lnv_change = std::abs(lnv_slope) * window;

  const double lnp_first = Slope(samples_, begin, middle, strain, log_p);
  const double lnp_second = Slope(samples_, middle, end, strain, log_p);
  result.lnp_half_difference = std::abs(lnp_second - lnp_first) * 0.5 * window;
  // d ln(1+e)/d ln p of each half as the ratio of the fitted rates per unit
  // strain (strain carries no noise; noise in ln p would bias a direct fit).
  const double lnv_first = Slope(samples_, begin, middle, strain, log_v);
  const double lnv_second = Slope(samples_, middle, end, strain, log_v);
  const double lambda_first = lnp_first != 0 ? lnv_first / lnp_first : 0.0;
  const double lambda_second = lnp_second != 0 ? lnv_second / lnp_second : 0.0;
  const double lambda_mean = 0.5 * (std::abs(lambda_first) + std::abs(lambda_second));
  result.slope_change = lambda_mean > 0 ? std::abs(lambda_second - lambda_first) / lambda_mean
                                        : (lambda_first == lambda_second ? 0.0 : HUGE_VAL);
  result.psi_epsilon_change_deg =
      std::abs(IncrementPsi(samples_[middle], last) - IncrementPsi(first, samples_[middle])) /
      kDegree;

  const AsymptoteCriterion& c = criterion_;
  bool holds = result.psi_change_deg < c.psi_tolerance_deg && !result.below_floor;
  switch (c.kind) {
    case PathKind::kIsochoric:
      holds = holds && result.lnp_change < c.lnp_tolerance;
      break;
    case PathKind::kCompression:
      holds = holds && result.slope_change < c.slope_tolerance;
      break;
    case PathKind::kExtension:
      holds = holds && result.lnp_half_difference < c.lnp_tolerance;
      break;
    case PathKind::kStressControlled:
      holds = holds && result.psi_epsilon_change_deg < c.psi_epsilon_tolerance_deg &&
              result.lnv_change < c.lnv_tolerance;
      break;
  }
  result.status = holds ? AsymptoteStatus::kDetected : AsymptoteStatus::kDrifting;
  return result;
}

void AsymptoteDetector::Track() {
  if (criterion_.kind != PathKind::kExtension) return;
  Result result = Evaluate();
  if (result.detected()) last_held_ = result;
}

namespace {

// The numbers of a Result in the order of PackResult.
template <typename R>
auto ResultFields(R& r) {
  return std::array{
      &r.window_strain,          &r.window_lnp, &r.window_start_time,   &r.window_end_time,
      &r.window_end_strain,      &r.p_min_kpa,  &r.p_max_kpa,           &r.psi_sigma,
      &r.mean_stress_kpa,        &r.void_ratio, &r.psi_epsilon,         &r.q_over_p,
      &r.psi_change_deg,         &r.lnp_change, &r.lnp_half_difference, &r.slope_change,
      &r.psi_epsilon_change_deg, &r.lnv_change, &r.slope_lnp,           &r.slope_lnv_lnp};
}

}  // namespace

std::vector<double> PackResult(const AsymptoteDetector::Result& result) {
  std::vector<double> values = {static_cast<double>(result.status), result.below_floor ? 1.0 : 0.0};
  for (const double* field : ResultFields(result)) values.push_back(*field);
  return values;
}

AsymptoteDetector::Result UnpackResult(const std::vector<double>& values) {
  AsymptoteDetector::Result result;
  auto fields = ResultFields(result);
  if (values.size() != fields.size() + 2) {
    throw std::invalid_argument(fmt::format("an asymptote window has {} numbers, not {}",
                                            values.size(), fields.size() + 2));
  }
  const int status = static_cast<int>(values[0]);
  if (status < 0 || status > static_cast<int>(AsymptoteStatus::kInvalid) || values[0] != status) {
    throw std::invalid_argument(fmt::format("{:g} is not an asymptote status", values[0]));
  }
  result.status = static_cast<AsymptoteStatus>(status);
  result.below_floor = values[1] != 0;
  for (size_t k = 0; k < fields.size(); ++k) *fields[k] = values[k + 2];
  return result;
}

}  // namespace granasym::dem
