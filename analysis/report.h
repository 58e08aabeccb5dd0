// The report of a study folder: DIR/index.html, one self-contained page (a
// small embedded stylesheet, no scripts, no network; images are the study's
// own files, referenced by relative paths), and DIR/report.md with the same
// content for a terminal or a forge. It shows every figure with the numbers
// behind it, the calibrated parameters with their intervals and warnings,
// the asymptotic states with their detection status and flags, the
// replicate summary, the NCL fits, the path convergence, the cases' run
// times and keys, the scale and the program version.
//
// What it reads (an absent file is stated in its place, never an error):
//
//   DIR/study.toml                           required: what makes DIR a study folder
//   DIR/figures/index.tsv                    stem, figure, title, caption (tab-separated)
//   DIR/figures/<stem>.png, .pdf             shown, linked; other <stem>.* linked as data
//   DIR/calibration/<model>/parameters.csv   parameter,value,std_error,ci95_low,ci95_high,status
//   DIR/calibration/<model>/warnings.txt     one warning per line
//   DIR/calibration/<model>/summary.txt      free text (a collapsible block)
//   DIR/calibration/<model>/model.toml       linked
//   DIR/asymptotic_states.csv, asymptotic_states_summary.csv, ncl_fit.csv,
//   DIR/path_convergence.csv                 study/state_table.h (read by column name)
//   DIR/cases/r<K>/<case>/case.toml, done.toml, running.toml
//   DIR/models/<name>/done.toml
//
// Malformed files (a row with the wrong number of fields, a missing column a
// section needs, a figure stem that is not a plain file name) are an
// InputError naming the file and the line.
#pragma once

#include <string>
#include <vector>

namespace granasym::analysis {

// The models a study calibrates, in the order the report shows them.
extern const char* const kReportModels[3];

struct ReportSummary {
  std::string html_path, markdown_path;
  int figures = 0;          // rows of figures/index.tsv
  int figures_missing = 0;  // of them without their PNG
  int models_calibrated = 0;
  int states = 0;  // rows of asymptotic_states.csv
  int cases = 0;
  std::vector<std::string> absent;  // inputs the report says are missing
  std::string Text() const;         // a few lines: where the report is, what is missing
};

// Writes DIR/index.html and DIR/report.md (each atomically).
ReportSummary WriteReport(const std::string& directory);

// `text` with &, <, >, " and ' replaced by entities (for text and attribute values).
std::string HtmlEscaped(const std::string& text);

}  // namespace granasym::analysis
