// The report's fitted parameters (analysis/report_sections.h): each model's
// outcome with an honest label, its parameters with their intervals and
// profile-likelihood flags, the profile and Pareto figures where drawn, its
// warnings and summary.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <tuple>

#include "analysis/calibration_selections.h"
#include "analysis/quasi_static_selection.h"
#include "analysis/report.h"
#include "analysis/report_images.h"
#include "analysis/report_sections.h"
#include "analysis/report_tables.h"
#include "common/config.h"
#include "common/text_file.h"

namespace granasym::analysis::report {
namespace {

// The statuses of fit_status.toml (the calibration's overall outcome), in
// order of precedence from the worst.
const std::vector<std::string>& FitStatuses() {
  static const std::vector<std::string> statuses = {
      "failed", "no_convergence", "converged_inadmissible", "at_bound", "converged"};
  return statuses;
}

// The admissibility checks of the calibration (CheckAdmissibility,
// calibration/calibration_report.h) whose warning says that the fitted model
// is inadmissible. structural_misfit says that it fits some kind of state
// badly, not that it is inadmissible.
bool IsInadmissibility(const std::string& code) {
  return code == "kappa_not_below_lambda" || code == "ocr_below_one" || code == "asbs_outside" ||
         code == "csl_ocr_mismatch";
}

// The code of a line of warnings.txt ("asbs_outside: ..."), or "".
std::string WarningCode(const std::string& line) {
  const size_t colon = line.find(':');
  if (colon == std::string::npos || colon == 0) return "";
  const std::string code = line.substr(0, colon);
  const bool word = std::all_of(code.begin(), code.end(), [](char c) {
    return std::islower(static_cast<unsigned char>(c)) ||
           std::isdigit(static_cast<unsigned char>(c)) || c == '_';
  });
  return word ? code : "";
}

std::vector<std::string> WarningLines(const StudyFolder& study, const std::string& file) {
  std::vector<std::string> lines;
  if (!study.Exists(file)) return lines;
  for (const std::string& line : TextLines(ReadTextFile(study.Path(file)))) {
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

// The first fit's termination in summary.txt ("ceres: converged after 34
// iterations, ..."): the fitter and converged, no_convergence or failure;
// false when the summary has no such line.
bool FitTerminationOf(const std::string& summary, std::string* fitter, std::string* termination) {
  for (const std::string& line : TextLines(summary)) {
    const size_t colon = line.find(": ");
    if (colon == std::string::npos || colon == 0) continue;
    const std::string name = line.substr(0, colon);
    if (!std::all_of(name.begin(), name.end(), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
        })) {
      continue;
    }
    for (const char* word : {"converged", "no_convergence", "failure"}) {
      if (line.compare(colon + 2, std::string(word).size() + 7, std::string(word) + " after ") ==
          0) {
        *fitter = name;
        *termination = word;
        return true;
      }
    }
  }
  return false;
}

std::string Joined(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& word : words) text += (text.empty() ? "" : ", ") + word;
  return text;
}

// The outcome of a calibration written before fit_status.toml existed.
FitOutcome DerivedOutcome(const StudyFolder& study, const std::string& folder,
                          const CsvTextTable& parameters) {
  FitOutcome outcome;
  outcome.derived = true;
  std::string fitter, termination;
  const bool known =
      study.Exists(folder + "/summary.txt") &&
      FitTerminationOf(ReadTextFile(study.Path(folder + "/summary.txt")), &fitter, &termination);
  std::vector<std::string> inadmissible;
  for (const std::string& line : WarningLines(study, folder + "/warnings.txt")) {
    const std::string code = WarningCode(line);
    if (IsInadmissibility(code) &&
        std::find(inadmissible.begin(), inadmissible.end(), code) == inadmissible.end()) {
      inadmissible.push_back(code);
    }
  }
  std::vector<std::string> at_bound;
  const size_t name = parameters.Column("parameter"), status = parameters.Column("status");
  for (const auto& row : parameters.rows) {
    if (row[status] == "at_bound") at_bound.push_back(row[name]);
  }
  const std::string fit = known ? fitter + " " + (termination == "failure" ? "failed" : termination)
                                : "the fitter's termination is not in summary.txt";
  if (known && termination == "failure") {
    outcome.status = "failed";
    outcome.reason = fit + ": its values are only where it stopped";
  } else if (known && termination == "no_convergence") {
    outcome.status = "no_convergence";
    outcome.reason = fitter + " stopped before a convergence criterion was met";
  } else if (!inadmissible.empty()) {
    outcome.status = "converged_inadmissible";
    outcome.reason = fit + ", but the fitted model is inadmissible (" + Joined(inadmissible) +
                     " in warnings.txt)";
  } else if (!at_bound.empty()) {
    outcome.status = "at_bound";
    outcome.reason = fit + ", with " + Joined(at_bound) + " at a bound of the fit";
  } else {
    outcome.status = "converged";
    outcome.reason = fit + ", no parameter at a bound and no admissibility warning";
  }
  outcome.reason =
      "Derived by the report (no fit_status.toml: calibrated by an earlier version): " +
      outcome.reason + ".";
  return outcome;
}

}  // namespace

std::string FitOutcome::Label() const {
  if (status == "converged") return "fitted";
  if (status == "converged_inadmissible") return "fitted, inadmissible";
  if (status == "at_bound") return "fitted, at a bound";
  return "failed";
}

std::string FitOutcome::Css() const {
  if (status == "converged") return "status-fitted";
  if (status == "at_bound") return "status-at_bound";
  return status == "converged_inadmissible" ? "status-inadmissible" : "status-failed";
}

std::optional<FitOutcome> ReadFitOutcome(const StudyFolder& study, const std::string& model) {
  return ReadFitOutcomeIn(study, "calibration/" + model);
}

std::optional<FitOutcome> ReadFitOutcomeIn(const StudyFolder& study, const std::string& folder) {
  if (!study.Exists(folder + "/parameters.csv")) return std::nullopt;
  const std::string file = folder + "/fit_status.toml";
  if (!study.Exists(file)) {
    return DerivedOutcome(study, folder,
                          CsvTextTable::ReadFile(study.Path(folder + "/parameters.csv")));
  }
  const ConfigTable toml = ConfigTable::ParseFile(study.Path(file));
  FitOutcome outcome;
  // Required (GetString fails naming the file and key), then one of the five.
  outcome.status = toml.GetChoice("status", FitStatuses(), toml.GetString("status"));
  outcome.reason = toml.GetString("reason");
  return outcome;
}

namespace {

// One calibrated model: its outcome, parameters with intervals and statuses,
// the warnings and the summary (folded) and model.toml.
Section ModelSection(const StudyFolder& study, const std::string& model, const std::string& folder,
                     const std::string& id, const std::string& title,
                     const std::optional<FitOutcome>& outcome, std::vector<std::string>* absent) {
  Section section{id, title, 3, {}};
  // The figures' labels: the model, and the selection where not the default.
  const std::string label = model + title.substr(title.find(model) + model.size());
  if (!study.Exists(folder)) {
    absent->push_back(folder + "/");
    section.blocks.push_back(Note(Plain("Not calibrated: ") + Code(folder + "/") +
                                  Plain(" is absent (run ") +
                                  DirectoryHint("calibrate", study.directory) + Plain(").")));
    return section;
  }
  const std::string parameters = folder + "/parameters.csv";
  if (outcome) {
    Inline line = Plain("Outcome: " + outcome->Label() + ". " + outcome->reason);
    if (!outcome->derived) {
      const std::string file = folder + "/fit_status.toml";
      line = line + Plain(" (from ") + Link(file, UrlPath(file), true) + Plain(")");
    }
    section.blocks.push_back(Paragraph(std::move(line)));
    const CsvTextTable table = CsvTextTable::ReadFile(study.Path(parameters));
    const size_t name = table.Column("parameter"), value = table.Column("value"),
                 error = table.Column("std_error"), low = table.Column("ci95_low"),
                 high = table.Column("ci95_high"), status = table.Column("status");
    // The profile likelihood's columns (calibrations since issue 36 §3).
    const bool profiled =
        std::find(table.columns.begin(), table.columns.end(), "profile") != table.columns.end();
    const size_t profile = profiled ? table.Column("profile") : 0,
                 profile_low = profiled ? table.Column("profile_low") : 0,
                 profile_high = profiled ? table.Column("profile_high") : 0;
    Block block;
    block.type = Block::Type::kTable;
    block.header = {"parameter", "value", "standard error", "95 % interval", "status"};
    if (profiled) {
      block.header.push_back("profile 95 % interval");
      block.header.push_back("profile");
    }
    std::vector<std::string> flat, determined;
    std::map<std::string, int> by_status;
    for (const auto& row : table.rows) {
      const std::optional<double> v = Number(row[value]), s = Number(row[error]),
                                  lo = Number(row[low]), hi = Number(row[high]);
      const std::string interval =
          lo && hi ? fmt::format("[{:.6g}, {:.6g}]", *lo, *hi) : std::string("—");
      // A parameter is shown as fitted (green) only when the model is.
      const bool plain = row[status] == "fitted" && outcome->status != "converged";
      block.rows.push_back({Cell{Code(row[name]), ""},
                            Cell{Plain(v ? fmt::format("{:.6g}", *v) : row[value]), "num"},
                            Cell{Plain(s                    ? fmt::format("{:.3g}", *s)
                                       : row[error].empty() ? "—"
                                                            : row[error]),
                                 "num"},
                            Cell{Plain(interval), "num"},
                            Cell{Plain(row[status]), plain ? "" : StatusCss(row[status])}});
      if (profiled) {
        const std::optional<double> plo = Number(row[profile_low]), phi = Number(row[profile_high]);
        const std::string& shape = row[profile];
        // A flat side has no end: "[0.04, —]".
        const std::string profile_interval =
            shape.empty() ? std::string("—")
                          : fmt::format("[{}, {}]", plo ? fmt::format("{:.6g}", *plo) : "—",
                                        phi ? fmt::format("{:.6g}", *phi) : "—");
        block.rows.back().push_back(Cell{Plain(profile_interval), "num"});
        block.rows.back().push_back(Cell{Plain(shape.empty()     ? "not profiled"
                                               : shape == "flat" ? "flat: not determined"
                                                                 : shape),
                                         shape == "flat" ? StatusCss("undetermined") : ""});
        if (shape == "flat") flat.push_back(row[name]);
        if (shape == "determined") determined.push_back(row[name]);
      }
      ++by_status[row[status]];
    }
    std::string counts;
    for (const auto& [state, count] : by_status) {
      counts += fmt::format("{}{} {}", counts.empty() ? "" : ", ", count, state);
    }
    section.blocks.push_back(
        Paragraph(Plain(fmt::format("{} parameters ({}), from ", table.rows.size(), counts)) +
                  Link(parameters, UrlPath(parameters), true) + Plain(".")));
    section.blocks.push_back(std::move(block));
    if (profiled) {
      section.blocks.push_back(Paragraph(Plain(fmt::format(
          "Profile likelihoods (each parameter fixed on a grid, the others refitted; summary.txt "
          "says how): {} determined{}; {} flat, not determined{}.",
          determined.size(), determined.empty() ? "" : " (" + Joined(determined) + ")", flat.size(),
          flat.empty() ? "" : " (" + Joined(flat) + ")"))));
    }
  } else {
    absent->push_back(parameters);
    section.blocks.push_back(Note(Code(parameters) + Plain(" is absent: no fitted parameters.")));
  }
  // The profile and Pareto figures of the plot data, where drawn.
  for (const auto& [data, png, label, caption] :
       {std::tuple<std::string, std::string, std::string, std::string>{
            folder + "/plot_data/profiles.csv", folder + "/plot_data/profiles.png",
            "Profile likelihoods: " + label,
            "Each parameter's profile: D = 2 (cost - cost_min)/s^2 with the other parameters "
            "refitted, against its 95 % threshold (dashed); the interval where D stays below it "
            "is shaded, red where the profile stays flat to a bound or over a decade."},
        {folder + "/plot_data/pareto.csv", folder + "/plot_data/pareto.png",
         "Pareto front: " + label,
         "The trade-off between two groups of states over a weighted-sum sweep, with the "
         "ordinary fit (equal weights) and the compromise (the knee: closest to each group's "
         "least cost in normalised costs) marked; summary.txt lists each point's parameters."}}) {
    if (study.Exists(png)) {
      Block image;
      image.type = Block::Type::kFigure;
      image.image = png;
      image.text = Plain(label);
      image.data_uri = DataUri("image/png", ReadTextFile(study.Path(png)));
      section.blocks.push_back(std::move(image));
      section.blocks.push_back(Paragraph(Plain(caption + " From ") + Code(png) + Plain(".")));
    } else if (study.Exists(data)) {
      absent->push_back(png);
      section.blocks.push_back(Note(Code(png) + Plain(" is missing (its data ") + Code(data) +
                                    Plain(" is there): run ") +
                                    DirectoryHint("calibrate", study.directory) +
                                    Plain(" with gnuplot on PATH to draw it.")));
    }
  }
  const std::string warnings = folder + "/warnings.txt";
  if (study.Exists(warnings)) {
    Block list;
    list.type = Block::Type::kList;
    std::map<std::string, int> codes;
    for (const std::string& line : WarningLines(study, warnings)) {
      list.items.push_back(Plain(line));
      const std::string code = WarningCode(line);
      ++codes[code.empty() ? "other" : code];
    }
    if (list.items.empty()) {
      section.blocks.push_back(Paragraph(Plain("No warnings.")));
    } else {
      std::string by_code;
      for (const auto& [code, count] : codes) {
        by_code += fmt::format("{}{} {}", by_code.empty() ? "" : ", ", count, code);
      }
      Block details;
      details.type = Block::Type::kDetails;
      details.text = Plain(fmt::format("{} warning{} ({}), from ", list.items.size(),
                                       list.items.size() == 1 ? "" : "s", by_code)) +
                     Code(warnings);
      details.children.push_back(std::move(list));
      section.blocks.push_back(std::move(details));
    }
  } else {
    absent->push_back(warnings);
    section.blocks.push_back(Note(Code(warnings) + Plain(" is absent.")));
  }
  const std::string summary = folder + "/summary.txt";
  if (study.Exists(summary)) {
    Block details;
    details.type = Block::Type::kDetails;
    details.text = Plain("Summary of the fit (") + Code(summary) + Plain(")");
    details.preformatted = ReadTextFile(study.Path(summary));
    if (details.preformatted.empty()) details.preformatted = "(empty)\n";
    section.blocks.push_back(std::move(details));
  } else {
    absent->push_back(summary);
    section.blocks.push_back(Note(Code(summary) + Plain(" is absent.")));
  }
  const std::string model_toml = folder + "/model.toml";
  if (study.Exists(model_toml)) {
    section.blocks.push_back(Paragraph(Plain("The calibrated model, for ") +
                                       Code("granasym model run") + Plain(": ") +
                                       Link(model_toml, UrlPath(model_toml), true) + Plain(".")));
  } else {
    absent->push_back(model_toml);
    section.blocks.push_back(Note(Code(model_toml) + Plain(" is absent.")));
  }
  return section;
}

// The parameters of both selections of `model` side by side (columns:
// parameter, unit, each selection's value ± interval and its verdict);
// nullopt when the model lacks one of them.
std::optional<Block> SideBySide(const StudyFolder& study, const std::string& model) {
  const SelectionComparison comparison = CompareSelections(study.directory, {model});
  if (comparison.empty()) return std::nullopt;
  Block block;
  block.type = Block::Type::kTable;
  const std::string all = SelectionTitle(study.directory, CalibrationSelection::kAll),
                    quasi = SelectionTitle(study.directory, CalibrationSelection::kQuasiStatic);
  block.header = {"parameter",
                  "unit",
                  all + ": value [95 % interval]",
                  all + ": status",
                  quasi + ": value [95 % interval]",
                  quasi + ": status"};
  for (const SelectionComparisonRow& row : comparison.rows) {
    std::vector<Cell> cells = {Cell{Code(row.parameter), ""}, Cell{Plain(row.units), ""}};
    for (const std::optional<SelectionParameter>& p : {row.all, row.quasi_static}) {
      if (!p) {
        cells.push_back(Cell{Plain("—"), "num"});
        cells.push_back(Cell{Plain("not in this calibration"), ""});
        continue;
      }
      cells.push_back(Cell{Plain(p->ValueText()), "num"});
      const std::string verdict = p->Verdict();
      cells.push_back(Cell{Plain(verdict), verdict.rfind("undetermined", 0) == 0
                                               ? StatusCss("undetermined")
                                               : StatusCss(p->status)});
    }
    block.rows.push_back(std::move(cells));
  }
  return block;
}

}  // namespace

std::vector<Section> CalibrationSections(const StudyFolder& study, int* calibrated,
                                         std::vector<std::string>* absent) {
  std::vector<Section> sections;
  Section top{"fitted-parameters", "Fitted parameters", 2, {}};
  top.blocks.push_back(Paragraph(Plain(
      "The constitutive models fitted to the study's asymptotic states, each with its outcome: "
      "fitted (converged), fitted, inadmissible (converged to a model that fails an "
      "admissibility check), fitted, at a bound (a parameter ended at a bound of the fit) or "
      "failed (no convergence, or the fit failed); then each model's values, standard errors, "
      "95 % intervals and the status of each parameter (fitted, fixed, at_bound, "
      "undetermined), with the fit's warnings and summary.")));
  // Which states the models were fitted to, where `study calibrate
  // --select quasi_static` chose a rate study's quasi-static set.
  if (const std::optional<QuasiStaticSelection> selection =
          ReadQuasiStaticSelection(study.directory)) {
    top.blocks.push_back(Paragraph(
        Plain("The default calibrations (calibration/<model>/) fitted to the quasi-static set only "
              "(") +
        Code("study calibrate --select quasi_static") +
        Plain(fmt::format("): {}, as ", SelectionText(*selection))) +
        Link(kQuasiStaticSelectionFile, UrlPath(kQuasiStaticSelectionFile), true) +
        Plain(" records. Figure rate (e) and, where the study draws it, Fig. 17 (the ASBS "
              "sections) draw those states against the models.")));
  }
  Block table;
  table.type = Block::Type::kTable;
  table.header = {"model", "outcome", "why"};
  std::vector<Section> models;
  *calibrated = 0;
  const std::string directory = study.directory;
  const CalibrationSelection default_selection = DefaultSelection(directory);
  for (const char* model : kReportModels) {
    // The study's default selection's folder, then the other selection's
    // where calibrated (analysis/calibration_selections.h).
    std::vector<SelectionCalibration> selections = CalibratedSelections(directory, model);
    if (selections.empty() || !selections.front().is_default) {
      selections.insert(selections.begin(),
                        {default_selection, "calibration/" + std::string(model), true});
    }
    const bool both = selections.size() > 1;
    bool any = false;  // a calibrated model counts once, whatever its selections
    for (const SelectionCalibration& selection : selections) {
      // The default's section keeps its title (and so its anchor); the
      // other's names its selection.
      const std::string title =
          "Calibration: " + std::string(model) +
          (selection.is_default ? std::string()
                                : " (" + SelectionTitle(directory, selection.selection) + ")");
      const std::string id = Slug(title);
      const std::optional<FitOutcome> outcome = ReadFitOutcomeIn(study, selection.folder);
      if (outcome) any = true;
      const Inline name =
          Link(model + (both ? " (" + SelectionTitle(directory, selection.selection) + ")"
                             : std::string()),
               "#" + id, true);
      if (outcome) {
        table.rows.push_back({Cell{name, ""}, Cell{Plain(outcome->Label()), outcome->Css()},
                              Cell{Plain(outcome->reason), "text"}});
      } else {
        table.rows.push_back({Cell{name, ""}, Cell{Plain("not calibrated"), "status-not_run"},
                              Cell{Plain("no parameters.csv"), "text"}});
      }
      models.push_back(ModelSection(study, model, selection.folder, id, title, outcome, absent));
      // Both selections' parameters side by side, in the default's section.
      if (both && selection.is_default) {
        std::optional<Block> side = SideBySide(study, model);
        if (side) {
          Section& section = models.back();
          section.blocks.insert(section.blocks.begin(), std::move(*side));
          const Inline source =
              study.Exists(kParametersBySelectionFile)
                  ? Link(kParametersBySelectionFile, UrlPath(kParametersBySelectionFile), true)
                  : Plain("from both parameters.csv");
          section.blocks.insert(
              section.blocks.begin(),
              Paragraph(Plain("Both selections, side by side (") + source +
                        Plain("): the value with its 95 % interval (the profile likelihood's where "
                              "it crosses on both sides, else the Jacobian's) and the verdict. " +
                              SelectionAdvice(directory))));
        }
      }
    }
    if (any) ++*calibrated;
  }
  top.blocks.push_back(std::move(table));
  sections.push_back(std::move(top));
  for (Section& section : models) sections.push_back(std::move(section));
  return sections;
}

}  // namespace granasym::analysis::report
