#include "common/csv_table.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/text_file.h"

namespace granasym {
namespace {

// One record of a table: its fields and the line it starts on.
struct Record {
  std::vector<std::string> fields;
  int line = 0;
};

// Splits `text` into records. Blank lines and lines starting with '#' (outside
// quotes, after leading blanks) are skipped; their text goes to `comments`.
std::vector<Record> SplitRecords(const std::string& text, const std::string& origin,
                                 CsvTextTable::Format format, std::vector<std::string>* comments) {
  const bool csv = format == CsvTextTable::Format::kCsv;
  const char delimiter = csv ? ',' : '\t';
  std::vector<Record> records;
  size_t at = 0;
  int line = 1;
  while (at < text.size()) {
    // A blank or comment line.
    const size_t end_of_line = std::min(text.find('\n', at), text.size());
    const std::string trimmed = Trimmed(text.substr(at, end_of_line - at));
    if (trimmed.empty() || trimmed[0] == '#') {
      if (!trimmed.empty() && comments) comments->push_back(Trimmed(trimmed.substr(1)));
      at = end_of_line + 1;
      ++line;
      continue;
    }
    Record record;
    record.line = line;
    std::string field;
    bool quoted = false;  // the current field was quoted (kept as written, not trimmed)
    auto finish_field = [&] {
      record.fields.push_back(quoted ? field : Trimmed(field));
      field.clear();
      quoted = false;
    };
    while (true) {
      if (at >= text.size() || text[at] == '\n') {
        finish_field();
        if (at < text.size()) ++at;
        ++line;
        break;
      }
      const char c = text[at];
      if (c == delimiter) {
        finish_field();
        ++at;
        continue;
      }
      if (csv && c == '"' && Trimmed(field).empty() && !quoted) {
        const int opened = line;
        ++at;
        field.clear();
        while (true) {
          if (at >= text.size()) {
            throw InputError(origin + ": line " + std::to_string(opened) +
                             ": a quoted field is not closed (a '\"' is missing)");
          }
          if (text[at] == '"') {
            if (at + 1 < text.size() && text[at + 1] == '"') {
              field += '"';
              at += 2;
              continue;
            }
            ++at;
            break;
          }
          if (text[at] == '\n') ++line;
          field += text[at++];
        }
        quoted = true;
        // Only blanks may follow the closing quote before the delimiter.
        while (at < text.size() && (text[at] == ' ' || text[at] == '\t' || text[at] == '\r')) ++at;
        if (at < text.size() && text[at] != delimiter && text[at] != '\n') {
          throw InputError(origin + ": line " + std::to_string(line) +
                           ": text after the closing quote of a field ('" +
                           text.substr(at, std::min<size_t>(20, text.size() - at)) + "')");
        }
        continue;
      }
      field += c;
      ++at;
    }
    records.push_back(std::move(record));
  }
  return records;
}

std::string ListColumns(const std::vector<std::string>& columns) {
  std::string available;
  for (const std::string& column : columns) available += (available.empty() ? "" : ", ") + column;
  return available;
}

// The header's names: none empty, none twice.
void CheckHeader(const std::vector<std::string>& columns, int line, const std::string& origin) {
  for (size_t c = 0; c < columns.size(); ++c) {
    if (columns[c].empty()) {
      throw InputError(origin + ": line " + std::to_string(line) + ": header column " +
                       std::to_string(c + 1) + " has no name (header: " + ListColumns(columns) +
                       "); every column needs a name");
    }
    for (size_t earlier = 0; earlier < c; ++earlier) {
      if (columns[earlier] == columns[c]) {
        throw InputError(origin + ": line " + std::to_string(line) + ": column '" + columns[c] +
                         "' appears twice in the header (columns " + std::to_string(earlier + 1) +
                         " and " + std::to_string(c + 1) + "); every column name must be unique");
      }
    }
  }
}

std::string ReadWholeFile(const std::string& path, const char* what) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(std::string("cannot open ") + what + " '" + path + "'");
  std::stringstream buffer;
  buffer << file.rdbuf();
  return buffer.str();
}

}  // namespace

CsvTable CsvTable::Parse(const std::string& text, const std::string& origin) {
  CsvTable table;
  table.origin = origin;
  const std::vector<Record> records =
      SplitRecords(text, origin, CsvTextTable::Format::kCsv, nullptr);
  if (records.empty()) throw InputError(origin + ": no header row (the file is empty)");
  table.columns = records.front().fields;
  table.header_line = records.front().line;
  CheckHeader(table.columns, table.header_line, origin);
  for (size_t r = 1; r < records.size(); ++r) {
    const std::vector<std::string>& fields = records[r].fields;
    const int line_number = records[r].line;
    if (fields.size() != table.columns.size()) {
      throw InputError(origin + ": line " + std::to_string(line_number) + " has " +
                       std::to_string(fields.size()) + " fields, but the header has " +
                       std::to_string(table.columns.size()) + " columns (" +
                       ListColumns(table.columns) + ")");
    }
    std::vector<double> row;
    for (size_t c = 0; c < fields.size(); ++c) {
      const char* begin = fields[c].c_str();
      char* end = nullptr;
      // An overflow reads as inf; an underflow as its rounded value, so that
      // what WriteCsv writes (17 digits, subnormal numbers too) reads back.
      const double value = std::strtod(begin, &end);
      if (fields[c].empty() || *end != '\0' || !std::isfinite(value)) {
        throw InputError(origin + ": line " + std::to_string(line_number) + ", column '" +
                         table.columns[c] + "': '" + fields[c] + "' is not a finite number");
      }
      row.push_back(value);
    }
    table.rows.push_back(row);
    table.line_numbers.push_back(line_number);
  }
  return table;
}

CsvTable CsvTable::ReadFile(const std::string& path) {
  return Parse(ReadWholeFile(path, "CSV file"), path);
}

size_t CsvTable::Column(const std::string& name) const {
  const int c = Find(name);
  if (c < 0) {
    throw InputError(origin + ": missing column '" + name +
                     "' (columns present: " + ListColumns(columns) + ")");
  }
  return static_cast<size_t>(c);
}

size_t CsvTable::Column(const std::string& name, const std::string& former_name) const {
  const int former = Find(former_name);
  return Find(name) < 0 && former >= 0 ? static_cast<size_t>(former) : Column(name);
}

int CsvTable::Find(const std::string& name) const {
  for (size_t c = 0; c < columns.size(); ++c) {
    if (columns[c] == name) return static_cast<int>(c);
  }
  return -1;
}

void CsvTable::RequireOnlyColumns(const std::vector<std::string>& known) const {
  for (size_t c = 0; c < columns.size(); ++c) {
    if (std::find(known.begin(), known.end(), columns[c]) == known.end()) {
      throw InputError(origin + ": line " + std::to_string(header_line) + ": unknown column '" +
                       columns[c] + "' (column " + std::to_string(c + 1) +
                       "; known columns: " + ListColumns(known) + ")");
    }
  }
}

std::vector<double> CsvTable::ColumnValues(const std::string& name) const {
  const size_t c = Column(name);
  std::vector<double> values;
  values.reserve(rows.size());
  for (const auto& row : rows) values.push_back(row[c]);
  return values;
}

CsvTextTable CsvTextTable::Parse(const std::string& text, const std::string& origin,
                                 Format format) {
  CsvTextTable table;
  table.origin = origin;
  std::vector<Record> records = SplitRecords(text, origin, format, &table.comments);
  if (records.empty()) throw InputError(origin + ": no header row (the file is empty)");
  table.columns = std::move(records.front().fields);
  table.header_line = records.front().line;
  CheckHeader(table.columns, table.header_line, origin);
  for (size_t r = 1; r < records.size(); ++r) {
    if (records[r].fields.size() != table.columns.size()) {
      throw InputError(origin + ": line " + std::to_string(records[r].line) + " has " +
                       std::to_string(records[r].fields.size()) + " fields, but the header has " +
                       std::to_string(table.columns.size()) + " columns (" +
                       ListColumns(table.columns) + ")");
    }
    table.rows.push_back(std::move(records[r].fields));
    table.line_numbers.push_back(records[r].line);
  }
  return table;
}

CsvTextTable CsvTextTable::ReadFile(const std::string& path, Format format) {
  return Parse(ReadWholeFile(path, format == Format::kCsv ? "CSV file" : "TSV file"), path, format);
}

size_t CsvTextTable::Column(const std::string& name) const {
  const int c = Find(name);
  if (c < 0) {
    throw InputError(origin + ": missing column '" + name +
                     "' (columns present: " + ListColumns(columns) + ")");
  }
  return static_cast<size_t>(c);
}

int CsvTextTable::Find(const std::string& name) const {
  for (size_t c = 0; c < columns.size(); ++c) {
    if (columns[c] == name) return static_cast<int>(c);
  }
  return -1;
}

void WriteCsv(const std::string& path, const std::vector<std::string>& columns,
              const std::vector<std::vector<double>>& column_values) {
  GRANASYM_CHECK(columns.size() == column_values.size());
  const size_t rows = column_values.empty() ? 0 : column_values[0].size();
  for (const std::vector<double>& values : column_values) {
    GRANASYM_CHECK(values.size() == rows)
        << path << ": columns of " << values.size() << " and " << rows << " rows";
  }
  std::ostringstream out;
  out.precision(17);
  for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
  out << "\n";
  for (size_t r = 0; r < rows; ++r) {
    for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << column_values[c][r];
    out << "\n";
  }
  WriteTextFileAtomically(path, out.str());
}

}  // namespace granasym
