// Numeric CSV tables with a header row (GSD tables, calibration data).
//
// Lines starting with '#' and blank lines are skipped; the first other line is
// the header. Every error names the file, the line and the offending text.
// No Debian 12 package offers a small, maintained C++ CSV reader, and the
// format needed here (numbers, a header, comments) is a few dozen lines.
#pragma once

#include <string>
#include <vector>

namespace granasym {

struct CsvTable {
  std::string origin;                     // file name for messages
  std::vector<std::string> columns;       // header names
  std::vector<std::vector<double>> rows;  // rows x columns
  std::vector<int> line_numbers;          // source line of each row (1-based)

  static CsvTable ReadFile(const std::string& path);
  static CsvTable Parse(const std::string& text, const std::string& origin);
  // Index of a column; InputError listing the available columns if missing.
  size_t Column(const std::string& name) const;
  std::vector<double> ColumnValues(const std::string& name) const;
};

// Writes a table with a header row; numbers in full precision.
void WriteCsv(const std::string& path, const std::vector<std::string>& columns,
              const std::vector<std::vector<double>>& column_values);

}  // namespace granasym
