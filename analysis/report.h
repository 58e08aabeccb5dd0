// The report of a study folder: DIR/index.html, one self-contained page
// (one file: a small embedded stylesheet, the figures inside it as inline
// SVG or PNG data URIs, no scripts, no network; only the PDFs, data and
// cases are linked, by relative paths), and DIR/report.md with the same
// content for a terminal or a forge (its images link the PNGs). It answers
// first: the paper's claims judged (findings.csv), then the fitted
// parameters with their intervals and each model's outcome (fitted; fitted,
// inadmissible; fitted, at a bound; failed), then every figure with the
// numbers behind it (hover over a state of an SVG to see what it is), then
// the tables: the asymptotic states folded by kind, the replicate summary,
// the NCL fits, the path convergence, the cases' run times and keys, the
// scale and the program version.
//
// What it reads (an absent file is stated in its place, never an error):
//
//   DIR/study.toml                           required: what makes DIR a study folder
//   DIR/findings.csv                         analysis/findings.h
//   DIR/calibration/<model>/parameters.csv   parameter,value,std_error,ci95_low,ci95_high,status
//   DIR/calibration/<model>/fit_status.toml  status (converged, converged_inadmissible,
//                                            at_bound, no_convergence, failed) and reason;
//                                            without it the outcome is derived from
//                                            summary.txt, warnings.txt and parameters.csv
//   DIR/calibration/<model>/warnings.txt     one warning per line ("code: message")
//   DIR/calibration/<model>/summary.txt      free text (a collapsible block)
//   DIR/calibration/<model>/model.toml       linked
//   DIR/figures/index.tsv                    stem, figure, title, caption (tab-separated)
//   DIR/figures/<stem>.svg                   inline, made script-free (report_images.h)
//   DIR/figures/<stem>.png                   a data URI where there is no SVG
//   DIR/figures/<stem>.*                     linked (PNG, PDF, SVG, data)
//   DIR/asymptotic_states.csv, asymptotic_states_summary.csv, ncl_fit.csv,
//   DIR/path_convergence.csv                 study/state_table.h (read by column name)
//   DIR/rate_*.csv                           analysis/rate_files.h (a study with rate cases)
//   DIR/cases/r<K>/<case>/case.toml, done.toml, running.toml
//   DIR/models/<name>/done.toml
//
// Malformed files (a row with the wrong number of fields, a missing column a
// section needs, a figure stem that is not a plain file name or is listed
// twice, an SVG that is not one, a fit_status.toml without a valid status
// and a reason) are an InputError naming the file and the line or key.
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
