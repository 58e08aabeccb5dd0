// The rate study (issue 10 §2, SPEC §8.2): asymptotic states of proportional
// paths driven at fixed inertial numbers I* (and at a constant ‖D‖, the
// paper's 167 1/s), from NC states at several p, with replicates. Per
// (E, ψ_ε, p_0, rate) it gives the replicate means with 95 % Student-t
// intervals; per (E, ψ_ε, p_0) the quasi-static limit, extrapolated as I → 0
// by the least-squares line y = a + b·I(d_max) through the states of the
// smallest I* (the small-I form of the μ(I) laws that the paper cites: da
// Cruz et al. 2005, its ref. [10], and Jop et al. 2006, ref. [29]); per
// (E, ψ_ε, rate) the line ln(1+e) = N − λ ln p of its asymptotic states (the
// NCL at ψ_ε = 0°, the CSL at 90°, the NEL beyond); and whether the two
// smallest I* agree within their intervals in e, ψ_σ and the CSL's position
// (SPEC §8.2: rate-independent).
//
// Rate cases are the cases whose `figures` key names "rate" (the programme
// says which cases make up the rate study: studies/programmes/rate.toml);
// a study without them has no rate files. Files in the study folder:
//
//   rate_states.csv        one row per rate case and detector stage: its E, ψ_ε, start
//                          p_0, rule, I* or ‖D‖, and the asymptotic state of the state table
//   rate_summary.csv       per (E, ψ_ε, p_0, rate): means and 95 % intervals over replicates
//   rate_lines.csv         per (E, ψ_ε, rate): N, λ and ln(1+e) at the reference p (± 95 %);
//                          at ψ_ε = 0° the mean of the paths' own lines (RateState::path_n)
//   rate_quasi_static.csv  per (E, ψ_ε, p_0, quantity): the limit a ± 95 %, the slope b ± 95 %
//   rate_independence.csv  per (E, ψ_ε, p_0): the two smallest I* compared, and the verdict
//   rate_stiffness.csv     per (other E, ψ_ε, p_0, rate): ψ_σ and the CSL against the main E
//   rate_extension.csv     per (E, rate, p_0, ψ_ε ≥ 90°): σ_r/p, ψ_σ, liquefied replicates
//   rate_extension_limit.csv per (E, rate, p_0): ψ_ε(d) ± 95 %, or where it liquefies
//   rate_drained_states.csv  one row per drained triaxial rate case (constant σ_r)
//   rate_drained.csv         per (E, σ_r, ε̇_a): means and 95 % intervals
//   rate_drained_limit.csv   per (E, σ_r): M, ln(1+e), ln p as I → 0; the two slowest rates
//   rate_drained_critical_state.csv per E: quasi-static M, φ_c, the CSL and M's p-dependence
#pragma once

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "dem/strain_path_stage.h"
#include "study/state_table.h"

namespace granasym::analysis {

enum class Agreement { kAgree, kDiffer, kUndetermined };
}  // namespace granasym::analysis

template <>
struct granasym::EnumNames<granasym::analysis::Agreement> {
  static constexpr EnumEntry<analysis::Agreement> kEntries[] = {
      {analysis::Agreement::kAgree, "agree", "the difference is inside its 95 % interval"},
      {analysis::Agreement::kDiffer, "differ", "the difference is outside its 95 % interval"},
      {analysis::Agreement::kUndetermined, "undetermined",
       "an estimate lacks its interval (fewer than two states, or three points for a line)"},
  };
};

namespace granasym::analysis {

// The study's table of asymptotic states, which the analyses read.
using study::CsvNumber;
using study::CsvText;
using study::Interval;
using study::MeanInterval95;
using study::ReadStateTable;
using study::StateRow;
using study::TableKind;
using study::TableStatus;

// The published critical-state stress ratio of frictional spheres without
// rolling resistance that the study's quasi-static M is set against (issue 10
// §2); `source` says where the numbers come from and how they were converted.
// No triaxial value at μ ≈ 0.5 was found in a retrievable text, so the band is
// bounded by two shear-zone frictions read as tan φ = τ/σ_n:
//   Latham, Abe & Mora (2005), "Macroscopic friction response of rotational
//   and non-rotational lattice solid gouge models in 2D and 3D";
//   Mair, Frye & Marone (2002), J. Geophys. Res. 107(B10), 2219,
//   doi:10.1029/2001JB000516.
struct LiteratureBand {
  double low, high;
  const char* source;  // one sentence, for captions and the report
};
inline constexpr LiteratureBand kSphereCriticalStateRatio = {
    0.81, 0.95,
    "M = 0.81 from the 3D DEM of rotating spheres of Latham, Abe & Mora (2005, 'Macroscopic "
    "friction response of rotational and non-rotational lattice solid gouge models in 2D and "
    "3D': macroscopic friction 0.38 for contact friction μ_P ≥ 0.3, sheared between plates) to "
    "0.95 from the glass-bead shear zones of Mair, Frye & Marone (2002, J. Geophys. Res. "
    "107(B10) 2219: sliding friction 0.45), each friction read as tan φ and M = 6 sin φ/(3 − "
    "sin φ); read as sin φ they give 0.87 and 1.06, so the band brackets rather than checks a "
    "triaxial value"};

struct RateStudyOptions {
  // Detector statuses of the states that enter means, lines, fits and verdicts.
  std::vector<TableStatus> statuses = {TableStatus::kDetected};
  // ψ_ε = 0° states also when drifting: on the isotropic path the detector's
  // ψ_σ and slope tests are at the noise level of a small sample (the
  // study's own NCL fit takes them for the same reason, state_table.h).
  std::vector<TableStatus> ncl_statuses = {TableStatus::kDetected, TableStatus::kDrifting};
  // Validity flags that exclude a state (a gas or liquefied sample, overlaps
  // that make a result unreliable, SPEC §8.3).
  std::vector<std::string> excluded_flags = {"gas", "overlap_above_10pct"};
  // The quasi-static line is fitted through the states of this many of the
  // smallest I* values (with usable states); at least 2.
  int fit_rates = 3;
  // The mean stress (kPa) at which a line's position is read and compared.
  double reference_p_kpa = 100.0;
  // The published band the quasi-static M is compared with.
  LiteratureBand literature_m = kSphereCriticalStateRatio;
  bool IsValid(std::string* why) const;
};

// A mean (or a fitted value) with its standard error and the half-width of
// its two-sided 95 % interval (Student t with `dof` degrees of freedom);
// NaN errors when there is no interval.
struct Estimate {
  double mean = std::numeric_limits<double>::quiet_NaN();
  double standard_error = std::numeric_limits<double>::quiet_NaN();
  double half_width = std::numeric_limits<double>::quiet_NaN();
  int n = 0;    // values
  int dof = 0;  // degrees of freedom of the interval (0: none)
  bool has_interval() const { return dof >= 1 && std::isfinite(standard_error); }
  static Estimate Of(const std::vector<double>& values);  // mean over n, dof n − 1
  static Estimate Fitted(double value, double standard_error, int points);  // dof points − 2
};

// Whether two estimates agree: the difference b − a against the half-width
// of its 95 % interval, t_{ν} sqrt(se_a² + se_b²), ν by Welch–Satterthwaite
// (rounded down, so the interval is not narrower than it should be).
struct Comparison {
  Agreement agreement = Agreement::kUndetermined;
  double difference = std::numeric_limits<double>::quiet_NaN();
  double half_width = std::numeric_limits<double>::quiet_NaN();
};
Comparison Compare(const Estimate& a, const Estimate& b);

// One rate case's asymptotic state (a row of rate_states.csv).
struct RateState {
  int replicate = 1;
  std::string case_name, stage, flags;
  TableKind kind = TableKind::kNone;
  TableStatus status = TableStatus::kNoResult;
  double youngs_modulus_mpa = 0;
  double psi_epsilon_deg = 0;  // the stage's nominal direction
  double start_p_kpa = 0;      // the state it started from: the parent stage's p target
  dem::RateRule rule = dem::RateRule::kConstant;
  double inertial_number = std::numeric_limits<double>::quiet_NaN();  // I* (inertial rule)
  double stretching_rate = 0;  // ‖D‖ (constant), its cap (inertial), 1/s
  // The asymptotic state (the state table's row).
  double p_kpa = 0, e = 0, ln_1_plus_e = 0, psi_sigma_deg = 0, q_over_p = 0;
  double ocr = 0;  // against the study's NCL (the state table's)
  // Against the NCL of the same E and rate (its ψ_ε = 0° line in
  // rate_lines.csv), set by RateStudy::Analyse; NaN without that line.
  double ocr_same_rate = std::numeric_limits<double>::quiet_NaN();
  double inertial_number_dmin = 0, inertial_number_dmax = 0;
  double stiffness_number = 0;  // κ at the asymptote's p (SPEC §8.2)
  // A ψ_ε = 0° path's own NCL at its rate: ln(1+e) = N − λ ln(p / 1 kPa) by
  // least squares through the stage's rows once p has grown by a factor e
  // from its first row (one unit of ln p, the compression detector's window:
  // past the change of rate at the start), over [path_p_min_kpa,
  // path_p_max_kpa]; NaN for other paths and for fewer than 3 such rows. The
  // asymptotic states of these paths all lie at the stress cap, so the NCL of
  // a rate (rate_lines.csv) comes from these lines.
  double path_n = std::numeric_limits<double>::quiet_NaN();
  double path_lambda = std::numeric_limits<double>::quiet_NaN();
  double path_p_min_kpa = std::numeric_limits<double>::quiet_NaN();
  double path_p_max_kpa = std::numeric_limits<double>::quiet_NaN();
  bool HasPathLine() const { return std::isfinite(path_n) && std::isfinite(path_lambda); }
  // The rate of the case: I* for the inertial rule, ‖D‖ for a constant one.
  double rate() const {
    return rule == dem::RateRule::kInertial ? inertial_number : stretching_rate;
  }
};

// What groups states: the material, the direction, the start and the rate.
struct RateKey {
  double youngs_modulus_mpa = 0, psi_epsilon_deg = 0, start_p_kpa = 0;
  dem::RateRule rule = dem::RateRule::kConstant;
  double rate = 0;
  bool operator<(const RateKey& other) const;
  bool operator==(const RateKey& other) const { return !(*this < other) && !(other < *this); }
  std::string RateLabel() const;  // "I* = 0.001" or "‖D‖ = 167 1/s"
};
RateKey KeyOf(const RateState& state);

// Per (E, ψ_ε, p_0, rate): the replicates' states and their means.
struct RateGroup {
  RateKey key;
  int states = 0;     // rows of the group
  int used = 0;       // of them usable (statuses, flags)
  int liquefied = 0;  // of them a gas (status or flag "gas": no asymptotic state)
  // "2 usable of 3 states" and, when some liquefied, "(1 liquefied)".
  std::string UsableText() const;
  Estimate p_kpa, e, ln_1_plus_e, psi_sigma_deg, q_over_p, ocr, ocr_same_rate, inertial_number_dmin,
      inertial_number_dmax, stiffness_number;
};

// Per (E, ψ_ε, rate): ln(1+e) = N − λ ln(p / 1 kPa) through the usable states
// of every start (all replicates), and ln(1+e) on it at the reference p.
struct RateLine {
  double youngs_modulus_mpa = 0, psi_epsilon_deg = 0;
  dem::RateRule rule = dem::RateRule::kConstant;
  double rate = 0;
  int points = 0;
  double n = std::numeric_limits<double>::quiet_NaN();
  double lambda = std::numeric_limits<double>::quiet_NaN();
  Estimate position;  // ln(1+e) at reference_p_kpa (the prediction's standard error)
  double p_min_kpa = 0, p_max_kpa = 0;
  bool valid() const { return std::isfinite(n) && std::isfinite(lambda); }
};

// Per (E, ψ_ε, p_0) and quantity (psi_sigma_deg, q_over_p, ln_1_plus_e): the
// line y = a + b·I(d_max) through the usable states of the smallest I*.
struct QuasiStaticFit {
  double youngs_modulus_mpa = 0, psi_epsilon_deg = 0, start_p_kpa = 0;
  std::string quantity;
  std::vector<double> rates;  // the I* values fitted over, ascending
  int points = 0;
  double i_min = std::numeric_limits<double>::quiet_NaN();  // the measured I(d_max) range
  double i_max = std::numeric_limits<double>::quiet_NaN();
  Estimate limit;  // a: the value as I → 0
  Estimate slope;  // b
  bool valid() const { return std::isfinite(limit.mean); }
};

// Per (E, ψ_ε, p_0): the two smallest I* compared in ln(1+e), ψ_σ and the
// CSL's position (ln(1+e) at the reference p of the CSLs of those I* at
// this E). Rate-independent when all three agree, rate-dependent when one
// differs, undetermined otherwise (`reason` says what is missing).
struct RateVerdict {
  double youngs_modulus_mpa = 0, psi_epsilon_deg = 0, start_p_kpa = 0;
  double smallest = std::numeric_limits<double>::quiet_NaN();  // I*
  double next = std::numeric_limits<double>::quiet_NaN();      // the next larger I*
  Estimate ln_v_smallest, ln_v_next, psi_smallest, psi_next, csl_smallest, csl_next;
  Comparison ln_1_plus_e, psi_sigma, csl_position;
  std::string verdict;  // rate_independent, rate_dependent, undetermined
  std::string reason;
};

// Stiffness scaling (issue 10 §1): per (ψ_ε, p_0, rate) with groups at the
// reference modulus and at another E, the other E against the reference in
// ψ_σ and in the position of the CSL of that rate (its ln(1+e) at the
// reference p; on an isochoric path e is the start's, which the modulus
// changes, so the CSL's position is compared, not e), with the stiffness
// numbers κ = E/p-like of both. stiffness_independent when both agree within
// the 95 % interval of their difference (Welch), stiffness_dependent when one
// differs, undetermined otherwise (`reason`).
struct StiffnessComparison {
  double youngs_modulus_mpa = 0, reference_modulus_mpa = 0, psi_epsilon_deg = 0, start_p_kpa = 0;
  dem::RateRule rule = dem::RateRule::kConstant;
  double rate = 0;
  Estimate psi_reference, psi_other, csl_reference, csl_other, kappa_reference, kappa_other;
  Comparison psi_sigma, csl_position;  // other − reference
  std::string verdict, reason;
};

// §3 (issue 10): the extension sweep. Per (E, rate, p_0), the groups with
// ψ_ε ≥ 90° in ascending ψ_ε, each with the asymptotic σ_r/p = 1 − (q/p)/3
// (zero at the limit "d", where ψ_σ = atan √2 = 54.74°, SPEC §2) and how
// many of its replicates liquefied (status or flag "gas": no load-bearing
// network or p below the floor, SPEC §8.3).
struct ExtensionStep {
  double youngs_modulus_mpa = 0, start_p_kpa = 0, psi_epsilon_deg = 0;
  dem::RateRule rule = dem::RateRule::kConstant;
  double rate = 0;
  int states = 0, used = 0, liquefied = 0;
  Estimate sigma_r_over_p, psi_sigma_deg, p_kpa, ln_1_plus_e;
  // asymptote: σ_r/p > 0 outside its interval; limit_d: zero within it (or
  // below); liquefied: most replicates liquefied; undetermined: fewer than
  // two usable states and no majority liquefied.
  std::string status;
};

// The end of one sweep: the limit ψ_ε(d) (σ_r/p zero within its interval),
// or the ψ_ε at which the sample liquefies first, or neither up to the
// largest ψ_ε swept.
struct ExtensionLimit {
  double youngs_modulus_mpa = 0, start_p_kpa = 0;
  dem::RateRule rule = dem::RateRule::kConstant;
  double rate = 0;
  int steps = 0;
  double psi_max_deg = std::numeric_limits<double>::quiet_NaN();  // the largest ψ_ε swept
  // limit_d, liquefied, not_reached (σ_r/p > 0 up to psi_max), undetermined.
  std::string result;
  double last_asymptote_deg = std::numeric_limits<double>::quiet_NaN();
  double liquefied_at_deg = std::numeric_limits<double>::quiet_NaN();
  double limit_step_deg = std::numeric_limits<double>::quiet_NaN();  // the first limit_d step
  // ψ_ε(d): the root of the least-squares line σ_r/p = a + b ψ_ε through the
  // usable states of the limit step and the (up to two) asymptote steps
  // before it, with its delta-method interval (t, points − 2 dof).
  Estimate psi_d_deg;
  std::string Text() const;  // "psi_epsilon(d) = 127.2 +- 3.1 deg", "liquefied at ..."
};

// Drained triaxial compression (constant σ_r, constant ε̇_a) from the NC
// states: the critical state under stress control. The isochoric paths from
// loose NC states liquefy as I* → 0, so the quasi-static M, φ_c and CSL come
// from these cases. On a drained path p moves only from σ_r to about
// 1.4 σ_r, so a constant ε̇_a keeps I nearly fixed; the analysis uses the
// I(d_max) measured over each asymptote's window.
struct DrainedState {
  int replicate = 1;
  std::string case_name, stage, flags;
  TableStatus status = TableStatus::kNoResult;
  double youngs_modulus_mpa = 0, radial_stress_kpa = 0, axial_strain_rate = 0;  // ε̇_a (1/s)
  double p_kpa = 0, e = 0, ln_1_plus_e = 0, psi_sigma_deg = 0, q_over_p = 0;
  double inertial_number_dmin = 0, inertial_number_dmax = 0;
};

// Per (E, σ_r, ε̇_a): the replicates' means.
struct DrainedGroup {
  double youngs_modulus_mpa = 0, radial_stress_kpa = 0, axial_strain_rate = 0;
  int states = 0, used = 0;
  Estimate p_kpa, e, ln_1_plus_e, psi_sigma_deg, q_over_p, inertial_number_dmax;
};

// Per (E, σ_r): y = a + b·I(d_max) through the usable states of every rate
// (at least two rates): M = q/p, ln(1+e) and ln p as I → 0; and the two
// slowest rates compared in M and ln(1+e) (rate_independent when both
// agree within the 95 % interval of their difference).
struct DrainedLimit {
  double youngs_modulus_mpa = 0, radial_stress_kpa = 0;
  int rates = 0, points = 0;
  double i_min = std::numeric_limits<double>::quiet_NaN();
  double i_max = std::numeric_limits<double>::quiet_NaN();
  Estimate m, ln_1_plus_e, ln_p_kpa;                          // the limits a
  Estimate m_slope;                                           // b of M
  double slowest = std::numeric_limits<double>::quiet_NaN();  // ε̇_a (1/s)
  double next = std::numeric_limits<double>::quiet_NaN();
  Comparison m_change, ln_1_plus_e_change;  // next − slowest
  std::string verdict, reason;              // rate_independent, rate_dependent, undetermined
  bool valid() const { return std::isfinite(m.mean); }
};

// Per E: the quasi-static critical state from the limits of every σ_r.
struct DrainedCriticalState {
  double youngs_modulus_mpa = 0;
  int starts = 0;       // σ_r with a limit
  Estimate m;           // mean of the limits' M (Student t, starts − 1 dof)
  Estimate phi_c_deg;   // φ_c = asin(3M/(6 + M)), its interval by the delta method
  Estimate m_per_ln_p;  // slope of the limits' M against ln p: M's p-dependence
  Estimate lambda;      // the CSL ln(1+e) = Γ − λ ln(p / 1 kPa) through the limits
  double gamma = std::numeric_limits<double>::quiet_NaN();
  Estimate position;  // ln(1+e) on it at the reference p
  std::string Text(double reference_p_kpa) const;
};

struct DrainedStudy {
  std::vector<DrainedState> states;
  std::vector<DrainedGroup> groups;            // by (E, σ_r, ε̇_a)
  std::vector<DrainedLimit> limits;            // by (E, σ_r)
  std::vector<DrainedCriticalState> critical;  // by E
  // `usable`: the rate study's rule for a state's status and flags.
  static DrainedStudy Analyse(std::vector<DrainedState> states, const RateStudyOptions& options);
};

struct RateStudy {
  RateStudyOptions options;
  std::vector<RateState> states;  // every row, usable or not
  std::vector<RateGroup> groups;  // in key order
  std::vector<RateLine> lines;
  std::vector<QuasiStaticFit> quasi_static;
  std::vector<RateVerdict> verdicts;
  std::vector<ExtensionStep> extension_steps;    // by (E, rate, p_0), ψ_ε ascending
  std::vector<ExtensionLimit> extension_limits;  // one per (E, rate, p_0) with a ψ_ε > 90° step
  std::vector<StiffnessComparison> stiffness;    // per other E, ψ_ε, p_0 and rate
  DrainedStudy drained;                          // the drained triaxial cases
  bool Usable(const RateState& state) const;
  bool Usable(const DrainedState& state) const;  // the same rule for drained states
  const RateGroup* Find(const RateKey& key) const;
  // The Young's modulus of most groups (ties: the largest), the study's main
  // material; the others are its stiffness variants. NaN without groups.
  double ReferenceModulus() const;
  std::string Text() const;  // a few lines for the console
  // The study's answers to issue 10's questions, one sentence each, with
  // their intervals: the quasi-static critical state and whether it depends
  // on p (drained), ψ_σ of the isochoric paths as I → 0 per start and where
  // they liquefy, how far the extension states go, and the verdicts on rate
  // and stiffness independence (the report's first paragraphs).
  std::vector<std::string> Answers() const;
  static RateStudy Analyse(std::vector<RateState> states, const RateStudyOptions& options = {});
};

// §4 (issue 10): the quasi-static states that `study calibrate` fits the
// models to in a rate study, and that figure rate (e) sets beside the
// paper-rate ones: the rate cases at one I* and the reference modulus. By
// default the smallest I* whose ψ_ε = 90° cases have usable states from at
// least two starts (so that it has a CSL); `inertial_number` chooses it.
// With them, the drained triaxial cases of the reference modulus at the
// slowest axial rate of each σ_r that has usable states: the critical state
// under stress control, which the isochoric paths from loose NC states do
// not reach as I* → 0 (they liquefy).
struct QuasiStaticSelection {
  double inertial_number = std::numeric_limits<double>::quiet_NaN();
  double youngs_modulus_mpa = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> cases;          // case names, each once, in the states' order
  std::vector<std::string> drained_cases;  // likewise, the drained cases
  std::string reason;                      // why there is none (empty when valid)
  bool valid() const { return !cases.empty(); }
};
QuasiStaticSelection SelectQuasiStatic(const RateStudy& study,
                                       std::optional<double> inertial_number = std::nullopt);
// DIR/calibration/quasi_static.toml, written by `study calibrate` for a rate
// study: the selection its calibrations were fitted to.
inline constexpr char kQuasiStaticSelectionFile[] = "calibration/quasi_static.toml";
void WriteQuasiStaticSelection(const std::string& directory, const QuasiStaticSelection& s);
// The selection written there, or nullopt without the file (InputError when malformed).
std::optional<QuasiStaticSelection> ReadQuasiStaticSelection(const std::string& directory);

// The rate study of a study folder from its rate_states.csv and
// rate_drained_states.csv (ReadRateStates, ReadDrainedStates), analysed with
// the default options; nullopt when it has neither.
std::optional<RateStudy> ReadRateStudy(const std::string& directory);

// Whether a case's `figures` key ("10, rate") names the rate study.
bool ServesRateStudy(const std::string& figures);

// Reads the rate cases of the study folder (their case.toml, their result and
// their parent's, for the rate rule, E and the start) against the rows of
// its state table, analyses them and writes the rate files; returns nullopt,
// and removes rate files of an earlier run, when there are no rate cases.
std::optional<RateStudy> WriteRateStudy(const std::string& directory,
                                        const std::vector<StateRow>& rows,
                                        const RateStudyOptions& options = {});

// Writes the rate files of an analysed study into `directory`.
void WriteRateFiles(const std::string& directory, const RateStudy& study);

// DIR/rate_states.csv back (InputError naming the file when malformed); empty
// when the study has no rate cases (no file).
std::vector<RateState> ReadRateStates(const std::string& directory);
// DIR/rate_drained_states.csv back (the same rules).
std::vector<DrainedState> ReadDrainedStates(const std::string& directory);

// The file names, for the report and the figures.
inline constexpr char kRateStatesFile[] = "rate_states.csv";
inline constexpr char kRateSummaryFile[] = "rate_summary.csv";
inline constexpr char kRateLinesFile[] = "rate_lines.csv";
inline constexpr char kRateStiffnessFile[] = "rate_stiffness.csv";
inline constexpr char kRateQuasiStaticFile[] = "rate_quasi_static.csv";
inline constexpr char kRateIndependenceFile[] = "rate_independence.csv";
inline constexpr char kRateExtensionFile[] = "rate_extension.csv";
inline constexpr char kRateExtensionLimitFile[] = "rate_extension_limit.csv";
inline constexpr char kRateDrainedStatesFile[] = "rate_drained_states.csv";
inline constexpr char kRateDrainedFile[] = "rate_drained.csv";
inline constexpr char kRateDrainedLimitFile[] = "rate_drained_limit.csv";
inline constexpr char kRateDrainedCriticalFile[] = "rate_drained_critical_state.csv";

}  // namespace granasym::analysis
