// `granasym study compare A B [--out DIR]`: the asymptotic states of two
// study folders matched by sample, case name and stage, with the
// differences B − A and their 95 % intervals (analysis/study_compare.h),
// written to DIR (default compare-<A>-vs-<B> in the current folder):
// compare.md, compare_states.csv, compare_unmatched.csv, compare_ncl.csv
// and three figures under DIR/figures/ (analysis/study_compare_files.h).
// A and B are only read. Exit status 0 when the comparison was written
// (differences are results), 2 for a folder that is no study, A = B or an
// --out that is refused, 4 when a figure could not be drawn.
#include "app/study_compare_command.h"

#include <cstdio>
#include <string>
#include <vector>

#include "analysis/study_compare.h"
#include "analysis/study_compare_files.h"
#include "app/figure_drawing.h"
#include "common/stopwatch.h"

namespace granasym {
namespace {

struct CompareFlags {
  std::string a, b, out;
  std::vector<std::string> rename_a, rename_b;
  bool data_only = false;
};

void RunCompare(const CompareFlags& flags) {
  const Stopwatch clock;
  const std::string out =
      flags.out.empty() ? analysis::DefaultCompareFolder(flags.a, flags.b) : flags.out;
  analysis::CheckCompareFolder(out, flags.a, flags.b);
  analysis::CompareStudy a = analysis::ReadCompareStudy(flags.a);
  analysis::CompareStudy b = analysis::ReadCompareStudy(flags.b);
  for (const std::string& rule : flags.rename_a) analysis::RenameCases(&a, rule, "--rename-a");
  for (const std::string& rule : flags.rename_b) analysis::RenameCases(&b, rule, "--rename-b");
  const analysis::StudyComparison comparison = analysis::CompareStudies(a, b);
  analysis::WriteComparisonTables(out, comparison);
  std::vector<analysis::FigureSpec> figures = analysis::WriteComparisonFigureData(out, comparison);
  const int failed = DrawFigures(out, &figures, flags.data_only);
  analysis::WriteFigureIndex(out, figures);
  analysis::WriteComparisonSummary(out, comparison, figures);
  std::printf("%s", comparison.Text().c_str());
  std::printf(
      "written in %.1f s: %s/compare.md, compare_states.csv, compare_unmatched.csv, "
      "compare_ncl.csv, figures/index.tsv\n",
      clock.Seconds(), out.c_str());
  if (failed > 0) throw CLI::RuntimeError(4);
}

}  // namespace

void RegisterStudyCompareCommand(CLI::App* study) {
  static CompareFlags flags;
  CLI::App* compare = study->add_subcommand(
      "compare",
      "compare two study folders: their asymptotic states matched by case and stage, the "
      "differences B - A with 95 % intervals, the NCL and CSL, figures with both overlaid");
  compare->add_option("a", flags.a, "study folder A")->required()->check(CLI::ExistingDirectory);
  compare->add_option("b", flags.b, "study folder B")->required()->check(CLI::ExistingDirectory);
  compare->add_option("--out", flags.out,
                      "output folder (default: compare-<A>-vs-<B> in the current folder); new, "
                      "empty, or an earlier comparison's, never inside A or B");
  compare->add_option("--rename-a", flags.rename_a,
                      "rename A's cases before matching: REGEX=REPLACEMENT on the whole case "
                      "name (ECMAScript, $1 for groups; repeat)");
  compare->add_option("--rename-b", flags.rename_b,
                      "rename B's cases before matching, e.g. "
                      "'(nc\\d+_psi\\d+)_I0\\.001_E500=$1' for the rate study against the "
                      "paper's names");
  compare->add_flag("--data-only", flags.data_only,
                    "write the tables, the summary and the figures' data, draw nothing");
  compare->callback([] { RunCompare(flags); });
}

}  // namespace granasym
