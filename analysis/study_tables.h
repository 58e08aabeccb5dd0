// What follows a study's runs (`study run`, `study merge`, the Python
// module's run_programme): the state table, then the analyses that belong
// with it.
#pragma once

#include <string>

namespace granasym::analysis {

// Writes DIR's state table (study/state_table.h), the paper's claims judged
// from it (analysis/findings.h) and, for a study with rate cases, the rate
// study's files (analysis/rate_cases.h); returns their summary lines.
std::string WriteStudyTables(const std::string& directory);

}  // namespace granasym::analysis
