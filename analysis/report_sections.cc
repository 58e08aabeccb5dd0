#include "analysis/report_sections.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <set>

#include "analysis/findings.h"
#include "analysis/quasi_static_selection.h"
#include "analysis/rate_files.h"
#include "analysis/report_images.h"
#include "analysis/report_tables.h"
#include "common/config.h"
#include "common/error.h"
#include "common/provenance.h"
#include "common/text_file.h"

namespace granasym::analysis::report {
namespace fs = std::filesystem;
using study::CaseRecord;
using study::FigureSet;
namespace {

// A figure stem must be a plain file name inside figures/.
void CheckStem(const std::string& stem, const CsvTextTable& table, int line) {
  const bool plain =
      !stem.empty() && stem[0] != '.' && std::all_of(stem.begin(), stem.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
      });
  if (!plain) {
    throw InputError(table.origin + ": line " + std::to_string(line) + ": stem '" + stem +
                     "' is not a plain file name (letters, digits, '_', '-', '.'; not starting "
                     "with '.')");
  }
}

// "" when `path` is a complete PNG (its signature first, its IEND chunk
// last); else what is wrong with it.
std::string PngDefect(const std::string& path) {
  static const std::string signature = "\x89PNG\r\n\x1a\n";
  static const std::string iend = std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  const std::string bytes = ReadTextFile(path);
  if (bytes.compare(0, signature.size(), signature) != 0) return "no PNG signature";
  if (bytes.size() < signature.size() + iend.size() ||
      bytes.compare(bytes.size() - iend.size(), iend.size(), iend) != 0) {
    return "no IEND chunk at its end (truncated)";
  }
  return "";
}

// Whether a row of the state table is an ensemble row (source column; older
// tables have none).
bool IsEnsembleRow(const CsvTextTable& states, const std::vector<std::string>& row) {
  const int source = states.Find("source");
  return source >= 0 && row[source] == "ensemble";
}

// What an entry of figures/index.tsv names: a figure of the paper ("16"), a
// section ("Sec. 5.2", also written "5.2"), or neither (the rate study's
// figures, which draw its own tables). Numbers are compared whole: figure 5
// is not Sec. 5.2.
struct FigureEntry {
  int figure = 0;       // 1-22, or 0
  std::string section;  // "5.2", or ""
  std::string Name() const {
    return figure > 0 ? fmt::format("figure {}", figure) : "Sec. " + section;
  }
  bool NamedBy(const FigureSet& set) const {
    return figure > 0 ? set.HasFigure(figure) : !section.empty() && set.HasSection(section);
  }
};

FigureEntry ParseFigureEntry(std::string text) {
  FigureEntry entry;
  const std::string prefix = "Sec.";
  if (text.compare(0, prefix.size(), prefix) == 0) {
    text = text.substr(prefix.size());
    text.erase(0, std::min(text.size(), text.find_first_not_of(' ')));
    entry.section = text;
    return entry;
  }
  const bool digits = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) || c == '.';
  });
  if (!digits) return entry;
  if (text.find('.') != std::string::npos) {
    entry.section = text;
  } else if (text.size() <= 3) {
    entry.figure = std::stoi(text);
  }
  return entry;
}

// Figures that draw the states of every case by kind, not those of the
// cases that serve them: figure 21 draws the detected critical states
// (isochoric, csl) and drained triaxial states of all replicates against
// their inertial number. The φ = 0 and Δt/5 variants (the cases serving
// Fig. 20 or Sec. 5.2) are other samples, drawn in their own figures.
struct DrawnByKind {
  int figure;
  std::vector<std::string> kinds;
  const char* what;
};
const DrawnByKind kDrawnByKind[] = {
    {21, {"csl", "triaxial"}, "detected critical (csl) and drained triaxial states"},
};

// The states behind a figure: the rows it draws (kDrawnByKind), else the
// rows of the cases that serve it (the `figures` column names it).
std::optional<Block> StatesOfFigure(const StudyFolder& study, const std::string& text) {
  const FigureEntry entry = ParseFigureEntry(text);
  if (!study.states || (entry.figure == 0 && entry.section.empty())) return std::nullopt;
  const CsvTextTable& states = *study.states;
  const int figures = states.Find("figures");
  if (figures < 0) return std::nullopt;
  const DrawnByKind* by_kind = nullptr;
  for (const DrawnByKind& d : kDrawnByKind) {
    if (d.figure == entry.figure) by_kind = &d;
  }
  const int kind = states.Find("kind"), status = states.Find("status");
  if (by_kind && (kind < 0 || status < 0)) return std::nullopt;
  const std::vector<std::string> wanted = {
      "replicate", "source", "case",          "stage",    "kind", "status", "psi_epsilon_deg",
      "p_kpa",     "e",      "psi_sigma_deg", "q_over_p", "ocr",  "flags"};
  std::vector<int> columns;
  Block table;
  table.type = Block::Type::kTable;
  for (const std::string& name : wanted) {
    const int c = states.Find(name);
    if (c < 0) continue;
    columns.push_back(c);
    table.header.push_back(name);
  }
  const std::string origin = study.Path("asymptotic_states.csv");
  for (const auto& fields : states.rows) {
    const FigureSet serves = FigureSet::Parse(fields[figures], origin, "figures");
    if (by_kind) {
      const bool drawn = std::find(by_kind->kinds.begin(), by_kind->kinds.end(), fields[kind]) !=
                             by_kind->kinds.end() &&
                         fields[status] == "detected" && !IsEnsembleRow(states, fields) &&
                         !serves.HasFigure(20) && !serves.HasSection("5.2");
      if (!drawn) continue;
    } else if (!entry.NamedBy(serves)) {
      continue;
    }
    std::vector<Cell> row;
    for (int c : columns) {
      Cell cell = FieldCell(fields[c]);
      if (states.columns[c] == "status") cell.css = StatusCss(fields[c]);
      if (states.columns[c] == "flags" && !fields[c].empty()) cell.css = "flagged";
      row.push_back(std::move(cell));
    }
    table.rows.push_back(std::move(row));
  }
  const size_t n = table.rows.size();
  Block details;
  details.type = Block::Type::kDetails;
  if (by_kind) {
    details.text =
        Plain(fmt::format("The {} {} that {} draws (all replicates; those of Fig. 20 "
                          "and Sec. 5.2 are other samples)",
                          n, by_kind->what, entry.Name()));
  } else if (n > 0) {
    details.text =
        Plain(fmt::format("{} row{} of the state table behind {} (the rows of the "
                          "cases that serve it)",
                          n, n == 1 ? "" : "s", entry.Name()));
  } else if (entry.figure == 5) {
    return Paragraph(Plain("Figure 5 draws the constitutive models' element tests (") +
                     Code("models/") + Plain("), not states of the DEM."));
  } else {
    return Paragraph(Plain("No row of the state table names " + entry.Name() +
                           ": no case of this study serves it."));
  }
  if (n == 0) return Paragraph(Plain(PlainText(details.text) + ": none."));
  details.children.push_back(std::move(table));
  return details;
}

}  // namespace

namespace {
// "not_reproduced" → "not reproduced".
std::string Words(std::string name) {
  std::replace(name.begin(), name.end(), '_', ' ');
  return name;
}
}  // namespace

Section FindingsSection(const StudyFolder& study, std::vector<std::string>* absent) {
  Section section{"findings", "Findings: the paper's claims in this study", 2, {}};
  if (!study.Exists(kFindingsFile)) {
    absent->push_back(kFindingsFile);
    section.blocks.push_back(Note(Plain(std::string(kFindingsFile) +
                                        " is absent: run `granasym study run` or `study merge` "
                                        "with this version to write it.")));
    return section;
  }
  const CsvTextTable findings = CsvTextTable::ReadFile(study.Path(kFindingsFile));
  const size_t source = findings.Column("source"), claim = findings.Column("claim"),
               verdict = findings.Column("verdict"), numbers = findings.Column("numbers"),
               rule = findings.Column("rule");
  std::map<std::string, int> counts;
  for (const auto& row : findings.rows) ++counts[row[verdict]];
  std::string tally;
  for (const char* v : {"reproduced", "partly", "not_reproduced", "not_tested"}) {
    tally += fmt::format("{}{} {}", tally.empty() ? "" : ", ", counts[v], Words(v));
  }
  section.blocks.push_back(Paragraph(
      Plain(fmt::format("{} claims of the paper, each judged from this study's own states and "
                        "paths by a stated rule: {}. From ",
                        findings.rows.size(), tally)) +
      Link(kFindingsFile, kFindingsFile, true) +
      Plain("; the rules are in the last column, the numbers are this study's.")));
  Block table;
  table.type = Block::Type::kTable;
  table.header = {"paper", "claim", "verdict", "numbers", "rule"};
  for (const auto& row : findings.rows) {
    table.rows.push_back({Cell{Plain(row[source]), ""}, Cell{Plain(row[claim]), "text"},
                          Cell{Plain(Words(row[verdict])), FindingCss(row[verdict])},
                          Cell{Plain(row[numbers]), "text small"},
                          Cell{Plain(row[rule]), "text small"}});
  }
  section.blocks.push_back(std::move(table));
  return section;
}

Section OverviewSection(const StudyFolder& study, const std::vector<CaseRow>& cases, int figures,
                        int figures_missing, int models) {
  Section section{"overview", "Overview", 2, {}};
  Block table;
  table.type = Block::Type::kTable;
  table.header = {"item", "value"};
  auto add = [&table](const std::string& item, Inline value, const std::string& css = "") {
    table.rows.push_back({Cell{Plain(item), ""}, Cell{std::move(value), css}});
  };
  add("programme", Plain(Lookup(study.record, "programme", "?")));
  add("scale", Plain(Lookup(study.record, "scale", "?")));
  add("replicates", Plain(Lookup(study.record, "replicates", "?")));
  add("spheres per sample", Plain(Lookup(study.record, "count", "?")));
  add("threads per case", Plain(Lookup(study.record, "threads", "?")));
  add("computed by", Code(Lookup(study.record, "program_version", "?")));
  add("report written by", Code(ProgramVersion()));
  std::map<std::string, int> by_status;
  for (const CaseRow& c : cases) ++by_status[c.status];
  std::string counts = fmt::format("{} case folders", cases.size());
  for (const auto& [status, count] : by_status) counts += fmt::format(", {} {}", count, status);
  add("cases", Plain(counts));
  if (study.states) {
    const CsvTextTable& states = *study.states;
    std::map<std::string, int> by_state;
    const int status = states.Find("status");
    int ensemble = 0;
    for (const auto& row : states.rows) {
      if (IsEnsembleRow(states, row)) {
        ++ensemble;
        continue;
      }
      ++by_state[status >= 0 ? row[status] : "?"];
    }
    std::string text = fmt::format("{} rows", states.rows.size() - ensemble);
    for (const auto& [name, count] : by_state) text += fmt::format(", {} {}", count, name);
    if (ensemble > 0) text += fmt::format("; and {} ensemble-mean rows", ensemble);
    add("asymptotic states", Plain(text));
  }
  add("figures",
      Plain(fmt::format("{} in figures/index.tsv, {} not drawn (no SVG or valid PNG)", figures,
                        figures_missing)),
      figures_missing > 0 ? "flagged" : "");
  add("models calibrated", Plain(fmt::format("{} of 3", models)));
  section.blocks.push_back(std::move(table));
  if (study.absent.empty()) {
    section.blocks.push_back(Paragraph(Plain("Every input of the report is present.")));
  } else {
    Block list;
    list.type = Block::Type::kList;
    for (const std::string& name : study.absent) list.items.push_back(Code(name));
    section.blocks.push_back(
        Note(Plain("Inputs absent when the report was written (each section says what to run):")));
    section.blocks.push_back(std::move(list));
  }
  return section;
}

std::vector<Section> FigureSections(const StudyFolder& study, int* figures, int* missing,
                                    std::vector<std::string>* absent) {
  std::vector<Section> sections;
  Section top{"figures", "Figures", 2, {}};
  if (!study.Exists("figures/index.tsv")) {
    absent->push_back("figures/index.tsv");
    top.blocks.push_back(Note(Plain("Figures not drawn: run ") +
                              DirectoryHint("figures", study.directory) + Plain(".")));
    sections.push_back(std::move(top));
    return sections;
  }
  const CsvTextTable index =
      CsvTextTable::ReadFile(study.Path("figures/index.tsv"), CsvTextTable::Format::kTsv);
  const size_t stem = index.Column("stem"), figure = index.Column("figure"),
               title = index.Column("title"), caption = index.Column("caption");
  top.blocks.push_back(Paragraph(Plain(fmt::format("{} figures, listed in ", index.rows.size())) +
                                 Link("figures/index.tsv", "figures/index.tsv", true) +
                                 Plain("; each is drawn here from its SVG (hover over a state to "
                                       "see what it is), with links to its PNG, PDF and data.")));
  std::set<std::string> indexed;
  std::vector<Section> figure_sections;
  for (size_t r = 0; r < index.rows.size(); ++r) {
    const std::vector<std::string>& row = index.rows[r];
    CheckStem(row[stem], index, index.line_numbers[r]);
    if (!indexed.insert(row[stem]).second) {
      throw InputError(index.origin + ": line " + std::to_string(index.line_numbers[r]) +
                       ": stem '" + row[stem] +
                       "' is listed twice: each figure has its own stem (its files' name)");
    }
    ++*figures;
    Section section;
    section.level = 3;
    // "Figure 16: ...", "Sec. 5.2: ...".
    section.title =
        (row[figure].rfind("Sec.", 0) == 0 ? "" : "Figure ") + row[figure] + ": " + row[title];
    const std::string& label = section.title;
    const std::string png = "figures/" + row[stem] + ".png", svg = "figures/" + row[stem] + ".svg";
    // A PNG that is not a whole PNG (truncated, or not a PNG) is reported,
    // not shown, and the figure counts as not drawn. (A broken SVG stops
    // the report, naming it: MakeInlineSvg parses it.)
    const std::string png_defect = study.Exists(png) ? PngDefect(study.Path(png)) : "";
    const bool png_valid = study.Exists(png) && png_defect.empty();
    const bool svg_valid = study.Exists(svg);
    if (!png_defect.empty()) {
      ++*missing;
      absent->push_back(png + " (invalid)");
      section.blocks.push_back(
          Note(Code(png) + Plain(" is not a valid PNG (" + png_defect + "): run ") +
               DirectoryHint("figures", study.directory) + Plain(" to draw it again.")));
    } else if (svg_valid || png_valid) {
      // In the page the image itself (the page is one file); in report.md a link.
      Block image;
      image.type = Block::Type::kFigure;
      image.image = png_valid ? png : svg;
      image.text = Plain(label);
      if (svg_valid) {
        image.svg_markup =
            MakeInlineSvg(ReadTextFile(study.Path(svg)), row[stem] + "-", label, study.Path(svg))
                .markup;
      } else {
        image.data_uri = DataUri("image/png", ReadTextFile(study.Path(png)));
      }
      section.blocks.push_back(std::move(image));
    } else {
      ++*missing;
      absent->push_back(png);
      section.blocks.push_back(Note(Code(png) + Plain(" is missing: run ") +
                                    DirectoryHint("figures", study.directory) +
                                    Plain(" to draw it.")));
    }
    if (!row[caption].empty()) section.blocks.push_back(Paragraph(Plain(row[caption])));
    // The figure's files by its stem: the images, then the others (data,
    // the gnuplot call) in name order.
    Inline files;
    std::vector<std::string> others;
    for (const auto& entry : fs::directory_iterator(study.Path("figures"))) {
      const std::string extension = entry.path().extension().string();
      if (entry.path().stem().string() == row[stem] && extension != ".png" && extension != ".pdf" &&
          extension != ".svg") {
        others.push_back("figures/" + entry.path().filename().string());
      }
    }
    std::sort(others.begin(), others.end());
    for (const char* extension : {"png", "pdf", "svg"}) {
      const std::string file = "figures/" + row[stem] + "." + extension;
      if (!study.Exists(file) || (file == png && !png_valid)) continue;
      std::string kind = extension;
      std::transform(kind.begin(), kind.end(), kind.begin(), ::toupper);
      files = files + Plain(files.empty() ? "" : " · ") + Link(kind, UrlPath(file), true);
    }
    if (files.empty()) files = Plain("No image files");
    for (const std::string& file : others) {
      files = files + Plain(" · ") + Link(file.substr(8), UrlPath(file), true);
    }
    section.blocks.push_back(Paragraph(Plain("Files: ") + files + Plain(".")));
    if (std::optional<Block> states = StatesOfFigure(study, row[figure])) {
      section.blocks.push_back(std::move(*states));
    }
    figure_sections.push_back(std::move(section));
  }
  std::vector<std::string> unindexed;
  for (const auto& entry : fs::directory_iterator(study.Path("figures"))) {
    if (entry.path().extension() == ".png" && !indexed.count(entry.path().stem().string())) {
      unindexed.push_back("figures/" + entry.path().filename().string());
    }
  }
  std::sort(unindexed.begin(), unindexed.end());
  if (!unindexed.empty()) {
    Block list;
    list.type = Block::Type::kList;
    for (const std::string& file : unindexed) list.items.push_back(Link(file, UrlPath(file), true));
    top.blocks.push_back(Note(Plain("Images in figures/ that index.tsv does not list:")));
    top.blocks.push_back(std::move(list));
  }
  sections.push_back(std::move(top));
  for (Section& section : figure_sections) sections.push_back(std::move(section));
  return sections;
}

Section StatesSection(const StudyFolder& study) {
  Section section{"asymptotic-states", "Asymptotic states", 2, {}};
  if (!study.states) {
    section.blocks.push_back(MissingTableNote("asymptotic_states.csv", study.directory));
    return section;
  }
  const CsvTextTable& states = *study.states;
  const size_t kind = states.Column("kind"), status = states.Column("status");
  states.Column("case");
  states.Column("stage");
  states.Column("replicate");
  section.blocks.push_back(Paragraph(
      Plain(fmt::format("{} rows: one per detector-carrying stage of every case, and one per case "
                        "without a result; with several replicates, one per stage for the "
                        "replicates' ensemble-mean path through the same detector (source "
                        "ensemble, case mean/<case>, counted apart below); from ",
                        states.rows.size())) +
      Link("asymptotic_states.csv", "asymptotic_states.csv", true) + Plain(" (full precision; ") +
      Code("asymptotic_states.h5") +
      Plain(" with units). OCR and p_e* refer to the NCL named in ncl_reference.")));
  // Counts by kind and status, the ensemble rows apart.
  std::map<std::string, std::map<std::string, int>> counts;
  std::set<std::string> statuses;
  for (const auto& row : states.rows) {
    ++counts[row[kind] + (IsEnsembleRow(states, row) ? " (ensemble mean)" : "")][row[status]];
    statuses.insert(row[status]);
  }
  Block count_table;
  count_table.type = Block::Type::kTable;
  count_table.header = {"kind"};
  for (const std::string& name : statuses) count_table.header.push_back(name);
  for (const auto& [name, by_status] : counts) {
    std::vector<Cell> row = {Cell{Plain(name), ""}};
    for (const std::string& state : statuses) {
      const auto found = by_status.find(state);
      row.push_back(Cell{Plain(found == by_status.end() ? "" : std::to_string(found->second)),
                         found == by_status.end() ? "num" : "num " + StatusCss(state)});
    }
    count_table.rows.push_back(std::move(row));
  }
  section.blocks.push_back(std::move(count_table));
  // The table itself; the detector's long description is given once below.
  const int detector = states.Find("detector");
  const int case_column = static_cast<int>(states.Column("case"));
  std::vector<std::string> detectors;
  Block table = TableOf(states);
  for (size_t r = 0; r < states.rows.size(); ++r) {
    const std::string& case_id = states.rows[r][case_column];
    if (fs::exists(study.Path("cases/" + case_id + "/case.toml"))) {
      table.rows[r][case_column].content =
          Link(case_id, UrlPath("cases/" + case_id + "/scene.toml"));
    }
    if (detector < 0) continue;
    const std::string& text = states.rows[r][detector];
    if (text.empty()) continue;
    auto found = std::find(detectors.begin(), detectors.end(), text);
    if (found == detectors.end()) found = detectors.insert(detectors.end(), text);
    table.rows[r][detector] = Cell{Plain(fmt::format("D{}", found - detectors.begin() + 1)), ""};
  }
  // One folded table per kind, rows unwrapped (the box scrolls sideways).
  const int message = states.Find("message");
  std::map<std::string, Block> groups;
  for (size_t r = 0; r < states.rows.size(); ++r) {
    const std::string group =
        states.rows[r][kind] + (IsEnsembleRow(states, states.rows[r]) ? " (ensemble mean)" : "");
    Block& part = groups[group];
    if (part.header.empty()) {
      part.type = Block::Type::kTable;
      part.header = table.header;
    }
    if (message >= 0) table.rows[r][message].css = "";
    part.rows.push_back(std::move(table.rows[r]));
  }
  section.blocks.push_back(Paragraph(
      Plain("The rows by kind, folded (open one to see its rows; the columns are those of the "
            "CSV). Each case links to the scene it ran; D<n> names the detector below.")));
  for (auto& [group, part] : groups) {
    std::string tally;
    for (const auto& [state, count] : counts[group]) {
      tally += fmt::format("{}{} {}", tally.empty() ? "" : ", ", count, state);
    }
    Block details;
    details.type = Block::Type::kDetails;
    details.text = Plain(fmt::format("{}: {} row{} ({})", group, part.rows.size(),
                                     part.rows.size() == 1 ? "" : "s", tally));
    details.children.push_back(std::move(part));
    section.blocks.push_back(std::move(details));
  }
  if (!detectors.empty()) {
    Block list;
    list.type = Block::Type::kList;
    for (size_t d = 0; d < detectors.size(); ++d) {
      list.items.push_back(Plain(fmt::format("D{}: ", d + 1)) + Plain(detectors[d]));
    }
    Block details;
    details.type = Block::Type::kDetails;
    details.text = Plain(fmt::format("Detectors D1–D{}", detectors.size()));
    details.children.push_back(std::move(list));
    section.blocks.push_back(std::move(details));
  }
  return section;
}

Section ReplicateSection(const StudyFolder& study) {
  Section section{"replicate-summary", "Replicate summary", 2, {}};
  if (!study.summary) {
    section.blocks.push_back(MissingTableNote("asymptotic_states_summary.csv", study.directory));
    return section;
  }
  const CsvTextTable& summary = *study.summary;
  section.blocks.push_back(Paragraph(
      Plain("Per case and stage: the mean over the replicates' detected states ± the half-width "
            "of its 95 % confidence interval (Student t; none below two states), from ") +
      Link("asymptotic_states_summary.csv", "asymptotic_states_summary.csv", true) + Plain(".")));
  section.blocks.push_back(
      Folded(MeanIntervalTable(summary), "the replicate summary (one per case and stage)"));
  return section;
}

// The rate study (analysis/rate_study.h): only for a study with rate cases.
std::optional<Section> RateSection(const StudyFolder& study, std::vector<std::string>* absent) {
  if (!study.Exists(kRateStatesFile)) return std::nullopt;
  Section section{"rate-study", "Rate study", 2, {}};
  section.blocks.push_back(Paragraph(
      Plain("The asymptotic states of the cases whose ") + Code("figures") +
      Plain(" key names the rate study: proportional paths at fixed inertial numbers I* (the "
            "stretching rate set from the measured p, ‖D‖ = I* √(p/2ρ_s)/d) and at constant "
            "‖D‖, from NC states at several p_0, by Young's modulus E. Usable states are those "
            "the tables' comments name; every number below has its 95 % interval (Student t). "
            "Figures rate (a)–(e) above draw them.")));
  if (const std::optional<RateStudy> rate = ReadRateStudy(study.directory)) {
    const std::vector<std::string> answers = rate->Answers();
    if (!answers.empty())
      section.blocks.push_back(Paragraph(Plain("The answers, from the tables below:")));
    for (const std::string& answer : answers) section.blocks.push_back(Paragraph(Plain(answer)));
  }
  if (const std::optional<QuasiStaticSelection> selection =
          ReadQuasiStaticSelection(study.directory)) {
    section.blocks.push_back(Paragraph(
        Plain(fmt::format(
            "The calibrated models (Parameters, figure rate (e) and, where drawn, Fig. 17) were "
            "fitted to the quasi-static states only: {}, from ",
            SelectionText(*selection))) +
        Link(kQuasiStaticSelectionFile, UrlPath(kQuasiStaticSelectionFile), true) + Plain(".")));
  }
  struct Table {
    const char* file;
    const char* title;
    const char* description;
  };
  const Table tables[] = {
      {kRateIndependenceFile, "Rate independence",
       "Per (E, ψ_ε, p_0): the two smallest I* compared in ln(1+e), ψ_σ and the position of the "
       "CSL (ln(1+e) of the ψ_ε = 90° line at the reference p); rate_independent when all "
       "three agree within the 95 % interval of their difference, rate_dependent when one "
       "differs, undetermined when an interval is missing (the reason says which)."},
      {kRateQuasiStaticFile, "Quasi-static limits",
       "Per (E, ψ_ε, p_0) and quantity: the limit a of y = a + b·I(d_max) as I → 0, fitted "
       "through the states of the smallest I*; for ψ_ε = 90° the q_over_p rows are the "
       "quasi-static critical-state ratio M_0."},
      {kRateLinesFile, "Lines at each rate",
       "Per (E, ψ_ε, rate): ln(1+e) = N − λ ln(p / 1 kPa) through the states of every start "
       "(the CSL at 90°, the NEL beyond; at ψ_ε = 0° the NCL as the mean of the paths' own "
       "lines, whose states all lie at the stress cap) and its position at the reference p."},
      {kRateStiffnessFile, "Stiffness scaling",
       "Per other Young's modulus, ψ_ε, p_0 and rate: ψ_σ and the position of the CSL of that "
       "rate against those at the main modulus, with the stiffness numbers κ of both; "
       "stiffness_independent when both agree within the 95 % interval of the difference. "
       "Stiffness scaling shortens a run (steps per unit strain ∝ √(E/p)/I) where this holds."},
      {kRateDrainedCriticalFile, "Quasi-static critical state from drained tests",
       "Per E: drained triaxial compression (constant σ_r = p_0, constant axial rate) from the "
       "NC states, extrapolated as I → 0 at each σ_r and then combined: the critical-state "
       "ratio M (mean over σ_r), φ_c = asin(3M/(6+M)), the slope of M against ln p (zero "
       "within its interval: M does not depend on p) and the CSL through the limits. These "
       "are the study's quasi-static M, φ_c and CSL where the isochoric paths liquefy."},
      {kRateDrainedLimitFile, "Drained critical states as I → 0, per σ_r",
       "Per (E, σ_r): the limits of M, ln(1+e) and ln p of y = a + b·I(d_max) through the "
       "states of every axial rate, and the two slowest rates compared in M and ln(1+e)."},
      {kRateDrainedFile, "Drained critical states per σ_r and rate",
       "Per (E, σ_r, axial rate): the asymptotic state's means over the replicates (q_over_p "
       "is M)."},
      {kRateExtensionLimitFile, "How far the extension states go",
       "Per (E, rate, p_0): the sweep of ψ_ε from 90° upwards ends at the limit d, where the "
       "asymptotic σ_r/p is zero within its 95 % interval (ψ_ε(d) is the root of the "
       "least-squares line of σ_r/p against ψ_ε through the last steps, with its interval), or "
       "at the first ψ_ε at which most replicates liquefied (a gas: mechanical coordination "
       "below 3 or p below 0.5 kPa), or it reaches neither."},
      {kRateExtensionFile, "Extension sweep, step by step",
       "Per (E, rate, p_0, ψ_ε ≥ 90°): σ_r/p and ψ_σ of the asymptotic states, the replicates "
       "that liquefied, and the step's status."},
      {kRateSummaryFile, "Means per start and rate",
       "Per (E, ψ_ε, p_0, rate): the asymptotic state's means over the replicates."},
  };
  for (const Table& t : tables) {
    section.blocks.push_back(
        Paragraph(Plain(std::string(t.title) + ". " + t.description + " From ") +
                  Link(t.file, UrlPath(t.file), true) + Plain(".")));
    if (!study.Exists(t.file)) {
      absent->push_back(t.file);
      section.blocks.push_back(
          Note(Code(t.file) + Plain(" is absent: run ") +
               Code("granasym study merge " + study.directory + " --out " + study.directory) +
               Plain(".")));
      continue;
    }
    const CsvTextTable table = CsvTextTable::ReadFile(study.Path(t.file));
    if (table.rows.empty()) {
      for (const std::string& comment : table.comments) {
        section.blocks.push_back(Paragraph(Plain(comment)));
      }
      section.blocks.push_back(Paragraph(Plain("No rows.")));
      continue;
    }
    // The answers are above: each table folded, with the notes of its fit.
    Block details;
    details.type = Block::Type::kDetails;
    details.text =
        Plain(fmt::format("{} row{} of ", table.rows.size(), table.rows.size() == 1 ? "" : "s")) +
        Code(t.file) + Plain(table.comments.empty() ? "" : ", with the notes of its fit");
    for (const std::string& comment : table.comments) {
      details.children.push_back(Paragraph(Plain(comment)));
    }
    details.children.push_back(
        MeanIntervalTable(table, {"verdict", "ln_1_plus_e_agreement", "psi_sigma_deg_agreement",
                                  "csl_position_agreement", "m_agreement", "result", "status"}));
    section.blocks.push_back(std::move(details));
  }
  return section;
}

Section CsvSection(const std::optional<CsvTextTable>& table, const std::string& id,
                   const std::string& title, const std::string& file, Inline description,
                   const std::string& directory) {
  Section section{id, title, 2, {}};
  if (!table) {
    section.blocks.push_back(MissingTableNote(file, directory));
    return section;
  }
  section.blocks.push_back(Paragraph(std::move(description) + Plain(" From ") +
                                     Link(file, UrlPath(file), true) + Plain(".")));
  for (const std::string& comment : table->comments) {
    section.blocks.push_back(Paragraph(Plain(comment)));
  }
  if (table->rows.empty()) {
    section.blocks.push_back(Paragraph(Plain("No rows.")));
  } else {
    section.blocks.push_back(Folded(TableOf(*table), file));
  }
  return section;
}

Section RunTimesSection(const StudyFolder& study, const std::vector<CaseRow>& cases) {
  Section section{"run-times-and-keys", "Run times and keys", 2, {}};
  if (cases.empty()) {
    section.blocks.push_back(Note(Plain("No case folders (") + Code("cases/r<K>/<case>/") +
                                  Plain(") in this study folder.")));
  } else {
    section.blocks.push_back(Paragraph(
        Plain("From each case's ") + Code("done.toml") + Plain(" (written when it ended) and ") +
        Code("case.toml") +
        Plain(": the key is the SHA-256 of its canonical scene, its parent's key, the program "
              "version and the thread count. Steps: the case's own (its engine steps less the "
              "step it started from: the end of the parent's stage it forks from) and the "
              "engine total.")));
    Block table;
    table.type = Block::Type::kTable;
    table.header = {"case",      "replicate",        "parent",    "status",
                    "own steps", "engine steps",     "particles", "particle-steps",
                    "wall s",    "particle-steps/s", "key",       "message"};
    int64_t own_steps = 0;
    double particle_steps = 0, wall_seconds = 0;
    int done = 0;
    for (const CaseRow& c : cases) {
      const double ps = static_cast<double>(c.own_steps) * static_cast<double>(c.particles);
      const CaseRecord& r = c.record;
      std::vector<Cell> row = {
          Cell{Link(r.id, UrlPath("cases/" + r.id + "/" + CaseRecord::kFileName)), ""},
          Cell{Plain(std::to_string(r.replicate)), "num"},
          Cell{r.parent.empty() ? Plain("sample") : Plain(r.parent), ""},
          Cell{Plain(c.status), StatusCss(c.status)}};
      if (c.done) {
        ++done;
        own_steps += c.own_steps;
        particle_steps += ps;
        wall_seconds += c.wall_seconds;
        row.push_back(Cell{Plain(std::to_string(c.own_steps)), "num"});
        row.push_back(Cell{Plain(std::to_string(c.steps)), "num"});
        row.push_back(Cell{Plain(std::to_string(c.particles)), "num"});
        row.push_back(Cell{Plain(fmt::format("{:.4g}", ps)), "num"});
        row.push_back(Cell{Plain(fmt::format("{:.3f}", c.wall_seconds)), "num"});
        row.push_back(Cell{Plain(c.wall_seconds > 0 ? fmt::format("{:.3g}", ps / c.wall_seconds)
                                                    : std::string("—")),
                           "num"});
      } else {
        for (int k = 0; k < 6; ++k) row.push_back(Cell{Plain("—"), "num"});
      }
      row.push_back(Cell{Code(r.key), ""});
      row.push_back(Cell{Plain(c.message), "text"});
      table.rows.push_back(std::move(row));
      table.row_css.push_back("");
    }
    table.rows.push_back(
        {Cell{Plain(fmt::format("total: {} finished of {}", done, cases.size())), ""},
         Cell{Plain(""), ""}, Cell{Plain(""), ""}, Cell{Plain(""), ""},
         Cell{Plain(std::to_string(own_steps)), "num"}, Cell{Plain(""), ""}, Cell{Plain(""), ""},
         Cell{Plain(fmt::format("{:.4g}", particle_steps)), "num"},
         Cell{Plain(fmt::format("{:.3f}", wall_seconds)), "num"},
         Cell{Plain(wall_seconds > 0 ? fmt::format("{:.3g}", particle_steps / wall_seconds)
                                     : std::string("—")),
              "num"},
         Cell{Plain(""), ""}, Cell{Plain(""), ""}});
    table.row_css.push_back("total");
    section.blocks.push_back(Paragraph(Plain(fmt::format(
        "{} finished cases: {} steps of their own, {:.4g} particle-steps, {:.1f} s of case wall "
        "time (cases run in parallel: the study's elapsed time is shorter).",
        done, own_steps, particle_steps, wall_seconds))));
    section.blocks.push_back(Folded(std::move(table), "cases (and the total)"));
  }
  // Model runs (element tests of the constitutive models).
  std::vector<fs::path> models;
  if (study.Exists("models")) {
    for (const auto& entry : fs::directory_iterator(study.Path("models"))) {
      if (entry.is_directory()) models.push_back(entry.path());
    }
  }
  std::sort(models.begin(), models.end());
  if (!models.empty()) {
    Block table;
    table.type = Block::Type::kTable;
    table.header = {"model run", "status", "wall s", "key", "message"};
    for (const fs::path& folder : models) {
      const std::string name = "models/" + folder.filename().string();
      if (!fs::exists(folder / "done.toml")) {
        table.rows.push_back({Cell{Code(name), ""}, Cell{Plain("not_run"), StatusCss("not_run")},
                              Cell{Plain("—"), "num"}, Cell{Plain(""), ""},
                              Cell{Plain("no done.toml"), "text"}});
        continue;
      }
      const ConfigTable done = ConfigTable::ParseFile((folder / "done.toml").string());
      const std::string status = done.GetString("termination", "?");
      table.rows.push_back(
          {Cell{Link(name, UrlPath(name + "/done.toml"), true), ""},
           Cell{Plain(status), StatusCss(status)},
           Cell{Plain(fmt::format("{:.3f}", done.GetDouble("wall_seconds", 0.0, Range::Any()))),
                "num"},
           Cell{Code(done.GetString("key", "")), ""},
           Cell{Plain(done.GetString("message", "")), "text"}});
    }
    section.blocks.push_back(Paragraph(Plain(
        fmt::format("{} element tests of the constitutive models (deterministic: not replicated):",
                    models.size()))));
    section.blocks.push_back(Folded(std::move(table), "model runs"));
  }
  return section;
}

Section ProvenanceSection(const StudyFolder& study) {
  Section section{"provenance", "Provenance", 2, {}};
  section.blocks.push_back(
      Paragraph(Plain("The study record ") + Link("study.toml", "study.toml", true) +
                Plain(", written by ") + Code("granasym study run") +
                Plain("; each case's key is in the table of run times, its scene in ") +
                Code("cases/r<K>/<case>/scene.toml") + Plain(".")));
  Block table;
  table.type = Block::Type::kTable;
  table.header = {"key", "value"};
  for (const auto& [key, value] : study.record) {
    table.rows.push_back({Cell{Code(key), ""}, Cell{Plain(value), ""}});
  }
  section.blocks.push_back(std::move(table));
  return section;
}

}  // namespace granasym::analysis::report
