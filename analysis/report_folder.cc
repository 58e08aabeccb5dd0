#include "analysis/report_folder.h"

#include <algorithm>
#include <map>

#include "common/config.h"
#include "common/error.h"
#include "common/text_file.h"
#include "study/study_folder.h"

namespace granasym::analysis::report {
namespace fs = std::filesystem;
using study::CaseRecord;
using study::DoneRecord;
using study::OwnSteps;
using study::ReadCaseRecords;
using study::ReadDone;

std::vector<std::string> TextLines(const std::string& text) {
  std::vector<std::string> lines;
  size_t at = 0;
  while (at < text.size()) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(at, end - at);
    at = end + 1;
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    lines.push_back(std::move(line));
  }
  return lines;
}

FlatRecord ReadFlatRecord(const std::string& path) {
  ConfigTable::ParseFile(path);
  FlatRecord entries;
  std::string table;
  for (std::string line : TextLines(ReadTextFile(path))) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    line = line.substr(first);
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

std::string Lookup(const FlatRecord& entries, const std::string& key, const std::string& fallback) {
  for (const auto& [name, value] : entries) {
    if (name == key) return value;
  }
  return fallback;
}

StudyFolder ReadStudyFolder(const std::string& directory) {
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
  return study;
}

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

}  // namespace granasym::analysis::report
