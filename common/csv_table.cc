#include "common/csv_table.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "common/error.h"

namespace granasym {
namespace {

std::string Trim(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const size_t last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> SplitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(Trim(field));
  if (!line.empty() && line.back() == ',') fields.push_back("");
  return fields;
}

}  // namespace

CsvTable CsvTable::Parse(const std::string& text, const std::string& origin) {
  CsvTable table;
  table.origin = origin;
  std::istringstream stream(text);
  std::string line;
  int line_number = 0;
  bool have_header = false;
  while (std::getline(stream, line)) {
    ++line_number;
    const std::string trimmed = Trim(line);
    if (trimmed.empty() || trimmed[0] == '#') continue;
    std::vector<std::string> fields = SplitFields(trimmed);
    if (!have_header) {
      table.columns = fields;
      have_header = true;
      continue;
    }
    if (fields.size() != table.columns.size()) {
      throw InputError(origin + ": line " + std::to_string(line_number) + " has " +
                       std::to_string(fields.size()) + " fields, but the header has " +
                       std::to_string(table.columns.size()) + " columns");
    }
    std::vector<double> row;
    for (size_t c = 0; c < fields.size(); ++c) {
      const char* begin = fields[c].c_str();
      char* end = nullptr;
      errno = 0;
      const double value = std::strtod(begin, &end);
      if (fields[c].empty() || *end != '\0' || errno == ERANGE || !std::isfinite(value)) {
        throw InputError(origin + ": line " + std::to_string(line_number) + ", column '" +
                         table.columns[c] + "': '" + fields[c] + "' is not a finite number");
      }
      row.push_back(value);
    }
    table.rows.push_back(row);
    table.line_numbers.push_back(line_number);
  }
  if (!have_header) throw InputError(origin + ": no header row (the file is empty)");
  return table;
}

CsvTable CsvTable::ReadFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError("cannot open CSV file '" + path + "'");
  std::stringstream buffer;
  buffer << file.rdbuf();
  return Parse(buffer.str(), path);
}

size_t CsvTable::Column(const std::string& name) const {
  for (size_t c = 0; c < columns.size(); ++c) {
    if (columns[c] == name) return c;
  }
  std::string available;
  for (const std::string& column : columns) available += (available.empty() ? "" : ", ") + column;
  throw InputError(origin + ": missing column '" + name + "' (columns present: " + available + ")");
}

std::vector<double> CsvTable::ColumnValues(const std::string& name) const {
  const size_t c = Column(name);
  std::vector<double> values;
  values.reserve(rows.size());
  for (const auto& row : rows) values.push_back(row[c]);
  return values;
}

void WriteCsv(const std::string& path, const std::vector<std::string>& columns,
              const std::vector<std::vector<double>>& column_values) {
  GRANASYM_CHECK(columns.size() == column_values.size());
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary);
    if (!out) throw RuntimeError("cannot write CSV file '" + temporary + "'");
    out.precision(17);
    for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
    out << "\n";
    const size_t rows = column_values.empty() ? 0 : column_values[0].size();
    for (size_t r = 0; r < rows; ++r) {
      for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << column_values[c][r];
      out << "\n";
    }
    if (!out) throw RuntimeError("error while writing CSV file '" + temporary + "'");
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    throw RuntimeError("cannot rename '" + temporary + "' to '" + path + "'");
  }
}

}  // namespace granasym
