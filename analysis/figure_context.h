// What the figure families of analysis/figure_data.h share: the study
// folder as the figures read it (`Context`: the cases with replicate 1's
// paths, the state table, the NCLs, the calibrated models), the data files
// they write (`BlockFile`), the entries of figures/index.tsv (`Spec`,
// `NotDrawn`, `Set`) and the legends' labels. Internal to the analysis
// library: analysis/figure_families.h lists the families.
#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "analysis/figure_data.h"
#include "dem/run_record.h"
#include "study/case_record.h"

namespace granasym::analysis::figures {

using study::FigureSet;
using study::TableKind;
using study::TableStatus;

// ---------------------------------------------------------------- data files

// A data file of blocks: a header (column names, then the legend title) and rows.
class BlockFile {
 public:
  explicit BlockFile(std::vector<std::string> columns) : columns_(std::move(columns)) {}
  // Adds a block; rows with a non-finite value are dropped; an empty block
  // is not written (gnuplot warns about blocks without points).
  void Add(const std::string& title, const std::vector<std::vector<double>>& rows);
  // A block whose rows end with a text column (the columns' last name): the
  // hover label of each point (`with labels hypertext` in the SVG). Rows with
  // a non-finite value are dropped with their label.
  void AddLabelled(const std::string& title, const std::vector<std::vector<double>>& rows,
                   const std::vector<std::string>& labels);
  int blocks() const { return blocks_; }
  // The blocks' titles as gnuplot words ("a b" "c"), for legend entries of
  // blocks drawn with `pt variable` (whose own key sample is a dot).
  const std::string& titles() const { return titles_; }
  void Write(const std::string& path) const;

 private:
  std::vector<std::string> columns_;
  std::string text_, titles_;
  int blocks_ = 0;
};

// The rows of equally long columns.
std::vector<std::vector<double>> Rows(std::initializer_list<const std::vector<double>*> columns);

// A number for a legend: 3 significant digits, no exponent for kPa values.
std::string Short(double v);

// Titles as gnuplot words, each quoted: "\"a b\" \"c\"" (read with word()).
std::string QuotedWords(const std::vector<std::string>& titles);

// The rows (p, ln(1+e)) of the line ln(1+e) = n − λ ln(p / 1 kPa), evenly in
// ln p from p_lo to p_hi over `intervals` steps.
std::vector<std::vector<double>> LineRows(double n, double lambda, double p_lo, double p_hi,
                                          int intervals);

// The range of an axis that holds every point of a figure (non-finite
// values, and on a log axis non-positive ones, are left out), padded so that
// no point sits on the frame:
//  - Padded (the rate study's figures): 8 % each side, in log for a log axis
//    and then at least a decade; a single linear value ±1 (gnuplot warns
//    about an empty autoscaled range, which `study figures` treats as an
//    error);
//  - Linear and Logarithmic (the paper's figures): `margin` of the span each
//    side, the span at least `min_span` (0: 1e-3 of the larger magnitude, and
//    1e-3) or 0.2 decades.
struct AxisRange {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  bool log = false;
  void Add(double v) {
    if (!std::isfinite(v) || (log && !(v > 0))) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  void Add(double v, double half_width) {
    Add(v);
    if (std::isfinite(half_width)) {
      Add(v - half_width);
      Add(v + half_width);
    }
  }
  bool empty() const { return !(lo <= hi); }
  std::pair<double, double> Padded() const;
  std::pair<double, double> Linear(double margin = 0.05, double min_span = 0) const;
  std::pair<double, double> Logarithmic(double margin = 0.08) const;
};

// ---------------------------------------------------------------- the study folder

struct Path {
  std::vector<double> p, ln_v, psi_sigma, psi_epsilon, eps_s, q, i_dmin, i_dmax;
  std::vector<double> eps_a, eps_r;  // logarithmic strains from the path's first row
  bool empty() const { return p.empty(); }
};

// The sample a case belongs to, from its own result: the study's own (the
// contact friction and time step of the study's NCL case), another contact
// friction (Fig. 20's φ = 0), or a time step below ¾ of the study's (Sec. 5.2).
enum class Sample { kMain, kOtherFriction, kFineStep };

struct CaseData {
  std::string name, directory, parent_name, parent_stage;
  int replicate = 1;
  FigureSet figures;
  bool finished = false;
  // From the result.
  std::vector<dem::StageRecord> stages;
  std::vector<double> stage_psi_epsilon;  // nominal ψ_ε per stage (NaN: not a strain path)
  std::vector<double> stage_radial_stress;
  // The rate of its last strain-path stage: "I* = 0.001" (inertial rule) or
  // "‖D‖ = 167 1/s"; empty for none (a drained or stress-controlled stage).
  std::string rate_label;
  double time_step = 0;
  double friction = std::numeric_limits<double>::quiet_NaN();  // rad
  Sample sample = Sample::kMain;
  bool stops_at_asymptote = false;  // its last stage stops when its detector holds
  Path path;                        // the case's own rows
  bool Serves(const std::string& figure) const { return figures.Contains(figure); }
  double NominalPsiEpsilon() const {
    for (double v : stage_psi_epsilon) {
      if (std::isfinite(v)) return v;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }
  // σ_r of its first stress-controlled (drained) stage; NaN for none.
  double RadialStress() const {
    for (double v : stage_radial_stress) {
      if (std::isfinite(v)) return v;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }
};

const CaseData* FindCase(const std::vector<CaseData>& cases, int replicate,
                         const std::string& name);
// Where a case starts: NC (its parent stage is isotropic compression), OC
// (unloading), or neither, and the parent stage's final p.
struct Start {
  std::string kind;  // "NC", "OC" or ""
  double p_kpa = std::numeric_limits<double>::quiet_NaN();
};
Start StartOf(const std::vector<CaseData>& cases, const CaseData& c);
// "NC 100 kPa", "OC 20 kPa" (unloaded from the NCL), from the parent stage;
// p rounded to a round value within 5 % (1001 → 1000, 0.99 → 1).
std::string StartLabel(const std::vector<CaseData>& cases, const CaseData& c);
// A value rounded for a legend: to one significant digit when that is within
// 5 %, else to two.
double Rounded(double v);
// "σ_r = 100 kPa" for a drained triaxial case, else "ψ_ε = 90°".
std::string DirectionLabel(const CaseData& c);

// A detected or drifting state with a positive p and a finite ln(1+e).
bool UsableState(const StateRow& row);
// The hover text of a state: case, replicate, stage, kind, status, p, e,
// ψ_ε, ψ_σ, q/p, I and flags, lines separated by the two characters \n.
std::string StateLabel(const StateRow& row);

// The mean of the replicates' paths of the case `name` (replicates with a
// finished path, aligned as the state table's ensemble rows are: at the
// ends for a case whose last stage stops at its asymptote, else at the
// starts), with the 95 % half-widths; `paths` 0 when fewer than two replicates.
struct MeanCasePath {
  std::vector<double> p, ln_v, psi_sigma, psi_sigma_band, ln_v_band, ln_p_band;
  int paths = 0;
};
MeanCasePath MeanPathOf(const std::vector<CaseData>& cases, const std::string& name);

// "hypoplastic clay (Mašín 2005)" for "hypoplastic_clay".
std::string ModelTitle(const std::string& name);

struct Context;

// Which states a figure shows: one sample, some kinds, detected states and
// (optionally) drifting ones, of the cases the user's settings include; and,
// when `cases` is non-empty, only the states of those case names.
struct StateSelection {
  Sample sample = Sample::kMain;
  std::vector<TableKind> kinds;  // empty: every kind
  bool drifting = true;          // drifting states too (drawn open)
  std::set<std::string> cases;   // empty: every case of the sample; a joined row
                                 // ("a+b") when both paths are among them
  // "states of the study's sample (φ = 0.5 rad, Δt = 2.1e-06 s); kinds csl;
  // detected and drifting; gas, invalid and unfinished stages left out".
  std::string Describe(const Context& ctx) const;
};

struct Context {
  std::string directory, data;  // DIR, OUT/figures/data
  FigureDataOptions options;
  std::vector<CaseData> cases;
  std::vector<StateRow> states;  // the state table without its ensemble rows
  std::map<std::pair<int, std::string>, NclLine> ncl_fits;
  std::string study_ncl;
  std::vector<ModelOverlay> models;
  std::string models_note;  // which models are overlaid, which absent
  // The study's own sample: the friction (rad) and time step of its NCL case.
  double main_friction = std::numeric_limits<double>::quiet_NaN();
  double main_time_step = 0;
  std::map<std::pair<int, std::string>, size_t> by_name;  // (replicate, name) → cases[k]

  std::string File(const std::string& name) const { return data + "/" + name; }
  const CaseData* Case(int replicate, const std::string& name) const {
    const auto it = by_name.find({replicate, name});
    return it == by_name.end() ? nullptr : &cases[it->second];
  }
  // The sample of a state's case (the study's own when its case is unknown).
  Sample SampleOf(const StateRow& row) const {
    const CaseData* c = Case(row.replicate, row.case_name);
    return c ? c->sample : Sample::kMain;
  }
  // Replicate 1's finished cases of `sample` that serve `figure` and that
  // the user's settings include.
  std::vector<const CaseData*> Serving(const std::string& figure,
                                       Sample sample = Sample::kMain) const {
    std::vector<const CaseData*> out;
    for (const CaseData& c : cases) {
      if (c.replicate == 1 && c.finished && !c.path.empty() && c.Serves(figure) &&
          c.sample == sample && options.settings.IncludesCase(c.name)) {
        out.push_back(&c);
      }
    }
    return out;
  }
  // The usable states (UsableState) that `selection` takes.
  std::vector<const StateRow*> Select(const StateSelection& selection) const;
  NclLine StudyNcl(int replicate) const {
    const auto it = ncl_fits.find({replicate, study_ncl});
    return it == ncl_fits.end() ? NclLine{} : it->second;
  }
};

// The friction and time step of the study's sample (those of its NCL case,
// else the most common among the finished cases), each case's sample
// against them, and `by_name`. ReadContext calls it; a Context built by hand
// calls it after its cases are in.
void ClassifySamples(Context* ctx);

// The study folder `directory` as the figures read it: its cases (with
// replicate 1's paths), its state table and NCL fits, the study's NCL case
// and the calibrated models of `options` that it has.
Context ReadContext(const std::string& directory, const FigureDataOptions& options);

// ---------------------------------------------------------------- index entries

FigureSpec Spec(const std::string& stem, const std::string& figure, const std::string& title,
                const std::string& caption, const std::string& script);
// `spec` without an image: `why` is its reason and ends its caption.
FigureSpec NotDrawn(FigureSpec spec, const std::string& why);
// A gnuplot variable of the figure's script: a number, or a text quoted.
void Set(FigureSpec* spec, const std::string& name, int value);
void Set(FigureSpec* spec, const std::string& name, const std::string& value);
// A number variable (6 significant digits), e.g. an axis end.
void SetNumber(FigureSpec* spec, const std::string& name, double value);

}  // namespace granasym::analysis::figures
