// CSV tables with a header row: numeric ones (GSD tables, calibration data)
// and ones of text fields read by column name (the study's state table and
// the other tables a study report shows).
//
// Lines starting with '#' and blank lines are skipped; the first other line is
// the header. Fields may be quoted as in RFC 4180 ("a, b", "say ""x""", line
// breaks inside quotes); unquoted fields are trimmed. No Debian 12 package
// offers a small, maintained C++ CSV reader, and the format needed here is a
// few dozen lines.
//
// One rule for every table, each break an InputError naming the file and the
// line:
//  - a header name may not be empty or appear twice (the message gives both
//    column positions, 1-based);
//  - every row has as many fields as the header;
//  - in a numeric table every field is a finite number (the message names the
//    line, the column and the text);
//  - numeric readers reject the columns they do not know (RequireOnlyColumns,
//    which lists the known ones) rather than ignore them: a misspelt column is
//    an error, never a silently unused one.
#pragma once

#include <string>
#include <vector>

namespace granasym {

struct CsvTable {
  std::string origin;                     // file name for messages
  std::vector<std::string> columns;       // header names
  std::vector<std::vector<double>> rows;  // rows x columns
  std::vector<int> line_numbers;          // source line of each row (1-based)
  int header_line = 0;                    // source line of the header (1-based)

  static CsvTable ReadFile(const std::string& path);
  static CsvTable Parse(const std::string& text, const std::string& origin);
  // Index of a column; InputError listing the available columns if missing.
  size_t Column(const std::string& name) const;
  // Index of `name`, else of `former_name`, its spelling in files written
  // before a renaming (common/quantity_names.h); InputError naming `name` if
  // neither is present.
  size_t Column(const std::string& name, const std::string& former_name) const;
  // Index of a column, or -1.
  int Find(const std::string& name) const;
  std::vector<double> ColumnValues(const std::string& name) const;
  // InputError naming the first column that is not in `known` (its name and
  // position) and listing the known ones.
  void RequireOnlyColumns(const std::vector<std::string>& known) const;
};

// A table of text fields: CSV as above, or tab-separated (TSV: fields split at
// tabs, no quoting, so a '"' is an ordinary character).
struct CsvTextTable {
  enum class Format { kCsv, kTsv };
  std::string origin;                          // file name for messages
  std::vector<std::string> columns;            // header names
  std::vector<std::vector<std::string>> rows;  // rows x columns
  std::vector<int> line_numbers;               // source line where each row starts (1-based)
  int header_line = 0;                         // source line of the header (1-based)
  std::vector<std::string> comments;           // '#' lines, without the '#' and leading blanks

  static CsvTextTable ReadFile(const std::string& path, Format format = Format::kCsv);
  static CsvTextTable Parse(const std::string& text, const std::string& origin,
                            Format format = Format::kCsv);
  // Index of a column; InputError listing the available columns if missing.
  size_t Column(const std::string& name) const;
  // Index of a column, or -1.
  int Find(const std::string& name) const;
};

// Writes a table with a header row; numbers in full precision
// (WriteTextFileAtomically: FileError when it cannot).
void WriteCsv(const std::string& path, const std::vector<std::string>& columns,
              const std::vector<std::vector<double>>& column_values);

}  // namespace granasym
