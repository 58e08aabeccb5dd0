#include "analysis/study_tables.h"

#include <optional>

#include "analysis/findings.h"
#include "analysis/rate_cases.h"
#include "study/state_table.h"

namespace granasym::analysis {

std::string WriteStudyTables(const std::string& directory) {
  std::string text = study::WriteStateTable(directory).Text();
  // The rate study's files first: the findings read its quasi-static set.
  const std::optional<RateStudy> rate = WriteRateStudy(directory, study::ReadStateTable(directory));
  text += FindingsLine(WriteStudyFindings(directory));
  if (rate) text += rate->Text();
  return text;
}

}  // namespace granasym::analysis
