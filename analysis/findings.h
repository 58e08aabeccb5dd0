// The paper's claims, each judged from a study's own results: a finding
// names the claim and where the paper makes it, says `reproduced`,
// `partly`, `not_reproduced` or `not_tested`, and gives the numbers that
// decide it and the rule that turned them into the verdict. Every study
// writes DIR/findings.csv with its state table; the report opens with it,
// and docs/REPRODUCTION.md sets the paper-scale, small-scale and rate-study
// verdicts side by side.
//
// The findings read the state table's per-replicate rows of the study's own
// material (rows whose OCR refers to the study's NCL; the φ = 0 and Δt/5
// samples only where a finding compares them), the cases' paths and the
// NCL fits (analysis/figure_context.h). They never read the ensemble or
// joined rows as replicates.
#pragma once

#include <string>
#include <vector>

#include "common/enum_names.h"

namespace granasym::analysis {

enum class Verdict { kReproduced, kPartly, kNotReproduced, kNotTested };

}  // namespace granasym::analysis

template <>
struct granasym::EnumNames<granasym::analysis::Verdict> {
  using V = analysis::Verdict;
  static constexpr EnumEntry<V> kEntries[] = {
      {V::kReproduced, "reproduced", "the study's numbers meet the rule of the claim"},
      {V::kPartly, "partly", "some of the claim holds, some does not or is undetermined"},
      {V::kNotReproduced, "not_reproduced", "the study's numbers contradict the claim"},
      {V::kNotTested, "not_tested", "the study has not the cases or states the claim needs"},
  };
};

namespace granasym::analysis {

struct Finding {
  std::string id;      // e.g. "ncl_linear"
  std::string source;  // the paper's figure and section, e.g. "Fig. 9, Sec. 4.1"
  std::string claim;   // what the paper says
  Verdict verdict = Verdict::kNotTested;
  std::string numbers;  // what decides it, with intervals
  std::string rule;     // how the numbers give the verdict
};

namespace figures {
struct Context;
}

// The findings of a study folder as read by the figures (ReadContext).
std::vector<Finding> ComputeFindings(const figures::Context& context);

// DIR/findings.csv: id, source, claim, verdict, numbers, rule.
constexpr char kFindingsFile[] = "findings.csv";
void WriteFindings(const std::string& directory, const std::vector<Finding>& findings);
// Computes and writes the findings of a study folder; returns them.
std::vector<Finding> WriteStudyFindings(const std::string& directory);
// "findings: 9 reproduced, 3 partly, 1 not_reproduced, 3 not_tested".
std::string FindingsLine(const std::vector<Finding>& findings);

}  // namespace granasym::analysis
