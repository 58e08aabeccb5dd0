// The five statuses of a calibration, their order, exit statuses and file.
#include "calibration/fit_status.h"

#include "common/config.h"
#include "common/text_file.h"

namespace granasym::calibration {

int Severity(FitStatus status) {
  switch (status) {
    case FitStatus::kConverged:
      return 0;
    case FitStatus::kAtBound:
      return 1;
    case FitStatus::kConvergedInadmissible:
      return 2;
    case FitStatus::kNoConvergence:
      return 3;
    case FitStatus::kFailed:
      return 4;
  }
  return 4;
}

FitStatus Worst(FitStatus a, FitStatus b) { return Severity(b) > Severity(a) ? b : a; }

int ExitStatus(FitStatus status) {
  switch (status) {
    case FitStatus::kConverged:
      return 0;
    case FitStatus::kFailed:
      return 3;
    case FitStatus::kAtBound:
      return 5;
    case FitStatus::kConvergedInadmissible:
      return 6;
    case FitStatus::kNoConvergence:
      return 7;
  }
  return 3;
}

std::string FitStatusToml(const FitOutcome& outcome) {
  std::string reason = outcome.reason;
  for (char& c : reason) c = (c == '\n' || c == '\r') ? ' ' : c;
  return "status = " + TomlQuoted(ToString(outcome.status)) + "\nreason = " + TomlQuoted(reason) +
         "\n";
}

FitOutcome ReadFitStatusToml(const std::string& path) {
  const ConfigTable table = ConfigTable::ParseFile(path);
  FitOutcome outcome;
  outcome.status = table.GetEnum<FitStatus>("status");
  outcome.reason = table.GetString("reason");
  table.CheckNoUnknownKeys();
  return outcome;
}

}  // namespace granasym::calibration
