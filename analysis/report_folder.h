// What the report (analysis/report.h) reads of a study folder, once: the
// study record, the state table's CSV files and the case folders with what
// became of each case. An absent file is listed, never an error; a
// malformed one is an InputError naming it. Internal to the analysis library.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/csv_table.h"
#include "study/case_record.h"

namespace granasym::analysis::report {

// The lines of a text, without their trailing spaces and carriage returns.
std::vector<std::string> TextLines(const std::string& text);

// `key = value` lines of a flat TOML record in file order (tables' keys
// prefixed by the table name), strings unquoted; the file is validated by
// the TOML parser first, so a malformed record is an InputError naming it.
using FlatRecord = std::vector<std::pair<std::string, std::string>>;
FlatRecord ReadFlatRecord(const std::string& path);
std::string Lookup(const FlatRecord& entries, const std::string& key,
                   const std::string& fallback = "");

// What the report knows of the study folder, read once.
struct StudyFolder {
  std::string directory;
  FlatRecord record;  // study.toml
  std::optional<CsvTextTable> states, summary, ncl, convergence;
  std::vector<std::string> absent;

  std::string Path(const std::string& name) const { return directory + "/" + name; }
  bool Exists(const std::string& name) const { return std::filesystem::exists(Path(name)); }

  std::optional<CsvTextTable> ReadCsv(const std::string& name) {
    if (!Exists(name)) {
      absent.push_back(name);
      return std::nullopt;
    }
    return CsvTextTable::ReadFile(Path(name));
  }
};
// study.toml (InputError when DIR is not a study folder) and the state
// table's CSV files of `directory`.
StudyFolder ReadStudyFolder(const std::string& directory);

// A case as the report shows it: its record and what became of it.
struct CaseRow {
  study::CaseRecord record;
  std::string status;  // the termination, or stale, running, not_run
  std::string message;
  int64_t steps = 0, own_steps = 0, particles = 0;
  double wall_seconds = 0;
  bool done = false;
};
std::vector<CaseRow> ReadCases(const std::string& directory);

}  // namespace granasym::analysis::report
