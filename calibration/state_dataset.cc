// Kinds and validation of asymptotic-state datasets.
#include "calibration/state_dataset.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/state_measures.h"

namespace granasym::calibration {

StateKind KindFromStretching(double psi_epsilon, double tolerance) {
  if (std::abs(psi_epsilon) <= tolerance) return StateKind::kNcl;
  if (std::abs(psi_epsilon - 0.5 * kPi) <= tolerance) return StateKind::kCsl;
  if (std::abs(std::abs(psi_epsilon) - kPi) <= tolerance) return StateKind::kUnloading;
  if (psi_epsilon > 0 && psi_epsilon < 0.5 * kPi) return StateKind::kCompression;
  return StateKind::kExtension;
}

bool AsymptoticStatePoint::HasFlag(const std::string& flag) const {
  for (size_t start = 0; start <= flags.size();) {
    const size_t end = std::min(flags.find(';', start), flags.size());
    if (flags.compare(start, end - start, flag) == 0 && end - start == flag.size()) return true;
    start = end + 1;
  }
  return false;
}

size_t StateDataset::Count(StateKind kind) const {
  size_t n = 0;
  for (const AsymptoticStatePoint& point : points) n += point.kind == kind ? 1 : 0;
  return n;
}

void StateDataset::Validate() const {
  if (points.empty()) {
    throw InputError(fmt::format("dataset '{}' ({}): no states", name, origin));
  }
  const double lowest = -std::atan(1.0 / std::sqrt(2.0));
  const double highest = std::atan(std::sqrt(2.0));
  for (const AsymptoticStatePoint& point : points) {
    auto fail = [&](const char* field, double value, const char* valid) {
      throw InputError(fmt::format("dataset '{}': {}: {} = {:.6g} is invalid ({})", name,
                                   point.source, field, value, valid));
    };
    if (!(std::isfinite(point.mean_stress) && point.mean_stress > 0)) {
      fail("p_kpa", point.mean_stress, "a finite mean stress > 0 kPa");
    }
    if (!(std::isfinite(point.void_ratio) && point.void_ratio > 0)) {
      fail("e", point.void_ratio, "a finite void ratio > 0");
    }
    if (!(std::isfinite(point.psi_sigma) && point.psi_sigma > lowest &&
          point.psi_sigma < highest)) {
      fail("psi_sigma_deg", point.psi_sigma / kDegree,
           "finite, in (-35.26, 54.74) deg: between sigma_a = 0 and sigma_r = 0");
    }
    if (point.kind != StateKind::kAsbs &&
        !(std::isfinite(point.psi_epsilon) && std::abs(point.psi_epsilon) <= kPi + 1e-12)) {
      fail("psi_epsilon_deg", point.psi_epsilon / kDegree, "finite, in [-180, 180] deg");
    }
    if (!(std::isfinite(point.weight) && point.weight >= 0)) {
      fail("weight", point.weight, ">= 0 (0: drawn, not fitted)");
    }
    if (!(std::isfinite(point.psi_sigma_uncertainty) && point.psi_sigma_uncertainty > 0)) {
      fail("psi_sigma_uncertainty_deg", point.psi_sigma_uncertainty / kDegree, "> 0");
    }
    if (!(std::isfinite(point.ln_volume_uncertainty) && point.ln_volume_uncertainty > 0)) {
      fail("ln_1_plus_e_uncertainty", point.ln_volume_uncertainty, "> 0");
    }
  }
}

bool ValidReaderSettings(double kind_tolerance_deg, double psi_sigma_uncertainty_deg,
                         double ln_volume_uncertainty, double weight, std::string* why) {
  if (!(kind_tolerance_deg >= 0 && kind_tolerance_deg < 45)) {
    *why = fmt::format("kind_tolerance_deg = {} must be in [0, 45)", kind_tolerance_deg);
    return false;
  }
  if (!(psi_sigma_uncertainty_deg > 0)) {
    *why = fmt::format("psi_sigma_uncertainty_deg = {} must be > 0", psi_sigma_uncertainty_deg);
    return false;
  }
  if (!(ln_volume_uncertainty > 0)) {
    *why = fmt::format("ln_1_plus_e_uncertainty = {} must be > 0", ln_volume_uncertainty);
    return false;
  }
  if (!(weight >= 0)) {
    *why = fmt::format("weight = {} must be >= 0 (0: drawn, not fitted)", weight);
    return false;
  }
  return true;
}

}  // namespace granasym::calibration
