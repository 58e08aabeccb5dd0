#include "dem/asymptote_detector.h"

#include <cmath>
#include <sstream>

#include "common/canonical_text.h"
#include "common/config.h"
#include "common/state_measures.h"

namespace granasym::dem {

std::string AsymptoteCriterion::Describe() const {
  std::ostringstream out;
  out << "over the last " << window_strain << " of accumulated strain (samples every "
      << sample_strain << "): fitted change of psi_sigma < " << psi_tolerance_deg
      << " deg, and the changes of ln p over the two half-windows differ by < " << lnp_tolerance;
  return out.str();
}

AsymptoteCriterion AsymptoteCriterion::Parse(const ConfigTable& a) {
  AsymptoteCriterion c;
  c.sample_strain = a.GetDouble("sample_strain", c.sample_strain, Range::Positive());
  c.window_strain = a.GetDouble("window_strain", c.window_strain, Range::Positive());
  c.psi_tolerance_deg = a.GetDouble("psi_tolerance_deg", c.psi_tolerance_deg, Range::Positive());
  c.lnp_tolerance = a.GetDouble("lnp_tolerance", c.lnp_tolerance, Range::Positive());
  if (c.window_strain < 8 * c.sample_strain) {
    a.Fail("window_strain", "= " + std::to_string(c.window_strain) +
                                " must be at least 8 times sample_strain (" +
                                std::to_string(c.sample_strain) + ")");
  }
  return c;
}

void AsymptoteCriterion::Canonical(CanonicalText& text, const std::string& prefix) const {
  text.Add(prefix + "sample_strain", sample_strain);
  text.Add(prefix + "window_strain", window_strain);
  text.Add(prefix + "psi_tolerance_deg", psi_tolerance_deg);
  text.Add(prefix + "lnp_tolerance", lnp_tolerance);
}
namespace {

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

}  // namespace

void AsymptoteDetector::Add(const Sample& sample) {
  if (!std::isfinite(sample.log_p)) {
    samples_.clear();
    return;
  }
  samples_.push_back(sample);
  // Keep a little more than one window.
  size_t first = 0;
  while (first < samples_.size() &&
         samples_.back().strain - samples_[first].strain > 1.5 * criterion_.window_strain) {
    ++first;
  }
  if (first > 0) samples_.erase(samples_.begin(), samples_.begin() + static_cast<long>(first));
}

bool AsymptoteDetector::ready() const {
  return samples_.size() >= 8 &&
         samples_.back().strain - samples_.front().strain >= criterion_.window_strain * (1 - 1e-9);
}

AsymptoteDetector::Result AsymptoteDetector::Evaluate() const {
  Result result;
  if (!ready()) return result;
  const double end_strain = samples_.back().strain;
  const double window = criterion_.window_strain;
  size_t begin = 0;
  while (end_strain - samples_[begin].strain > window * (1 + 1e-9)) ++begin;
  const size_t end = samples_.size();
  const double mid_strain = end_strain - 0.5 * window;
  size_t middle = begin;
  while (middle < end && samples_[middle].strain < mid_strain) ++middle;
  if (middle - begin < 3 || end - middle < 3) return result;
  auto strain = [](const Sample& s) { return s.strain; };
  auto psi = [](const Sample& s) { return s.psi_sigma; };
  auto log_p = [](const Sample& s) { return s.log_p; };
  auto log_v = [](const Sample& s) { return s.log_volume; };
  double mean_psi = 0;
  for (size_t k = begin; k < end; ++k) mean_psi += samples_[k].psi_sigma;
  result.psi_sigma = mean_psi / static_cast<double>(end - begin);
  result.psi_change_deg = std::abs(Slope(samples_, begin, end, strain, psi)) * window / kDegree;
  const double first_half = Slope(samples_, begin, middle, strain, log_p);
  const double second_half = Slope(samples_, middle, end, strain, log_p);
  result.lnp_half_difference = std::abs(second_half - first_half) * 0.5 * window;
  result.slope_lnp = Slope(samples_, begin, end, strain, log_p);
  result.slope_lnv_lnp = Slope(samples_, begin, end, log_p, log_v);
  result.detected = result.psi_change_deg < criterion_.psi_tolerance_deg &&
                    result.lnp_half_difference < criterion_.lnp_tolerance;
  return result;
}

}  // namespace granasym::dem
