// What a case of a study is: DIR/cases/r<K>/<name>/case.toml, written by the
// runner and read by everything that reads a study folder (the state table,
// the folder commands, the analyses). One struct, one writer, one reader:
// no other code spells the file's keys.
//
//   # what this case is (written by granasym study run)
//   id = "r1/nc100_psi90"
//   name = "nc100_psi90"
//   replicate = 1
//   key = "…"                # SHA-256 of what the case computes (study/plan.h)
//   parent = "r1/ncl"        # "" when the case starts from the sample
//   parent_stage = "p100"    # "" when it starts from the parent's final state
//   run = "nc{p}_psi{psi}"   # the [[run]] name template it came from
//   figures = "10, 16, 18"   # what it serves (FigureSet)
//   programme = "paper"
//   scale = "small"
//   threads = 1
//   program_version = "…"
//   [variables]              # the `vary` values that made it, as text
//   p = "100"
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "study/study_folder.h"

namespace granasym::study {

// What a case or model run serves (a programme's `figures` key): figures of
// the paper (1–22), sections of the paper ("Sec. 5.2") and the rate study
// ("rate"), comma-separated. Parsed once, where it is read, and checked: an
// unknown entry or a repeated one is an InputError that names the file, the
// key, the value and what is valid.
class FigureSet {
 public:
  // The paper's figures and sections (../shared/paper): what an entry may name.
  static constexpr int kPaperFigures = 22;
  static const std::vector<std::string>& PaperSections();  // "1", "2.1", ..., "6"
  static constexpr char kRate[] = "rate";

  FigureSet() = default;
  // `origin` and `key` name where the text comes from in messages.
  static FigureSet Parse(const std::string& text, const std::string& origin,
                         const std::string& key);

  bool empty() const { return entries_.empty(); }
  // The entries as written, in order: "8", "Sec. 5.2", "rate".
  const std::vector<std::string>& entries() const { return entries_; }
  bool Contains(const std::string& entry) const;     // an entry as written: "19", "Sec. 5.2"
  bool HasFigure(int number) const;                  // figure 1–22
  bool HasSection(const std::string& number) const;  // "5.2"
  bool ServesRateStudy() const;
  // The figure numbers named, in the order written.
  std::vector<int> Figures() const;
  // The canonical text: the entries joined by ", " (what case.toml and the
  // state table's `figures` column hold).
  std::string Text() const;

  bool operator==(const FigureSet& other) const { return entries_ == other.entries_; }

 private:
  std::vector<std::string> entries_;
};

// What became of a case: its done.toml and whether result.h5 is the
// complete result for the record's key.
struct CaseDone {
  std::optional<DoneRecord> done;  // whatever key it was written for
  bool current = false;            // done.toml is for the record's key
  bool finished = false;           // current, and result.h5 is the run done.toml records
  std::string mismatch;            // why a current done.toml's result.h5 is not the result
};

struct CaseRecord {
  std::string id;  // "r<K>/<name>"
  std::string name;
  int replicate = 1;
  std::string key;
  std::string parent;        // the parent case's id; "" for the sample
  std::string parent_stage;  // a stage of the parent; "" for its final state
  std::string run;           // the [[run]] name template
  FigureSet figures;
  std::string programme, scale;
  int threads = 1;
  std::string program_version;
  std::map<std::string, std::string> variables;

  // The folder it was read from (not written).
  std::string directory;
  // The parent case's name, without its replicate ("" for the sample).
  std::string parent_name() const;

  static constexpr char kFileName[] = "case.toml";
  std::string Text() const;
  // Writes DIRECTORY/case.toml unless it holds this text already.
  void Write(const std::string& directory) const;
  // Reads CASE_DIRECTORY/case.toml; a missing or malformed file is an
  // InputError naming it and the key.
  static CaseRecord Read(const std::string& case_directory);

  // DIRECTORY/done.toml and result.h5, read now.
  CaseDone Done() const;
  std::string result_path() const { return directory + "/result.h5"; }
};

// DIR/plan.tsv: the cases of the programme the folder was last run with
// (`study run` writes it; `study merge` copies it), one line per case: id,
// name, replicate, parent, parent_stage, run, figures. What the state table,
// `study status` and `study merge` hold the case folders to: a case removed
// from the programme keeps its folder (its cache) but is no longer part of
// the study, and a planned case without a folder is a case with no result.
inline constexpr char kPlanFileName[] = "plan.tsv";
std::string PlanFileText(const std::vector<CaseRecord>& cases);
// The planned cases, each with its folder (DIR/cases/<id>) and no key or
// variables (case.toml holds them); nullopt without a plan.tsv (a folder of
// an older version: every case folder is the study's). A malformed line is
// an InputError naming the file and the line.
std::optional<std::vector<CaseRecord>> ReadPlannedCases(const std::string& study_directory);

// The records of the study's cases, in the order of their folders: with a
// plan.tsv, each planned case (its case.toml when its folder has one, else
// the plan's line); without, every case folder with a case.toml.
std::vector<CaseRecord> ReadCaseRecords(const std::string& study_directory);

}  // namespace granasym::study
