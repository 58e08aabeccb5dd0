// The sections of the report (analysis/report.h), each from what the study
// folder holds (report_folder.h), in the order WriteReport puts them; an
// absent input is a note in its place and its name in `absent`.
// Internal to the analysis library.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/report_document.h"
#include "analysis/report_folder.h"

namespace granasym::analysis::report {

// The paper's claims judged from the study (DIR/findings.csv,
// analysis/findings.h): counts by verdict, then one row per claim with the
// numbers that decide it and, folded, the rule.
Section FindingsSection(const StudyFolder& study, std::vector<std::string>* absent);

// The study at a glance: programme, scale, cases and states by status,
// figures and models, and the inputs that are absent.
Section OverviewSection(const StudyFolder& study, const std::vector<CaseRow>& cases, int figures,
                        int figures_missing, int models);

// "Figures", then one section per row of figures/index.tsv: the image (or
// a note), the caption, the files and the state table's rows behind it;
// counts the figures and those without their PNG.
std::vector<Section> FigureSections(const StudyFolder& study, int* figures, int* missing,
                                    std::vector<std::string>* absent);

// What became of a model's calibration: DIR/calibration/<model>/fit_status.toml
// (status and reason, written by the calibration), or, for a folder written
// before that file existed, derived from what is there: the first fit's
// termination in summary.txt, the admissibility warnings in warnings.txt
// and the parameters at a bound in parameters.csv (in that precedence).
struct FitOutcome {
  // converged, converged_inadmissible, at_bound, no_convergence or failed.
  std::string status;
  std::string reason;    // one sentence
  bool derived = false;  // no fit_status.toml: derived by the report (the reason says so)
  // "fitted", "fitted, inadmissible", "fitted, at a bound" or "failed": never
  // a bare "fitted" for a model that is inadmissible or did not converge.
  std::string Label() const;
  std::string Css() const;  // the stylesheet's class of the label
};
// nullopt when the model has no parameters.csv (not calibrated); InputError
// naming the file for a fit_status.toml without a valid status or a reason.
std::optional<FitOutcome> ReadFitOutcome(const StudyFolder& study, const std::string& model);
// The same for a calibration's folder relative to the study (e.g.
// calibration/quasi_static/<model>: analysis/calibration_selections.h).
std::optional<FitOutcome> ReadFitOutcomeIn(const StudyFolder& study, const std::string& folder);

// "Fitted parameters": each model's outcome in one table, then one section
// per model (kReportModels) and selection (the default's first; where a
// model has both, the default's section opens with both selections'
// parameters side by side) with its parameters, intervals and statuses
// (a parameter's "fitted" is green only when its model converged), its
// warnings and summary folded, and model.toml; counts the calibrated models.
std::vector<Section> CalibrationSections(const StudyFolder& study, int* calibrated,
                                         std::vector<std::string>* absent);

// The table of asymptotic states with counts by kind and status.
Section StatesSection(const StudyFolder& study);

// The replicate means with their 95 % intervals.
Section ReplicateSection(const StudyFolder& study);

// The rate study (analysis/rate_study.h): its answers and tables; only for
// a study with rate cases.
std::optional<Section> RateSection(const StudyFolder& study, std::vector<std::string>* absent);

// A CSV of the state table shown whole under `description`.
Section CsvSection(const std::optional<CsvTextTable>& table, const std::string& id,
                   const std::string& title, const std::string& file, Inline description,
                   const std::string& directory);

// Each case's run time, steps and key, with totals; the model runs.
Section RunTimesSection(const StudyFolder& study, const std::vector<CaseRow>& cases);

// study.toml, key by key.
Section ProvenanceSection(const StudyFolder& study);

}  // namespace granasym::analysis::report
