#include "study/case_record.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <optional>

#include "common/config.h"
#include "common/error.h"
#include "common/text_file.h"

namespace granasym::study {
namespace fs = std::filesystem;
namespace {

constexpr char kSectionPrefix[] = "Sec. ";

std::string Trimmed(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

bool AllDigits(const std::string& text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// The figure number of an entry, or 0.
int FigureNumber(const std::string& entry) {
  if (!AllDigits(entry) || entry.size() > 3 || entry[0] == '0') return 0;
  const int number = std::stoi(entry);
  return number <= FigureSet::kPaperFigures ? number : 0;
}

std::string SectionOf(const std::string& entry) {
  const std::string prefix = kSectionPrefix;
  return entry.compare(0, prefix.size(), prefix) == 0 ? entry.substr(prefix.size()) : "";
}

std::string ValidEntries() {
  std::string sections;
  for (const std::string& s : FigureSet::PaperSections()) {
    sections += (sections.empty() ? "" : ", ") + s;
  }
  return "figure numbers 1-" + std::to_string(FigureSet::kPaperFigures) +
         " of the paper, its sections as 'Sec. N' (N one of " + sections + ") or '" +
         FigureSet::kRate + "' (the rate study), separated by commas";
}

}  // namespace

const std::vector<std::string>& FigureSet::PaperSections() {
  static const std::vector<std::string> sections = {"1",   "2",   "2.1", "2.2", "3",   "4",   "4.1",
                                                    "4.2", "4.3", "5",   "5.1", "5.2", "5.3", "6"};
  return sections;
}

FigureSet FigureSet::Parse(const std::string& text, const std::string& origin,
                           const std::string& key) {
  FigureSet set;
  size_t at = 0;
  while (at <= text.size()) {
    size_t end = text.find(',', at);
    if (end == std::string::npos) end = text.size();
    const std::string entry = Trimmed(text.substr(at, end - at));
    at = end + 1;
    if (entry.empty()) {
      if (Trimmed(text).empty()) break;
      throw InputError(origin + ": key '" + key + "' = '" + text +
                       "' has an empty entry: expected " + ValidEntries());
    }
    const std::string section = SectionOf(entry);
    const auto& sections = PaperSections();
    const bool valid = FigureNumber(entry) > 0 || entry == kRate ||
                       std::find(sections.begin(), sections.end(), section) != sections.end();
    if (!valid) {
      throw InputError(origin + ": key '" + key + "' = '" + text + "': '" + entry +
                       "' is not valid: expected " + ValidEntries());
    }
    if (std::find(set.entries_.begin(), set.entries_.end(), entry) != set.entries_.end()) {
      throw InputError(origin + ": key '" + key + "' = '" + text + "' names '" + entry +
                       "' twice: name each figure once");
    }
    set.entries_.push_back(entry);
  }
  return set;
}

bool FigureSet::Contains(const std::string& entry) const {
  return std::find(entries_.begin(), entries_.end(), entry) != entries_.end();
}

bool FigureSet::HasFigure(int number) const {
  for (const std::string& entry : entries_) {
    if (FigureNumber(entry) == number && number > 0) return true;
  }
  return false;
}

bool FigureSet::HasSection(const std::string& number) const {
  for (const std::string& entry : entries_) {
    if (SectionOf(entry) == number && !number.empty()) return true;
  }
  return false;
}

bool FigureSet::ServesRateStudy() const { return Contains(kRate); }

std::vector<int> FigureSet::Figures() const {
  std::vector<int> figures;
  for (const std::string& entry : entries_) {
    if (const int number = FigureNumber(entry)) figures.push_back(number);
  }
  return figures;
}

std::string FigureSet::Text() const {
  std::string text;
  for (const std::string& entry : entries_) text += (text.empty() ? "" : ", ") + entry;
  return text;
}

std::string CaseRecord::parent_name() const {
  return parent.empty() ? "" : parent.substr(parent.find('/') + 1);
}

std::string CaseRecord::Text() const {
  std::string text = "# what this case is (written by granasym study run)\n";
  text += "id = " + TomlQuoted(id) + "\n";
  text += "name = " + TomlQuoted(name) + "\n";
  text += "replicate = " + std::to_string(replicate) + "\n";
  text += "key = " + TomlQuoted(key) + "\n";
  text += "parent = " + TomlQuoted(parent) + "\n";
  text += "parent_stage = " + TomlQuoted(parent_stage) + "\n";
  text += "run = " + TomlQuoted(run) + "\n";
  text += "figures = " + TomlQuoted(figures.Text()) + "\n";
  text += "programme = " + TomlQuoted(programme) + "\n";
  text += "scale = " + TomlQuoted(scale) + "\n";
  text += "threads = " + std::to_string(threads) + "\n";
  text += "program_version = " + TomlQuoted(program_version) + "\n";
  text += "[variables]\n";
  for (const auto& [variable, value] : variables)
    text += variable + " = " + TomlQuoted(value) + "\n";
  return text;
}

void CaseRecord::Write(const std::string& directory) const {
  WriteIfChanged(directory + "/" + kFileName, Text());
}

CaseRecord CaseRecord::Read(const std::string& case_directory) {
  const std::string path = case_directory + "/" + kFileName;
  if (!fs::exists(path)) {
    throw InputError(path +
                     ": no such file: a case folder holds the case.toml that "
                     "`granasym study run` writes");
  }
  const ConfigTable table = ConfigTable::ParseFile(path);
  CaseRecord c;
  c.directory = case_directory;
  c.id = table.GetString("id");
  c.name = table.GetString("name");
  c.replicate = static_cast<int>(table.GetInt("replicate", 1, Range::AtLeast(1)));
  c.key = table.GetString("key");
  c.parent = table.GetString("parent", "");
  c.parent_stage = table.GetString("parent_stage", "");
  c.run = table.GetString("run", "");
  c.figures = FigureSet::Parse(table.GetString("figures", ""), path, "figures");
  c.programme = table.GetString("programme", "");
  c.scale = table.GetString("scale", "");
  c.threads = static_cast<int>(table.GetInt("threads", 1, Range::AtLeast(1)));
  c.program_version = table.GetString("program_version", "");
  if (table.Has("variables")) {
    const ConfigTable variables = table.GetTable("variables");
    for (const std::string& name : variables.Keys()) {
      c.variables[name] = variables.GetString(name);
    }
  }
  table.CheckNoUnknownKeys();
  return c;
}

CaseDone CaseRecord::Done() const {
  CaseDone outcome;
  outcome.done = ReadDone(directory);
  outcome.current = outcome.done && outcome.done->key == key;
  if (outcome.current && fs::exists(result_path())) {
    outcome.mismatch = ResultMismatch(result_path(), *outcome.done);
    outcome.finished = outcome.mismatch.empty();
  }
  return outcome;
}

namespace {

constexpr char kPlanHeader[] = "id\tname\treplicate\tparent\tparent_stage\trun\tfigures";

// A field of plan.tsv: backslash, tab and line breaks escaped.
std::string Escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\\') {
      out += "\\\\";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else {
      out += c;
    }
  }
  return out;
}

std::string Unescaped(const std::string& text) {
  std::string out;
  for (size_t k = 0; k < text.size(); ++k) {
    if (text[k] != '\\' || k + 1 == text.size()) {
      out += text[k];
      continue;
    }
    const char next = text[++k];
    out += next == 't' ? '\t' : next == 'n' ? '\n' : next == 'r' ? '\r' : next;
  }
  return out;
}

}  // namespace

std::string PlanFileText(const std::vector<CaseRecord>& cases) {
  std::string text = std::string(
                         "# the cases of the programme this folder was last run with "
                         "(written by granasym study run)\n") +
                     kPlanHeader + "\n";
  for (const CaseRecord& c : cases) {
    text += Escaped(c.id) + "\t" + Escaped(c.name) + "\t" + std::to_string(c.replicate) + "\t" +
            Escaped(c.parent) + "\t" + Escaped(c.parent_stage) + "\t" + Escaped(c.run) + "\t" +
            Escaped(c.figures.Text()) + "\n";
  }
  return text;
}

std::optional<std::vector<CaseRecord>> ReadPlannedCases(const std::string& study_directory) {
  const std::string path = study_directory + "/" + kPlanFileName;
  if (!fs::exists(path)) return std::nullopt;
  const std::string text = ReadTextFile(path);
  std::vector<CaseRecord> cases;
  size_t at = 0;
  int line_number = 0;
  bool header = false;
  while (at < text.size()) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(at, end - at);
    at = end + 1;
    ++line_number;
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line != kPlanHeader) {
        throw InputError(fmt::format("{}: line {}: expected the header '{}', found '{}'", path,
                                     line_number, kPlanHeader, line));
      }
      header = true;
      continue;
    }
    std::vector<std::string> fields;
    size_t start = 0;
    for (;;) {
      const size_t tab = line.find('\t', start);
      fields.push_back(Unescaped(line.substr(start, tab - start)));
      if (tab == std::string::npos) break;
      start = tab + 1;
    }
    if (fields.size() != 7) {
      throw InputError(fmt::format("{}: line {}: {} fields, expected 7 ({})", path, line_number,
                                   fields.size(), kPlanHeader));
    }
    CaseRecord c;
    c.id = fields[0];
    c.name = fields[1];
    try {
      c.replicate = std::stoi(fields[2]);
    } catch (const std::exception&) {
      c.replicate = 0;
    }
    if (c.replicate < 1 || c.id != "r" + fields[2] + "/" + c.name) {
      throw InputError(fmt::format(
          "{}: line {}: id '{}', name '{}' and replicate '{}' do not agree (expected the id "
          "r<replicate>/<name>, replicate >= 1)",
          path, line_number, c.id, c.name, fields[2]));
    }
    c.parent = fields[3];
    c.parent_stage = fields[4];
    c.run = fields[5];
    c.figures =
        FigureSet::Parse(fields[6], fmt::format("{}: line {}", path, line_number), "figures");
    c.directory = study_directory + "/cases/" + c.id;
    cases.push_back(std::move(c));
  }
  if (!header) throw InputError(path + ": no header line '" + kPlanHeader + "'");
  return cases;
}

std::vector<CaseRecord> ReadCaseRecords(const std::string& study_directory) {
  std::vector<CaseRecord> records;
  const std::optional<std::vector<CaseRecord>> planned = ReadPlannedCases(study_directory);
  if (!planned) {
    for (const std::string& folder : CaseFolders(study_directory)) {
      records.push_back(CaseRecord::Read(folder));
    }
    return records;
  }
  for (const CaseRecord& c : *planned) {
    if (fs::exists(c.directory + "/" + CaseRecord::kFileName)) {
      records.push_back(CaseRecord::Read(c.directory));
    } else {
      records.push_back(c);
    }
  }
  std::sort(records.begin(), records.end(),
            [](const CaseRecord& a, const CaseRecord& b) { return a.directory < b.directory; });
  return records;
}

}  // namespace granasym::study
