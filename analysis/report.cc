#include "analysis/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>

#include "analysis/report_document.h"
#include "analysis/report_folder.h"
#include "analysis/report_sections.h"
#include "common/text_file.h"

namespace granasym::analysis {

const char* const kReportModels[3] = {"hypoplastic_clay", "modified_cam_clay", "hypoplastic_sand"};

namespace report {
namespace {

// The folder as the header names it: absolute, so that "." says which.
std::string FolderName(const std::string& directory) {
  std::string name = std::filesystem::absolute(directory).lexically_normal().string();
  while (name.size() > 1 && name.back() == '/') name.pop_back();
  return name;
}

// The report of `study` as a document, its sections in reading order: the
// answers (findings, fitted parameters), the figures, then the tables;
// counts what it found in `summary` and adds the absent inputs to `study`.
Document ReportDocument(StudyFolder& study, const std::vector<CaseRow>& cases,
                        ReportSummary* summary_out) {
  ReportSummary& summary = *summary_out;
  std::vector<std::string> absent;
  Section findings = FindingsSection(study, &absent);
  std::vector<Section> calibration =
      CalibrationSections(study, &summary.models_calibrated, &absent);
  std::vector<Section> figures =
      FigureSections(study, &summary.figures, &summary.figures_missing, &absent);
  std::optional<Section> rate = RateSection(study, &absent);
  study.absent.insert(study.absent.end(), absent.begin(), absent.end());
  std::sort(study.absent.begin(), study.absent.end());

  Document document;
  const std::string programme = Lookup(study.record, "programme", "study");
  document.title = "Study report: " + programme;
  const std::string replicates = Lookup(study.record, "replicates", "?"),
                    threads = Lookup(study.record, "threads", "?");
  document.subtitle =
      Plain(
          fmt::format("Scale {}: {} replicate{} of {} spheres, {} thread{} per case; computed by ",
                      Lookup(study.record, "scale", "?"), replicates, replicates == "1" ? "" : "s",
                      Lookup(study.record, "count", "?"), threads, threads == "1" ? "" : "s")) +
      Code(Lookup(study.record, "program_version", "?")) + Plain("; folder ") +
      Code(FolderName(study.directory)) + Plain(".");
  document.sections.push_back(std::move(findings));
  for (Section& section : calibration) document.sections.push_back(std::move(section));
  for (Section& section : figures) document.sections.push_back(std::move(section));
  if (rate) document.sections.push_back(std::move(*rate));
  document.sections.push_back(OverviewSection(study, cases, summary.figures,
                                              summary.figures_missing, summary.models_calibrated));
  document.sections.push_back(StatesSection(study));
  document.sections.push_back(ReplicateSection(study));
  document.sections.push_back(CsvSection(
      study.ncl, "ncl-fits", "NCL fits", "ncl_fit.csv",
      Plain("The isotropic NCL ln(1+e) = N − λ* ln(p / 1 kPa) of each replicate and NCL case, "
            "fitted through its stage-end states that are neither a gas nor above 10 % overlap "
            "(invalid fits, below two points, are left empty)."),
      study.directory));
  document.sections.push_back(CsvSection(
      study.convergence, "path-convergence", "Path convergence", "path_convergence.csv",
      Plain("Paths of one ψ_ε from different starting stresses (paper Sec. 4.3): whether and at "
            "which p they join."),
      study.directory));
  document.sections.push_back(RunTimesSection(study, cases));
  document.sections.push_back(ProvenanceSection(study));
  std::map<std::string, int> anchors;
  for (Section& section : document.sections) {
    const std::string slug = Slug(section.title);
    const int seen = anchors[slug]++;
    section.id = seen == 0 ? slug : slug + "-" + std::to_string(seen);
  }
  return document;
}

}  // namespace
}  // namespace report

ReportSummary WriteReport(const std::string& directory) {
  report::StudyFolder study = report::ReadStudyFolder(directory);
  const std::vector<report::CaseRow> cases = report::ReadCases(study.directory);
  ReportSummary summary;
  const report::Document document = report::ReportDocument(study, cases, &summary);
  summary.states = study.states ? static_cast<int>(study.states->rows.size()) : 0;
  summary.cases = static_cast<int>(cases.size());
  summary.absent = study.absent;
  summary.html_path = study.Path("index.html");
  summary.markdown_path = study.Path("report.md");
  WriteTextFileAtomically(summary.html_path, report::RenderHtml(document));
  WriteTextFileAtomically(summary.markdown_path, report::RenderMarkdown(document));
  return summary;
}

std::string ReportSummary::Text() const {
  std::string text = fmt::format(
      "report: {} (and {})\n  {} figures ({} not drawn), {} of 3 models calibrated, "
      "{} asymptotic states, {} cases\n",
      html_path, markdown_path, figures, figures_missing, models_calibrated, states, cases);
  if (!absent.empty()) {
    text += "  absent:";
    for (const std::string& name : absent) text += " " + name;
    text += "\n";
  }
  return text;
}

}  // namespace granasym::analysis
