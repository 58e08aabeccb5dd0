// The data of the paper's figures (SPEC §5) from a study folder: tab-separated
// files under DIR/figures/data/ that the gnuplot scripts of plots/study/ draw,
// and the list of figures with their titles and captions (DIR/figures/index.tsv).
//
// A data file holds one block per curve (blocks separated by two blank
// lines, gnuplot's `index`); each block starts with a header line whose
// columns name the values and whose last field is the curve's legend title
// (gnuplot `title columnheader(K)`). Paths are replicate 1's; asymptotic
// states are those of all replicates.
//
// Layout read: DIR/cases/r<K>/<case>/{case.toml, done.toml, result.h5} (the
// `figures` key of case.toml says which figure a case serves),
// DIR/asymptotic_states.h5 (study/state_table.h), DIR/models/<name>/result.csv
// (Fig. 5) and DIR/calibration/<model>/plot_data/ (the format of
// calibration/calibration_report.cc WritePlotData: model_curve.csv,
// model_lines.dat), for the calibrated models' overlays.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "study/figure_settings.h"
#include "study/state_table.h"

namespace granasym::analysis {

using study::StateRow;

// One figure: what index.tsv says about it and how plots/study/ draws it.
struct FigureSpec {
  std::string stem;    // output file name without extension, e.g. "fig10_csl_nc"
  std::string figure;  // the paper's figure: "10", "Sec. 5.2"
  std::string title;
  std::string caption;  // what it shows, the method, what is missing
  std::string script;   // plots/study/<script>
  // gnuplot variables set with -e before the script (name, value as a
  // gnuplot expression: a number or a quoted string).
  std::vector<std::pair<std::string, std::string>> variables;
  std::string not_drawn;  // non-empty: why there is no image (then no data either)
};

struct FigureDataOptions {
  // What the user chose (study.toml's [figures], overridden by the flags of
  // `study figures`): ASBS levels, Fig. 18's level, cases, figures, models.
  study::FigureSettings settings;
  // Where figures/ is written; empty: the study folder itself.
  std::string out;
  // A state is projected to a level along its asymptotic line by at most
  // this much in ln p (farther states say little about that level).
  double max_projection_lnp = 1.0;
  // Half-width (rows) of the strain increments that give a path's ψ_ε.
  int psi_epsilon_half_rows = 2;
  bool IsValid(std::string* why) const;
};

// The isotropic NCL ln(1+e) = n − λ* ln(p / 1 kPa).
struct NclLine {
  double n = 0, lambda = 0;
  bool valid() const { return lambda > 0; }
  // p_e* (kPa) at ln(1+e) = ln_v.
  double EquivalentPressure(double ln_v) const;
};

// An asymptotic state moved to ln(1+e) = level along its asymptotic line,
// normalised by p_e* of the NCL at that level.
struct SectionPoint {
  double p_over_pe = 0, q_over_pe = 0;
  double psi_epsilon_deg = 0;
  double lnp_shift = 0;  // ln p at the level minus ln p of the state
};
// The asymptotic line of a compression or extension state is the detector's
// slope d ln(1+e)/d ln p when it is a usable negative number (below −1e-3);
// otherwise (isochoric and NCL states, flat or rising slopes) the line
// parallel to the NCL (slope −λ*, the state keeps its OCR). ψ_σ, and so q/p,
// stays. False when the shift exceeds `max_lnp` or the inputs are unusable.
bool ProjectToLevel(const StateRow& state, double level, const NclLine& ncl, double max_lnp,
                    SectionPoint* point);

// A path's stretching direction row by row, from the strain increments
// between rows k − h and k + h (clamped at the ends), in degrees.
std::vector<double> PathPsiEpsilon(const std::vector<double>& eps_a,
                                   const std::vector<double>& eps_r, int half_rows);

// A state picked along a path where its stretching direction first reaches
// a target ψ_ε (linear interpolation between the two rows around the crossing).
struct StretchingPick {
  double psi_epsilon_deg = 0;  // the target
  double p_kpa = 0, ln_1_plus_e = 0, psi_sigma_deg = 0;
  double row = 0;  // fractional row index
};
std::vector<StretchingPick> PickStretchingDirections(const std::vector<double>& psi_epsilon_deg,
                                                     const std::vector<double>& p_kpa,
                                                     const std::vector<double>& ln_1_plus_e,
                                                     const std::vector<double>& psi_sigma_deg,
                                                     const std::vector<double>& targets_deg);

// ASBS levels: `count` levels at evenly spaced fractions (20 %–80 %) of the
// range of `ln_v`, rounded to 0.005; one level when the range is narrower
// than 0.01; none for no values.
std::vector<double> SectionLevels(std::vector<double> ln_v, int count);

// A calibrated model's asymptotic curve (DIR/calibration/<model>/plot_data).
struct ModelOverlay {
  std::string name;   // hypoplastic_clay, ...
  std::string title;  // "hypoplastic clay"
  NclLine ncl;        // the model's NCL, from its ψ_ε = 0° line
  // model_curve.csv: normalised by the model's own p_e.
  std::vector<double> psi_epsilon_deg, psi_sigma_deg, p_over_pe, q_over_pe;
  // model_lines.dat: the asymptotic lines, one per ψ_ε.
  struct Line {
    double psi_epsilon_deg = 0, psi_sigma_deg = 0;
    std::vector<double> ln_p, ln_1_plus_e;
  };
  std::vector<Line> lines;
};
// Reads `folder` (a WritePlotData folder); InputError naming the file when
// a file is malformed, RuntimeError when the ψ_ε = 0° line is missing.
ModelOverlay ReadModelOverlay(const std::string& folder, const std::string& name);
// The model's cross-section at ln(1+e) = level, normalised by p_e* of the
// study's NCL at that level: p/p_e* scales by p_e(model)/p_e*(study).
void ModelSectionAt(const ModelOverlay& model, double level, const NclLine& study_ncl,
                    std::vector<double>* p_over_pe, std::vector<double>* q_over_pe);

// Writes OUT/figures/data/ (OUT: options.out, else the study folder DIR)
// and returns the figures (with the reason for each that has no data): the
// paper's figures that the study's cases declare in their `figures` keys
// (Fig. 5 when it has model runs, the calibrated models' Fig. 5 when `study
// calibrate` ran them), and the rate study's three figures when it has rate
// cases (analysis/rate_study.h); all of them, whatever options.settings.only
// says (that chooses what is drawn). Throws InputError when DIR is not a study folder with a
// state table, or when OUT lies inside another study's folder.
std::vector<FigureSpec> WriteFigureData(const std::string& directory,
                                        const FigureDataOptions& options = {});

// OUT/figures/index.tsv: stem, figure, title, caption (a figure not drawn
// has its reason in the caption); tabs and line breaks in fields become spaces.
void WriteFigureIndex(const std::string& out, const std::vector<FigureSpec>& figures);

// OUT/figures/<stem>.plt for every figure with data: the figure's gnuplot
// variables (absolute paths of its data and output) and the `load` of its
// script, copied with the shared ones from `plots` (plots/study/) into
// OUT/figures/scripts/. `gnuplot OUT/figures/<stem>.plt` redraws the PNG;
// `gnuplot -e "term='pdf'" …` (or 'svg') the other formats. Returns the
// wrappers' paths by stem.
std::vector<std::pair<std::string, std::string>> WriteFigureScripts(
    const std::string& out, const std::string& plots, const std::vector<FigureSpec>& figures);

}  // namespace granasym::analysis
