#include "analysis/report_tables.h"

#include <fmt/format.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace granasym::analysis::report {
namespace {

bool IsInteger(const std::string& text) {
  if (text.empty() || text.size() > 18) return false;
  size_t k = text[0] == '-' || text[0] == '+' ? 1 : 0;
  if (k == text.size()) return false;
  for (; k < text.size(); ++k) {
    if (!std::isdigit(static_cast<unsigned char>(text[k]))) return false;
  }
  return true;
}

}  // namespace

std::optional<double> Number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (*end != '\0' || errno == ERANGE) return std::nullopt;
  return value;
}

Cell FieldCell(const std::string& field) {
  if (IsInteger(field)) return Cell{Plain(field), "num"};
  if (const std::optional<double> value = Number(field)) {
    return Cell{Plain(fmt::format("{:.4g}", *value)), "num"};
  }
  return Cell{Plain(field), ""};
}

namespace {
// `prefix` and `value` with every character but letters, digits and '_' as '_'.
std::string CssClass(std::string css, const std::string& value) {
  for (char c : value) css += std::isalnum(static_cast<unsigned char>(c)) || c == '_' ? c : '_';
  return css;
}
}  // namespace

std::string StatusCss(const std::string& status) { return CssClass("status-", status); }

std::string FindingCss(const std::string& verdict) { return CssClass("verdict-", verdict); }

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

Block MeanIntervalTable(const CsvTextTable& summary, const std::set<std::string>& marked) {
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

Block Folded(Block table, const std::string& what) {
  if (table.rows.size() <= kUnfoldedRows) return table;
  Block details;
  details.type = Block::Type::kDetails;
  details.text = Plain(fmt::format("{} rows of {}", table.rows.size(), what));
  details.children.push_back(std::move(table));
  return details;
}

Inline DirectoryHint(const std::string& command, const std::string& directory) {
  return Code("granasym study " + command + " " + directory);
}

Block MissingTableNote(const std::string& name, const std::string& directory) {
  return Note(Code(name) + Plain(" is absent: the state table has not been written (run ") +
              Code("granasym study merge " + directory + " --out " + directory) +
              Plain(" after the cases ran)."));
}

}  // namespace granasym::analysis::report
