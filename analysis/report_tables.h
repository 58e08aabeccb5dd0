// The report's blocks made of the study's CSV tables (analysis/report.h):
// fields shortened for display, statuses and verdicts styled, estimates as
// "mean ± 95 %". Internal to the analysis library.
#pragma once

#include <optional>
#include <set>
#include <string>

#include "analysis/report_document.h"
#include "common/csv_table.h"

namespace granasym::analysis::report {

// The number a field holds (the whole field), or nullopt (empty, text, out of range).
std::optional<double> Number(const std::string& text);

// A field for display: integers as written, other numbers to 4 significant
// digits (the CSV linked beside every table has them in full), text as it is.
Cell FieldCell(const std::string& field);

// The stylesheet's class of a detector, fit or case status ("status-detected").
std::string StatusCss(const std::string& status);
// "verdict-reproduced" etc.: the class of a finding's verdict cell.
std::string FindingCss(const std::string& verdict);

// The style of a comparison or verdict of the rate study (the stylesheet's
// status colours: green, amber, red).
std::string VerdictCss(const std::string& value);

// A whole CSV as a table, numbers shortened, status and flag columns marked.
Block TableOf(const CsvTextTable& table);

// A table of a CSV whose X_mean and X_ci95 columns become one column
// "X (mean ± 95 %)" (the mean to 4 significant digits, the half-width to
// 2); every other column as it is, `status`-like columns in `marked` styled.
Block MeanIntervalTable(const CsvTextTable& summary, const std::set<std::string>& marked = {});

// A table of more than kUnfoldedRows rows folded into a <details> whose
// summary says "N rows of WHAT" (the page stays short); a smaller one as it is.
constexpr size_t kUnfoldedRows = 12;
Block Folded(Block table, const std::string& what);

// `granasym study COMMAND DIR`, as code.
Inline DirectoryHint(const std::string& command, const std::string& directory);

// The note in place of a file of the state table that is absent.
Block MissingTableNote(const std::string& name, const std::string& directory);

}  // namespace granasym::analysis::report
