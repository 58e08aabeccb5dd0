// Two study folders compared (`granasym study compare A B`): their asymptotic
// states matched by sample, case name and stage, each side's mean with its
// 95 % Student-t interval over the replicates, and the difference B − A of
// the means with its 95 % Welch interval; the NCL fits (N, λ*) and the
// critical states' M = q/p compared the same way; what did not match, with
// its status on each side.
//
// The difference of two means over n_a and n_b replicates with sample
// variances s_a², s_b²: d = m_b − m_a, interval d ± t_{0.975, ν} sqrt(s_a²/n_a +
// s_b²/n_b) with Welch–Satterthwaite's ν = (s_a²/n_a + s_b²/n_b)² /
// ((s_a²/n_a)²/(n_a − 1) + (s_b²/n_b)²/(n_b − 1)), rounded down (Welch 1947).
// One side with a single replicate has no variance of its own: the other
// side's s² stands for both (the replicates of one programme at one scale
// scatter alike), d ± t_{0.975, n − 1} s sqrt(1/n + 1); a single replicate on
// both sides gives no interval.
//
// Matching reads each folder once (ReadCompareStudy); CompareStudies is a
// pure function of what was read, so that tests build both sides by hand.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "analysis/estimate.h"
#include "common/enum_names.h"
#include "study/state_table.h"

namespace granasym::analysis {

using study::StateRow;
using study::TableKind;
using study::TableStatus;

// How the interval of a difference of means was formed.
enum class DifferenceInterval { kWelch, kVarianceOfA, kVarianceOfB, kNone };

}  // namespace granasym::analysis

template <>
struct granasym::EnumNames<granasym::analysis::DifferenceInterval> {
  using D = analysis::DifferenceInterval;
  static constexpr EnumEntry<D> kEntries[] = {
      {D::kWelch, "welch", "two replicates or more on both sides: Welch's interval"},
      {D::kVarianceOfA, "variance_of_a",
       "B has one replicate: the variance of A's replicates stands for both"},
      {D::kVarianceOfB, "variance_of_b",
       "A has one replicate: the variance of B's replicates stands for both"},
      {D::kNone, "none", "one replicate on both sides (or none on one): no interval"},
  };
};

namespace granasym::analysis {

// The difference B − A of two means with the half-width of its 95 % interval
// (NaN without one) and the interval's degrees of freedom.
struct MeanDifference {
  double difference = std::numeric_limits<double>::quiet_NaN();
  double half_width = std::numeric_limits<double>::quiet_NaN();
  double dof = 0;
  DifferenceInterval interval = DifferenceInterval::kNone;
  bool has_interval() const { return std::isfinite(half_width); }
  // Whether the 95 % interval of the difference leaves out zero.
  bool excludes_zero() const { return has_interval() && std::abs(difference) > half_width; }
};
// The difference of the means of `b` and `a` (the header's formulas); NaN
// difference when a side is empty.
MeanDifference DifferenceOfMeans(const std::vector<double>& a, const std::vector<double>& b);

// The quantities compared per matched state.
enum class StateQuantity { kPsiSigma, kLnVolume, kLnP, kStressRatio };
inline constexpr std::array<StateQuantity, 4> kStateQuantities = {
    StateQuantity::kPsiSigma, StateQuantity::kLnVolume, StateQuantity::kLnP,
    StateQuantity::kStressRatio};
// The column stem of a quantity ("psi_sigma_deg", "ln_1_plus_e", "ln_p", "q_over_p").
const char* QuantityColumn(StateQuantity quantity);
// How a text names it ("ψ_σ", "ln(1+e)", "ln p", "q/p").
const char* QuantitySymbol(StateQuantity quantity);
// Its value in a state row (ln p of p in kPa).
double QuantityOf(const StateRow& row, StateQuantity quantity);

// The samples a state can belong to within its study (analysis/figure_context.h's
// classes): the study's own (the contact friction and time step of its NCL
// case), another contact friction (Fig. 20's φ = 0), a finer time step
// (Sec. 5.2's Δt/5). States are matched only within one sample name.
inline constexpr char kSampleMain[] = "main";
inline constexpr char kSampleOtherFriction[] = "other_friction";
inline constexpr char kSampleFineStep[] = "fine_step";
// "the study's own sample", "the sample of other contact friction", ...
std::string SampleTitle(const std::string& sample);

// One study as the comparison reads it.
struct CompareStudy {
  std::string directory;
  std::string name;  // the folder's name
  std::string programme, scale;
  int count = 0, replicates = 0;
  // Its own sample: contact friction (rad), Young's modulus (MPa) and time
  // step (s) of the study's NCL case (NaN where unknown).
  double friction_rad = std::numeric_limits<double>::quiet_NaN();
  double youngs_modulus_mpa = std::numeric_limits<double>::quiet_NaN();
  double time_step_s = std::numeric_limits<double>::quiet_NaN();
  std::vector<StateRow> states;  // the state table (the matcher picks its rows)
  // The sample of each case, by (replicate, case name); a case not listed is "main".
  std::map<std::pair<int, std::string>, std::string> samples;
  // The NCL fits of each replicate (K >= 1) and NCL case: (K, case) → (N, λ*).
  std::map<std::pair<int, std::string>, std::pair<double, double>> ncl_fits;
  std::string study_ncl;  // the study's NCL case

  std::string SampleOf(const StateRow& row) const;
  // "paper, small: 3000 spheres × 3 replicates".
  std::string Describe() const;
  // "φ = 0.5 rad, E = 500 MPa, Δt = 2.1e-06 s".
  std::string DescribeSample() const;
};

// Reads a study folder (study.toml, the state table, the cases' samples and
// NCL fits); InputError naming the folder when it is not a study folder
// with a state table.
CompareStudy ReadCompareStudy(const std::string& directory);

// Renames the cases of `study` by `rule` "REGEX=REPLACEMENT" (ECMAScript;
// a case whose whole name the regex matches gets the replacement, with $1…
// for its groups; others keep their names), so that studies whose names
// differ can be matched (e.g. the rate study's "nc100_psi90_I0.001_E500"
// against the paper's "nc100_psi90": `(nc\d+_psi\d+)_I0\.001_E500=$1`).
// InputError for a malformed rule or regex, a rule that renames nothing, or
// two cases renamed to one name (or onto a case that keeps its name): their
// replicates would be pooled. `flag` names the option in messages.
void RenameCases(CompareStudy* study, const std::string& rule, const std::string& flag);

// What one side has of a matched state.
struct SideState {
  int replicates = 0;                   // usable rows (detected or drifting, p > 0)
  std::map<std::string, int> statuses;  // status → rows, of every replicate row
  std::array<Estimate, 4> mean;         // per kStateQuantities
  std::array<std::vector<double>, 4> values;
  Estimate psi_epsilon;  // ψ_ε (°), for the figures
  // "detected 2, drifting 1"; "absent" without rows.
  std::string StatusText() const;
};

// A state of both studies: one (sample, case name, stage) with usable rows on both sides.
struct StateMatch {
  std::string sample, case_name, stage;
  TableKind kind = TableKind::kNone;
  SideState a, b;
  std::array<MeanDifference, 4> difference;  // per kStateQuantities
  std::string note;  // what the reader must know (single replicates, a kind that differs)
  // "nc100_psi90" when the case name ends in its stage, else "ncl@p100".
  std::string Label() const;
};

// A (sample, case name, stage) without usable rows on one side or both.
struct UnmatchedState {
  std::string sample, case_name, stage;
  TableKind kind = TableKind::kNone;
  std::string where;  // "only in A", "only in B", "in both, usable in A only", "in both, usable in
                      // neither", ...
  std::string status_a, status_b;  // SideState::StatusText
};

// A line's parameter of both studies: N and λ* of an NCL case (over the
// replicates' fits), M of the critical states (over the detected csl states).
struct LineComparison {
  std::string sample, line, case_name, quantity;  // line "ncl" or "csl"
  std::vector<double> values_a, values_b;
  Estimate a, b;
  MeanDifference difference;
};

struct StudyComparison {
  CompareStudy a, b;  // without their rows (Strip)
  std::vector<StateMatch> matches;
  std::vector<UnmatchedState> unmatched;
  std::vector<LineComparison> lines;
  // The matched states of `kind` (kNone: all) whose `quantity` differs.
  int Differing(StateQuantity quantity, TableKind kind = TableKind::kNone) const;
  const LineComparison* Line(const std::string& sample, const std::string& line,
                             const std::string& quantity, const std::string& case_name = "") const;
  // The summary lines `study compare` prints.
  std::string Text() const;
};

// The comparison of `a` and `b`: matches in the order of sample (main
// first), kind, case name and stage; unmatched likewise.
StudyComparison CompareStudies(const CompareStudy& a, const CompareStudy& b);

// "+1.23 ± 0.45" with significant digits for `quantity`'s scale; "+1.23
// (no interval)" without one.
std::string WithInterval(double value, double half_width, int decimals, bool sign = false);

}  // namespace granasym::analysis
