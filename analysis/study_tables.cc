#include "analysis/study_tables.h"

#include <optional>

#include "analysis/findings.h"
#include "analysis/rate_cases.h"
#include "study/state_table.h"

namespace granasym::analysis {

std::string WriteStudyTables(const std::string& directory) {
  std::string text = study::WriteStateTable(directory).Text();
  text += FindingsLine(WriteStudyFindings(directory));
  if (const std::optional<RateStudy> rate =
          WriteRateStudy(directory, study::ReadStateTable(directory))) {
    text += rate->Text();
  }
  return text;
}

}  // namespace granasym::analysis
