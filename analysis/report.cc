#include "analysis/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include "analysis/rate_study.h"
#include "common/config.h"
#include "common/csv_table.h"
#include "common/error.h"
#include "common/provenance.h"
#include "common/text_file.h"
#include "study/case_record.h"
#include "study/study_folder.h"

namespace granasym::analysis {
using study::CaseRecord;
using study::DoneRecord;
using study::FigureSet;
using study::OwnSteps;
using study::ReadCaseRecords;
using study::ReadDone;

const char* const kReportModels[3] = {"hypoplastic_clay", "modified_cam_clay", "hypoplastic_sand"};

namespace {
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------
// The document: sections of blocks, rendered once as HTML and once as
// Markdown, so that both files carry the same content.

// A piece of inline text: plain, code, or a link (a relative path or an anchor).
struct Span {
  std::string text, href;
  bool code = false;
};
using Inline = std::vector<Span>;

Inline Plain(const std::string& text) { return {Span{text, "", false}}; }
Inline Code(const std::string& text) { return {Span{text, "", true}}; }
Inline Link(const std::string& text, const std::string& href, bool code = false) {
  return {Span{text, href, code}};
}
Inline operator+(Inline a, const Inline& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}
std::string PlainText(const Inline& content) {
  std::string text;
  for (const Span& span : content) text += span.text;
  return text;
}

struct Cell {
  Inline content;
  std::string css;  // classes of the cell (HTML only)
};

struct Block {
  enum class Type { kParagraph, kNote, kTable, kFigure, kDetails, kList };
  Type type = Type::kParagraph;
  Inline text;                          // paragraph, note, details' summary, figure's alt text
  std::vector<std::string> header;      // table
  std::vector<std::vector<Cell>> rows;  // table
  std::vector<std::string> row_css;     // table: classes of each row (may be empty)
  std::string image;                    // figure: relative path of the PNG
  std::string preformatted;             // details: shown as a code block
  std::vector<Block> children;          // details: blocks inside
  std::vector<Inline> items;            // list
};

Block Paragraph(Inline text) {
  Block block;
  block.text = std::move(text);
  return block;
}
Block Note(Inline text) {
  Block block = Paragraph(std::move(text));
  block.type = Block::Type::kNote;
  return block;
}

struct Section {
  std::string id;  // the anchor: set from the title when the document is complete
  std::string title;
  int level = 2;
  std::vector<Block> blocks;
};

struct Document {
  std::string title;
  Inline subtitle;
  std::vector<Section> sections;
};

// The anchor of a heading as forges derive it (lower case, blanks to '-',
// other ASCII punctuation dropped), so that report.md's contents work there
// too; a repeated anchor gets "-1", "-2", ... as on GitHub.
std::string Slug(const std::string& title) {
  std::string slug;
  for (char c : title) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || u >= 0x80) {
      slug += static_cast<char>(std::tolower(u));
    } else if (c == ' ' || c == '-') {
      slug += '-';
    } else if (c == '_') {
      slug += '_';
    }
  }
  return slug;
}

// A relative path as a URL: every byte but unreserved characters and '/'
// percent-encoded.
std::string UrlPath(const std::string& path) {
  std::string url;
  for (char c : path) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '/' || c == '.' || c == '_' || c == '-' || c == '~') {
      url += c;
    } else {
      url += fmt::format("%{:02X}", u);
    }
  }
  return url;
}

// ---------------------------------------------------------------------------
// HTML

constexpr const char* kStylesheet = R"(
*{box-sizing:border-box}
body{font:15px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,"Noto Sans",sans-serif;
 color:#1b1b1b;background:#fff;margin:0 auto;max-width:84rem;padding:0 1rem 3rem}
h1{font-size:1.7em;margin:1em 0 .3em}
h2{font-size:1.35em;border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2.2em}
h3{font-size:1.1em;margin-top:1.6em}
p,li,figcaption,summary,h1,h2,h3{overflow-wrap:anywhere}
a{color:#0b57a4}
nav.toc{background:#f4f6f8;border:1px solid #dde;padding:.3em 1em;margin:1em 0}
nav.toc ol{margin:.3em 0;padding-left:1.5em}
.scroll{overflow-x:auto;max-width:100%;margin:.5em 0 1em}
table{border-collapse:collapse;font-size:13px}
th,td{border:1px solid #d0d4d8;padding:.2em .5em;text-align:left;vertical-align:top;
 white-space:nowrap}
th{background:#eef1f4}
td.num{text-align:right;font-variant-numeric:tabular-nums}
td.text{white-space:normal;min-width:18em;max-width:44em}
tr.total td{font-weight:600;background:#f6f6f6}
.status-detected,.status-fitted,.status-fixed,.status-completed,.status-joined{color:#176b2c}
.status-drifting,.status-not_reached,.status-at_bound,.status-not_joined,.status-no_overlap,
.status-interrupted,.status-running,.status-stale,.flagged{color:#8a5a00;font-weight:600}
.status-gas,.status-invalid,.status-no_result,.status-undetermined,.status-failed,
.status-not_run{color:#b3261e;font-weight:600}
p.note{border-left:4px solid #d39e00;background:#fff8e1;padding:.4em .8em}
figure{margin:1em 0}
img{max-width:100%;height:auto;border:1px solid #e0e0e0;background:#fff}
pre{overflow-x:auto;background:#f5f5f5;padding:.6em;font-size:13px;max-width:100%}
code{font-size:90%;overflow-wrap:anywhere}
details{margin:.5em 0}
summary{cursor:pointer}
)";

std::string HtmlInline(const Inline& content) {
  std::string html;
  for (const Span& span : content) {
    std::string text = HtmlEscaped(span.text);
    if (span.code) text = "<code>" + text + "</code>";
    if (!span.href.empty()) text = "<a href=\"" + HtmlEscaped(span.href) + "\">" + text + "</a>";
    html += text;
  }
  return html;
}

void HtmlBlock(const Block& block, std::string* html) {
  switch (block.type) {
    case Block::Type::kParagraph:
      *html += "<p>" + HtmlInline(block.text) + "</p>\n";
      break;
    case Block::Type::kNote:
      *html += "<p class=\"note\">" + HtmlInline(block.text) + "</p>\n";
      break;
    case Block::Type::kTable: {
      *html += "<div class=\"scroll\"><table>\n<thead><tr>";
      for (const std::string& name : block.header) *html += "<th>" + HtmlEscaped(name) + "</th>";
      *html += "</tr></thead>\n<tbody>\n";
      for (size_t r = 0; r < block.rows.size(); ++r) {
        const std::string css = r < block.row_css.size() ? block.row_css[r] : "";
        *html += css.empty() ? "<tr>" : "<tr class=\"" + HtmlEscaped(css) + "\">";
        for (const Cell& cell : block.rows[r]) {
          *html += cell.css.empty() ? "<td>" : "<td class=\"" + HtmlEscaped(cell.css) + "\">";
          *html += HtmlInline(cell.content) + "</td>";
        }
        *html += "</tr>\n";
      }
      *html += "</tbody></table></div>\n";
      break;
    }
    case Block::Type::kFigure:
      *html += "<figure><a href=\"" + HtmlEscaped(UrlPath(block.image)) + "\"><img src=\"" +
               HtmlEscaped(UrlPath(block.image)) + "\" alt=\"" +
               HtmlEscaped(PlainText(block.text)) + "\"></a></figure>\n";
      break;
    case Block::Type::kDetails:
      *html += "<details><summary>" + HtmlInline(block.text) + "</summary>\n";
      if (!block.preformatted.empty()) {
        *html += "<pre>" + HtmlEscaped(block.preformatted) + "</pre>\n";
      }
      for (const Block& child : block.children) HtmlBlock(child, html);
      *html += "</details>\n";
      break;
    case Block::Type::kList:
      *html += "<ul>\n";
      for (const Inline& item : block.items) *html += "<li>" + HtmlInline(item) + "</li>\n";
      *html += "</ul>\n";
      break;
  }
}

std::string RenderHtml(const Document& document) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>" +
      HtmlEscaped(document.title) + "</title>\n<style>" + kStylesheet +
      "</style>\n</head>\n<body>\n";
  html += "<h1>" + HtmlEscaped(document.title) + "</h1>\n";
  html += "<p>" + HtmlInline(document.subtitle) + "</p>\n";
  html += "<nav class=\"toc\"><strong>Contents</strong>\n<ol>\n";
  bool open_item = false, nested = false;
  for (const Section& section : document.sections) {
    const std::string link =
        "<a href=\"#" + HtmlEscaped(section.id) + "\">" + HtmlEscaped(section.title) + "</a>";
    if (section.level > 2 && open_item) {
      if (!nested) html += "\n<ol>\n";
      nested = true;
      html += "<li>" + link + "</li>\n";
      continue;
    }
    if (nested) html += "</ol>";
    if (open_item) html += "</li>\n";
    html += "<li>" + link;
    open_item = true;
    nested = false;
  }
  if (nested) html += "</ol>";
  if (open_item) html += "</li>\n";
  html += "</ol></nav>\n";
  for (const Section& section : document.sections) {
    const std::string tag = "h" + std::to_string(section.level);
    html += "<" + tag + " id=\"" + HtmlEscaped(section.id) + "\">" + HtmlEscaped(section.title) +
            "</" + tag + ">\n";
    for (const Block& block : section.blocks) HtmlBlock(block, &html);
  }
  html += "</body>\n</html>\n";
  return html;
}

// ---------------------------------------------------------------------------
// Markdown (CommonMark with pipe tables, as forges render it)

std::string MarkdownEscaped(const std::string& text) {
  std::string out;
  for (size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (c == '\n' || c == '\r') {
      out += ' ';
      continue;
    }
    // '_' only emphasises at a word boundary (snake_case names stay readable).
    const bool boundary_underscore =
        c == '_' &&
        (k == 0 || k + 1 == text.size() || !std::isalnum(static_cast<unsigned char>(text[k - 1])) ||
         !std::isalnum(static_cast<unsigned char>(text[k + 1])));
    if (c == '\\' || c == '*' || c == '[' || c == ']' || c == '<' || c == '>' || c == '`' ||
        c == '|' || c == '#' || c == '&' || boundary_underscore) {
      out += '\\';
    }
    out += c;
  }
  return out;
}

std::string Fence(const std::string& text, char mark, size_t minimum) {
  size_t longest = 0, run = 0;
  for (char c : text) {
    run = c == mark ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  return std::string(std::max(minimum, longest + 1), mark);
}

std::string MarkdownInline(const Inline& content) {
  std::string md;
  for (const Span& span : content) {
    std::string text;
    if (span.code) {
      std::string code = span.text;
      std::replace(code.begin(), code.end(), '\n', ' ');
      const std::string fence = Fence(code, '`', 1);
      const bool pad = !code.empty() && (code.front() == '`' || code.back() == '`');
      text = fence + (pad ? " " : "") + code + (pad ? " " : "") + fence;
      // Inside a pipe table a '|' ends the cell even in a code span.
      std::string escaped;
      for (char c : text) escaped += c == '|' ? std::string("\\|") : std::string(1, c);
      text = escaped;
    } else {
      text = MarkdownEscaped(span.text);
    }
    if (!span.href.empty()) {
      std::string href;
      for (char c : span.href) {
        href += c == '(' ? std::string("%28") : c == ')' ? std::string("%29") : std::string(1, c);
      }
      text = "[" + text + "](" + href + ")";
    }
    md += text;
  }
  return md;
}

void MarkdownBlock(const Block& block, std::string* md) {
  switch (block.type) {
    case Block::Type::kParagraph:
      *md += MarkdownInline(block.text) + "\n\n";
      break;
    case Block::Type::kNote:
      *md += "> " + MarkdownInline(block.text) + "\n\n";
      break;
    case Block::Type::kTable: {
      std::string line = "|", rule = "|";
      for (const std::string& name : block.header) {
        line += " " + MarkdownEscaped(name) + " |";
        rule += " --- |";
      }
      *md += line + "\n" + rule + "\n";
      for (const std::vector<Cell>& row : block.rows) {
        line = "|";
        for (const Cell& cell : row) line += " " + MarkdownInline(cell.content) + " |";
        *md += line + "\n";
      }
      *md += "\n";
      break;
    }
    case Block::Type::kFigure:
      *md += "![" + MarkdownEscaped(PlainText(block.text)) + "](" + UrlPath(block.image) + ")\n\n";
      break;
    case Block::Type::kDetails:
      // Forges fold <details>; a terminal shows its content as it is.
      *md += "<details><summary>" + HtmlEscaped(PlainText(block.text)) + "</summary>\n\n";
      if (!block.preformatted.empty()) {
        const std::string fence = Fence(block.preformatted, '`', 3);
        *md += fence + "text\n" + block.preformatted +
               (block.preformatted.back() == '\n' ? "" : "\n") + fence + "\n\n";
      }
      for (const Block& child : block.children) MarkdownBlock(child, md);
      *md += "</details>\n\n";
      break;
    case Block::Type::kList:
      for (const Inline& item : block.items) *md += "- " + MarkdownInline(item) + "\n";
      *md += "\n";
      break;
  }
}

std::string RenderMarkdown(const Document& document) {
  std::string md = "# " + MarkdownEscaped(document.title) + "\n\n";
  md += MarkdownInline(document.subtitle) + "\n\n";
  md += "**Contents**\n\n";
  for (const Section& section : document.sections) {
    md += std::string(section.level > 2 ? "    " : "") + "- [" + MarkdownEscaped(section.title) +
          "](#" + section.id + ")\n";
  }
  md += "\n";
  for (const Section& section : document.sections) {
    md += std::string(section.level, '#') + " " + MarkdownEscaped(section.title) + "\n\n";
    for (const Block& block : section.blocks) MarkdownBlock(block, &md);
  }
  return md;
}

// ---------------------------------------------------------------------------
// Reading the study folder

// `key = value` lines of a flat TOML record in file order (tables' keys
// prefixed by the table name), strings unquoted; the file is validated by
// the TOML parser first, so a malformed record is an InputError naming it.
std::vector<std::pair<std::string, std::string>> ReadFlatRecord(const std::string& path) {
  ConfigTable::ParseFile(path);
  std::vector<std::pair<std::string, std::string>> entries;
  std::string table;
  const std::string text = ReadTextFile(path);
  size_t at = 0;
  while (at < text.size()) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(at, end - at);
    at = end + 1;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    line = line.substr(first);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.front() == '[') {
      table = line.substr(1, line.find(']') - 1);
      continue;
    }
    const size_t equals = line.find('=');
    if (equals == std::string::npos) continue;
    std::string key = line.substr(0, equals), value = line.substr(equals + 1);
    while (!key.empty() && key.back() == ' ') key.pop_back();
    value = value.substr(std::min(value.size(), value.find_first_not_of(' ')));
    if (value.size() >= 2 && value.front() == '"' && value.back() == '"') {
      std::string unquoted;
      for (size_t k = 1; k + 1 < value.size(); ++k) {
        if (value[k] == '\\' && k + 2 < value.size()) {
          ++k;
          unquoted += value[k] == 'n' ? '\n' : value[k] == 't' ? '\t' : value[k];
        } else {
          unquoted += value[k];
        }
      }
      value = unquoted;
    }
    entries.emplace_back(table.empty() ? key : table + "." + key, value);
  }
  return entries;
}

std::string Lookup(const std::vector<std::pair<std::string, std::string>>& entries,
                   const std::string& key, const std::string& fallback = "") {
  for (const auto& [name, value] : entries) {
    if (name == key) return value;
  }
  return fallback;
}

bool IsInteger(const std::string& text) {
  if (text.empty() || text.size() > 18) return false;
  size_t k = text[0] == '-' || text[0] == '+' ? 1 : 0;
  if (k == text.size()) return false;
  for (; k < text.size(); ++k) {
    if (!std::isdigit(static_cast<unsigned char>(text[k]))) return false;
  }
  return true;
}

std::optional<double> Number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (*end != '\0' || errno == ERANGE) return std::nullopt;
  return value;
}

// A field for display: integers as written, other numbers to 4 significant
// digits (the CSV linked beside every table has them in full), text as it is.
Cell FieldCell(const std::string& field) {
  if (IsInteger(field)) return Cell{Plain(field), "num"};
  if (const std::optional<double> value = Number(field)) {
    return Cell{Plain(fmt::format("{:.4g}", *value)), "num"};
  }
  return Cell{Plain(field), ""};
}

std::string StatusCss(const std::string& status) {
  std::string css = "status-";
  for (char c : status) css += std::isalnum(static_cast<unsigned char>(c)) || c == '_' ? c : '_';
  return css;
}

// A whole CSV as a table, numbers shortened, status and flag columns marked.
Block TableOf(const CsvTextTable& table) {
  Block block;
  block.type = Block::Type::kTable;
  block.header = table.columns;
  for (const std::vector<std::string>& fields : table.rows) {
    std::vector<Cell> row;
    for (size_t c = 0; c < fields.size(); ++c) {
      Cell cell = FieldCell(fields[c]);
      if (table.columns[c] == "status" && !fields[c].empty()) cell.css = StatusCss(fields[c]);
      if (table.columns[c] == "flags" && !fields[c].empty()) cell.css = "flagged";
      if (table.columns[c] == "message") cell.css = "text";
      row.push_back(std::move(cell));
    }
    block.rows.push_back(std::move(row));
  }
  return block;
}

Inline DirectoryHint(const std::string& command, const std::string& directory) {
  return Code("granasym study " + command + " " + directory);
}

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

// What the report knows of the study folder, read once.
struct StudyFolder {
  std::string directory;
  std::vector<std::pair<std::string, std::string>> record;  // study.toml
  std::optional<CsvTextTable> states, summary, ncl, convergence;
  std::vector<std::string> absent;

  std::string Path(const std::string& name) const { return directory + "/" + name; }
  bool Exists(const std::string& name) const { return fs::exists(Path(name)); }

  std::optional<CsvTextTable> ReadCsv(const std::string& name) {
    if (!Exists(name)) {
      absent.push_back(name);
      return std::nullopt;
    }
    return CsvTextTable::ReadFile(Path(name));
  }
};

Block MissingTableNote(const std::string& name, const std::string& directory) {
  return Note(Code(name) + Plain(" is absent: the state table has not been written (run ") +
              Code("granasym study merge " + directory + " --out " + directory) +
              Plain(" after the cases ran)."));
}

// ---------------------------------------------------------------------------
// Sections

// A case as the report shows it: its record and what became of it.
struct CaseRow {
  CaseRecord record;
  std::string status;  // the termination, or stale, running, not_run
  std::string message;
  int64_t steps = 0, own_steps = 0, particles = 0;
  double wall_seconds = 0;
  bool done = false;
};

std::vector<CaseRow> ReadCases(const std::string& directory) {
  std::vector<CaseRow> cases;
  for (const CaseRecord& record : ReadCaseRecords(directory)) {
    const fs::path folder(record.directory);
    CaseRow c;
    c.record = record;
    if (const std::optional<DoneRecord> done = ReadDone(record.directory)) {
      c.message = done->message;
      c.steps = done->steps;
      c.particles = done->particles;
      c.wall_seconds = done->wall_seconds;
      c.done = done->key == record.key;
      c.status = c.done ? ToString(done->termination) : "stale";
      if (!c.done)
        c.message = "done.toml is for another key: the inputs changed since; " + c.message;
    } else if (fs::exists(folder / "result.h5.ckpt") || fs::exists(folder / "running.toml")) {
      c.status = "running";
      c.message = "a checkpoint: running, or interrupted (resumes on the next run)";
    } else {
      c.status = "not_run";
      c.message = "not run";
    }
    cases.push_back(std::move(c));
  }
  // A case's own steps: its engine steps less the step it started from.
  const std::map<std::string, int64_t> own = OwnSteps(directory);
  for (CaseRow& c : cases) {
    const auto found = own.find(c.record.id);
    c.own_steps = c.done && found != own.end() ? found->second : c.steps;
  }
  return cases;
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
    for (const auto& row : states.rows) ++by_state[status >= 0 ? row[status] : "?"];
    std::string text = fmt::format("{} rows", states.rows.size());
    for (const auto& [name, count] : by_state) text += fmt::format(", {} {}", count, name);
    add("asymptotic states", Plain(text));
  }
  add("figures",
      Plain(fmt::format("{} in figures/index.tsv, {} without their PNG", figures, figures_missing)),
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

// The states behind a figure: the rows of the state table whose `figures`
// column names it ("10", "Sec. 5.2"; the rate study's figures draw its own tables).
std::optional<Block> StatesOfFigure(const StudyFolder& study, const std::string& entry) {
  if (!study.states || entry.empty() || entry.rfind(FigureSet::kRate, 0) == 0) return std::nullopt;
  const CsvTextTable& states = *study.states;
  const int figures = states.Find("figures");
  if (figures < 0) return std::nullopt;
  const std::vector<std::string> wanted = {
      "replicate", "case", "stage",         "kind",     "status", "psi_epsilon_deg",
      "p_kpa",     "e",    "psi_sigma_deg", "q_over_p", "ocr",    "flags"};
  std::vector<int> columns;
  Block table;
  table.type = Block::Type::kTable;
  for (const std::string& name : wanted) {
    const int c = states.Find(name);
    if (c < 0) continue;
    columns.push_back(c);
    table.header.push_back(name);
  }
  for (const auto& fields : states.rows) {
    if (!FigureSet::Parse(fields[figures], study.Path("asymptotic_states.csv"), "figures")
             .Contains(entry)) {
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
  if (table.rows.empty()) {
    const std::string what = entry.rfind("Sec.", 0) == 0 ? entry : "figure " + entry;
    return Paragraph(Plain("No row of the state table names " + what + "."));
  }
  Block details;
  details.type = Block::Type::kDetails;
  details.text = Plain(fmt::format("{} row{} of the state table behind {}", table.rows.size(),
                                   table.rows.size() == 1 ? "" : "s",
                                   entry.rfind("Sec.", 0) == 0 ? entry : "figure " + entry));
  details.children.push_back(std::move(table));
  return details;
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
                                 Plain("; each image links to itself at full size.")));
  std::set<std::string> indexed;
  std::vector<Section> figure_sections;
  for (size_t r = 0; r < index.rows.size(); ++r) {
    const std::vector<std::string>& row = index.rows[r];
    CheckStem(row[stem], index, index.line_numbers[r]);
    indexed.insert(row[stem]);
    ++*figures;
    Section section;
    section.level = 3;
    section.title = "Figure " + row[figure] + ": " + row[title];
    const std::string png = "figures/" + row[stem] + ".png";
    const std::string pdf = "figures/" + row[stem] + ".pdf";
    if (study.Exists(png)) {
      Block image;
      image.type = Block::Type::kFigure;
      image.image = png;
      image.text = Plain("Figure " + row[figure] + ": " + row[title]);
      section.blocks.push_back(std::move(image));
    } else {
      ++*missing;
      absent->push_back(png);
      section.blocks.push_back(Note(Code(png) + Plain(" is missing: run ") +
                                    DirectoryHint("figures", study.directory) +
                                    Plain(" to draw it.")));
    }
    if (!row[caption].empty()) section.blocks.push_back(Paragraph(Plain(row[caption])));
    Inline files = study.Exists(pdf) ? Plain("PDF: ") + Link(pdf, UrlPath(pdf), true)
                                     : Plain("No PDF (") + Code(pdf) + Plain(" is absent)");
    // Data files drawn from, by the figure's stem (figures/<stem>.csv, .dat, ...).
    std::vector<std::string> data;
    for (const auto& entry : fs::directory_iterator(study.Path("figures"))) {
      const std::string name = entry.path().filename().string();
      const std::string extension = entry.path().extension().string();
      if (entry.path().stem().string() == row[stem] && extension != ".png" && extension != ".pdf") {
        data.push_back("figures/" + name);
      }
    }
    std::sort(data.begin(), data.end());
    for (const std::string& file : data)
      files = files + Plain("; data: ") + Link(file, UrlPath(file), true);
    section.blocks.push_back(Paragraph(files + Plain(".")));
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

Section ModelSection(const StudyFolder& study, const std::string& model, bool* calibrated,
                     std::vector<std::string>* absent) {
  Section section{"calibration-" + Slug(model), "Calibration: " + model, 3, {}};
  const std::string folder = "calibration/" + model;
  *calibrated = false;
  if (!study.Exists(folder)) {
    absent->push_back(folder + "/");
    section.blocks.push_back(Note(Plain("Not calibrated: ") + Code(folder + "/") +
                                  Plain(" is absent (run ") +
                                  DirectoryHint("calibrate", study.directory) + Plain(").")));
    return section;
  }
  const std::string parameters = folder + "/parameters.csv";
  if (study.Exists(parameters)) {
    *calibrated = true;
    const CsvTextTable table = CsvTextTable::ReadFile(study.Path(parameters));
    const size_t name = table.Column("parameter"), value = table.Column("value"),
                 error = table.Column("std_error"), low = table.Column("ci95_low"),
                 high = table.Column("ci95_high"), status = table.Column("status");
    Block block;
    block.type = Block::Type::kTable;
    block.header = {"parameter", "value", "standard error", "95 % interval", "status"};
    std::map<std::string, int> by_status;
    for (const auto& row : table.rows) {
      const std::optional<double> v = Number(row[value]), s = Number(row[error]),
                                  lo = Number(row[low]), hi = Number(row[high]);
      const std::string interval =
          lo && hi ? fmt::format("[{:.6g}, {:.6g}]", *lo, *hi) : std::string("—");
      block.rows.push_back({Cell{Code(row[name]), ""},
                            Cell{Plain(v ? fmt::format("{:.6g}", *v) : row[value]), "num"},
                            Cell{Plain(s                    ? fmt::format("{:.3g}", *s)
                                       : row[error].empty() ? "—"
                                                            : row[error]),
                                 "num"},
                            Cell{Plain(interval), "num"},
                            Cell{Plain(row[status]), StatusCss(row[status])}});
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
  } else {
    absent->push_back(parameters);
    section.blocks.push_back(Note(Code(parameters) + Plain(" is absent: no fitted parameters.")));
  }
  const std::string warnings = folder + "/warnings.txt";
  if (study.Exists(warnings)) {
    Block list;
    list.type = Block::Type::kList;
    const std::string text = ReadTextFile(study.Path(warnings));
    size_t at = 0;
    while (at < text.size()) {
      size_t end = text.find('\n', at);
      if (end == std::string::npos) end = text.size();
      std::string line = text.substr(at, end - at);
      at = end + 1;
      while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
      if (!line.empty()) list.items.push_back(Plain(line));
    }
    if (list.items.empty()) {
      section.blocks.push_back(Paragraph(Plain("No warnings.")));
    } else {
      section.blocks.push_back(Paragraph(Plain(fmt::format("{} warnings:", list.items.size()))));
      section.blocks.push_back(std::move(list));
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
                        "without a result, from ",
                        states.rows.size())) +
      Link("asymptotic_states.csv", "asymptotic_states.csv", true) + Plain(" (full precision; ") +
      Code("asymptotic_states.h5") +
      Plain(" with units). OCR and p_e* refer to the NCL named in ncl_reference.")));
  // Counts by kind and status.
  std::map<std::string, std::map<std::string, int>> counts;
  std::set<std::string> statuses;
  for (const auto& row : states.rows) {
    ++counts[row[kind]][row[status]];
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
  section.blocks.push_back(
      Paragraph(Plain("Each case links to the scene it ran; D<n> names the detector below.")));
  section.blocks.push_back(std::move(table));
  if (!detectors.empty()) {
    Block list;
    list.type = Block::Type::kList;
    for (size_t d = 0; d < detectors.size(); ++d) {
      list.items.push_back(Plain(fmt::format("D{}: ", d + 1)) + Plain(detectors[d]));
    }
    section.blocks.push_back(Paragraph(Plain("Detectors:")));
    section.blocks.push_back(std::move(list));
  }
  return section;
}

// The style of a comparison or verdict of the rate study (the stylesheet's
// status colours: green, amber, red).
std::string VerdictCss(const std::string& value) {
  if (value == "agree" || value == "rate_independent" || value == "stiffness_independent") {
    return "status-detected";
  }
  if (value == "differ" || value == "rate_dependent" || value == "stiffness_dependent") {
    return "status-invalid";
  }
  if (value == "undetermined") return "status-drifting";
  // The extension sweep (rate_extension*.csv).
  if (value == "asymptote" || value == "limit_d") return "status-detected";
  if (value == "liquefied") return "status-invalid";
  if (value == "not_reached") return "status-drifting";
  return "";
}

// A table of a CSV whose X_mean and X_ci95 columns become one column
// "X (mean ± 95 %)" (the mean to 4 significant digits, the half-width to
// 2); every other column as it is, `status`-like columns in `marked` styled.
Block MeanIntervalTable(const CsvTextTable& summary, const std::set<std::string>& marked = {}) {
  // Pair X_mean with X_ci95; every other column as it is.
  struct Column {
    std::string name;
    int value = -1, ci = -1;
  };
  std::vector<Column> columns;
  for (size_t c = 0; c < summary.columns.size(); ++c) {
    const std::string& name = summary.columns[c];
    const std::string suffix = "_mean";
    if (name.size() > suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      const std::string base = name.substr(0, name.size() - suffix.size());
      columns.push_back(
          {base + " (mean ± 95 %)", static_cast<int>(c), summary.Find(base + "_ci95")});
    } else if (name.size() > 5 && name.compare(name.size() - 5, 5, "_ci95") == 0 &&
               summary.Find(name.substr(0, name.size() - 5) + "_mean") >= 0) {
      continue;
    } else {
      columns.push_back({name, static_cast<int>(c), -1});
    }
  }
  Block table;
  table.type = Block::Type::kTable;
  for (const Column& column : columns) table.header.push_back(column.name);
  for (const auto& fields : summary.rows) {
    std::vector<Cell> row;
    for (const Column& column : columns) {
      if (column.ci < 0) {
        Cell cell = FieldCell(fields[column.value]);
        if (marked.count(column.name)) cell.css = VerdictCss(fields[column.value]);
        row.push_back(std::move(cell));
        continue;
      }
      const std::optional<double> mean = Number(fields[column.value]),
                                  ci = Number(fields[column.ci]);
      std::string text;
      if (mean) text = fmt::format("{:.4g}", *mean);
      if (mean && ci && std::isfinite(*ci)) text += fmt::format(" ± {:.2g}", *ci);
      row.push_back(Cell{Plain(text), "num"});
    }
    table.rows.push_back(std::move(row));
  }
  return table;
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
  Block table = MeanIntervalTable(summary);
  section.blocks.push_back(std::move(table));
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
        Plain(fmt::format("The calibrated models (Parameters, and figure rate (e)) were fitted to "
                          "the quasi-static states only: the {} rate cases at I* = {:g} and "
                          "the {} drained triaxial cases at the slowest axial rate of each "
                          "σ_r, E = {:g} MPa, from ",
                          selection->cases.size(), selection->inertial_number,
                          selection->drained_cases.size(), selection->youngs_modulus_mpa)) +
        Link(kQuasiStaticSelectionFile, UrlPath(kQuasiStaticSelectionFile), true) + Plain(".")));
  }
  struct Table {
    const char* file;
    const char* title;
    const char* description;
    bool folded;
  };
  const Table tables[] = {
      {kRateIndependenceFile, "Rate independence",
       "Per (E, ψ_ε, p_0): the two smallest I* compared in ln(1+e), ψ_σ and the position of the "
       "CSL (ln(1+e) of the ψ_ε = 90° line at the reference p); rate_independent when all "
       "three agree within the 95 % interval of their difference, rate_dependent when one "
       "differs, undetermined when an interval is missing (the reason says which).",
       false},
      {kRateQuasiStaticFile, "Quasi-static limits",
       "Per (E, ψ_ε, p_0) and quantity: the limit a of y = a + b·I(d_max) as I → 0, fitted "
       "through the states of the smallest I*; for ψ_ε = 90° the q_over_p rows are the "
       "quasi-static critical-state ratio M_0.",
       false},
      {kRateLinesFile, "Lines at each rate",
       "Per (E, ψ_ε, rate): ln(1+e) = N − λ ln(p / 1 kPa) through the states of every start "
       "(the CSL at 90°, the NEL beyond; at ψ_ε = 0° the NCL as the mean of the paths' own "
       "lines, whose states all lie at the stress cap) and its position at the reference p.",
       false},
      {kRateStiffnessFile, "Stiffness scaling",
       "Per other Young's modulus, ψ_ε, p_0 and rate: ψ_σ and the position of the CSL of that "
       "rate against those at the main modulus, with the stiffness numbers κ of both; "
       "stiffness_independent when both agree within the 95 % interval of the difference. "
       "Stiffness scaling shortens a run (steps per unit strain ∝ √(E/p)/I) where this holds.",
       false},
      {kRateDrainedCriticalFile, "Quasi-static critical state from drained tests",
       "Per E: drained triaxial compression (constant σ_r = p_0, constant axial rate) from the "
       "NC states, extrapolated as I → 0 at each σ_r and then combined: the critical-state "
       "ratio M (mean over σ_r), φ_c = asin(3M/(6+M)), the slope of M against ln p (zero "
       "within its interval: M does not depend on p) and the CSL through the limits. These "
       "are the study's quasi-static M, φ_c and CSL where the isochoric paths liquefy.",
       false},
      {kRateDrainedLimitFile, "Drained critical states as I → 0, per σ_r",
       "Per (E, σ_r): the limits of M, ln(1+e) and ln p of y = a + b·I(d_max) through the "
       "states of every axial rate, and the two slowest rates compared in M and ln(1+e).",
       false},
      {kRateDrainedFile, "Drained critical states per σ_r and rate",
       "Per (E, σ_r, axial rate): the asymptotic state's means over the replicates (q_over_p "
       "is M).",
       true},
      {kRateExtensionLimitFile, "How far the extension states go",
       "Per (E, rate, p_0): the sweep of ψ_ε from 90° upwards ends at the limit d, where the "
       "asymptotic σ_r/p is zero within its 95 % interval (ψ_ε(d) is the root of the "
       "least-squares line of σ_r/p against ψ_ε through the last steps, with its interval), or "
       "at the first ψ_ε at which most replicates liquefied (a gas: mechanical coordination "
       "below 3 or p below 0.5 kPa), or it reaches neither.",
       false},
      {kRateExtensionFile, "Extension sweep, step by step",
       "Per (E, rate, p_0, ψ_ε ≥ 90°): σ_r/p and ψ_σ of the asymptotic states, the replicates "
       "that liquefied, and the step's status.",
       true},
      {kRateSummaryFile, "Means per start and rate",
       "Per (E, ψ_ε, p_0, rate): the asymptotic state's means over the replicates.", true},
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
    for (const std::string& comment : table.comments) {
      section.blocks.push_back(Paragraph(Plain(comment)));
    }
    if (table.rows.empty()) {
      section.blocks.push_back(Paragraph(Plain("No rows.")));
      continue;
    }
    Block block =
        MeanIntervalTable(table, {"verdict", "ln_1_plus_e_agreement", "psi_sigma_deg_agreement",
                                  "csl_position_agreement", "m_agreement", "result", "status"});
    if (!t.folded) {
      section.blocks.push_back(std::move(block));
      continue;
    }
    Block details;
    details.type = Block::Type::kDetails;
    details.text = Plain(fmt::format("{} rows", table.rows.size()));
    details.children.push_back(std::move(block));
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
    section.blocks.push_back(TableOf(*table));
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
    section.blocks.push_back(std::move(table));
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
    section.blocks.push_back(std::move(table));
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

}  // namespace

std::string HtmlEscaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

ReportSummary WriteReport(const std::string& directory) {
  StudyFolder study;
  study.directory = directory;
  while (study.directory.size() > 1 && study.directory.back() == '/') study.directory.pop_back();
  if (!study.Exists("study.toml")) {
    throw InputError(study.Path("study.toml") +
                     ": not a study folder (no study.toml; run granasym study run first)");
  }
  study.record = ReadFlatRecord(study.Path("study.toml"));
  study.states = study.ReadCsv("asymptotic_states.csv");
  study.summary = study.ReadCsv("asymptotic_states_summary.csv");
  study.ncl = study.ReadCsv("ncl_fit.csv");
  study.convergence = study.ReadCsv("path_convergence.csv");
  const std::vector<CaseRow> cases = ReadCases(study.directory);

  ReportSummary summary;
  std::vector<std::string> absent;
  std::vector<Section> figures =
      FigureSections(study, &summary.figures, &summary.figures_missing, &absent);
  std::vector<Section> models;
  Section calibration{"calibration", "Calibration", 2, {}};
  calibration.blocks.push_back(Paragraph(
      Plain("The models fitted to the study's asymptotic states: values, standard errors, 95 % "
            "intervals and the status of each parameter (fitted, fixed, at_bound, undetermined), "
            "with the fit's warnings and summary.")));
  for (const char* model : kReportModels) {
    bool calibrated = false;
    models.push_back(ModelSection(study, model, &calibrated, &absent));
    summary.models_calibrated += calibrated ? 1 : 0;
  }
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
      Code(study.directory) + Plain(".");
  document.sections.push_back(OverviewSection(study, cases, summary.figures,
                                              summary.figures_missing, summary.models_calibrated));
  for (Section& section : figures) document.sections.push_back(std::move(section));
  document.sections.push_back(std::move(calibration));
  for (Section& section : models) document.sections.push_back(std::move(section));
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
  if (rate) document.sections.push_back(std::move(*rate));
  document.sections.push_back(RunTimesSection(study, cases));
  document.sections.push_back(ProvenanceSection(study));
  std::map<std::string, int> anchors;
  for (Section& section : document.sections) {
    const std::string slug = Slug(section.title);
    const int seen = anchors[slug]++;
    section.id = seen == 0 ? slug : slug + "-" + std::to_string(seen);
  }

  summary.states = study.states ? static_cast<int>(study.states->rows.size()) : 0;
  summary.cases = static_cast<int>(cases.size());
  summary.absent = study.absent;
  summary.html_path = study.Path("index.html");
  summary.markdown_path = study.Path("report.md");
  WriteTextFileAtomically(summary.html_path, RenderHtml(document));
  WriteTextFileAtomically(summary.markdown_path, RenderMarkdown(document));
  return summary;
}

std::string ReportSummary::Text() const {
  std::string text = fmt::format(
      "report: {} (and {})\n  {} figures ({} without their PNG), {} of 3 models calibrated, "
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
