// The rate study's files in a study folder: the analysis (analysis/rate_study.h)
// written as CSV, each file from one table of columns that also reads the
// states back.
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
//
// An estimate X is two columns, X_mean and X_ci95 (the half-width of its 95 %
// interval); a comparison X is X_difference, X_difference_ci95 and
// X_agreement. Each file starts with '#' comments that say how its numbers
// were made.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/rate_study.h"

namespace granasym::analysis {

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

// Writes the rate files of an analysed study into `directory` (each atomically).
void WriteRateFiles(const std::string& directory, const RateStudy& study);

// Removes the rate files of an earlier run (a study that no longer has rate cases).
void RemoveRateFiles(const std::string& directory);

// DIR/rate_states.csv back (InputError naming the file, the line and the
// column when malformed); empty when the study has no rate cases (no file).
std::vector<RateState> ReadRateStates(const std::string& directory);
// DIR/rate_drained_states.csv back (the same rules).
std::vector<DrainedState> ReadDrainedStates(const std::string& directory);

// The rate study of a study folder from its rate_states.csv and
// rate_drained_states.csv, analysed with the default options; nullopt when
// it has neither.
std::optional<RateStudy> ReadRateStudy(const std::string& directory);

}  // namespace granasym::analysis
