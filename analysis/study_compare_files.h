// What `granasym study compare A B --out DIR` writes (analysis/study_compare.h
// computes it): DIR/compare_states.csv (one row per matched state),
// DIR/compare_unmatched.csv, DIR/compare_ncl.csv (the NCL fits' N and λ*
// and the critical states' M), DIR/compare.md (the summary), the data and
// the list of its three figures under DIR/figures/ (plots/study/compare_*.gp),
// and DIR/compare.toml, which marks the folder as a comparison's so that a
// later comparison may write it again. Each CSV starts with '#' lines that
// name its columns.
#pragma once

#include <string>
#include <vector>

#include "analysis/figure_data.h"
#include "analysis/study_compare.h"

namespace granasym::analysis {

// The file that marks a comparison's folder.
inline constexpr char kCompareRecord[] = "compare.toml";

// `compare-<name of A>-vs-<name of B>`: the default output folder.
std::string DefaultCompareFolder(const std::string& a, const std::string& b);

// InputError unless `out` may take a comparison of the study folders `a`
// and `b`: A and B are different folders; `out` is neither of them nor lies
// inside either; it is absent, empty, or a folder that an earlier
// comparison wrote (it holds compare.toml).
void CheckCompareFolder(const std::string& out, const std::string& a, const std::string& b);

// DIR/compare_states.csv, compare_unmatched.csv, compare_ncl.csv and compare.toml.
void WriteComparisonTables(const std::string& out, const StudyComparison& comparison);

// The figures' data under DIR/figures/data/ and their specs: (a) ψ_σ
// against ψ_ε of the matched states, (b) ln(1+e) against p with each
// study's NCL, (c) the differences B − A of ψ_σ and ln(1+e) per state.
std::vector<FigureSpec> WriteComparisonFigureData(const std::string& out,
                                                  const StudyComparison& comparison);

// DIR/compare.md: the studies, the counts, the lines, the largest
// differences, the unmatched states and the figures (those drawn are linked).
void WriteComparisonSummary(const std::string& out, const StudyComparison& comparison,
                            const std::vector<FigureSpec>& figures);

}  // namespace granasym::analysis
