#include "analysis/rate_options.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/text_file.h"

namespace granasym::analysis {

bool RateStudyOptions::IsValid(std::string* why) const {
  if (statuses.empty()) {
    *why = "statuses: give at least one detector status";
    return false;
  }
  if (fit_rates < 2) {
    *why = fmt::format("fit_rates = {}: a line needs at least 2 rates", fit_rates);
    return false;
  }
  if (!(reference_p_kpa > 0) || !std::isfinite(reference_p_kpa)) {
    *why = "reference_p_kpa: must be a positive mean stress (kPa)";
    return false;
  }
  return true;
}

bool HasFlag(const std::string& flags, const std::string& flag) {
  std::stringstream in(flags);
  std::string item;
  while (std::getline(in, item, ';')) {
    if (Trimmed(item) == flag) return true;
  }
  return false;
}

bool PassesFilters(TableStatus status, const std::string& flags,
                   const std::vector<TableStatus>& statuses, const RateStudyOptions& options) {
  if (std::find(statuses.begin(), statuses.end(), status) == statuses.end()) return false;
  for (const std::string& flag : options.excluded_flags) {
    if (HasFlag(flags, flag)) return false;
  }
  return true;
}

bool IsLiquefied(TableStatus status, const std::string& flags) {
  return status == TableStatus::kGas || HasFlag(flags, "gas");
}

}  // namespace granasym::analysis
