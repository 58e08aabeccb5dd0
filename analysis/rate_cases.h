// The rate cases of a study folder as the rate study's input: the rows of
// the state table whose case's `figures` key names "rate", completed from
// the case's result (its stage's rate rule, I* or ‖D‖, ψ_ε or the drained
// stage's σ_r and ε̇_a, E, κ, the ψ_ε = 0° path's own NCL) and its parent's
// (the start p_0). `WriteRateStudy` reads them, analyses them
// (analysis/rate_study.h) and writes the rate files (analysis/rate_files.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/quasi_static_selection.h"
#include "analysis/rate_study.h"

namespace granasym::analysis {

// Whether a case's `figures` key ("10, rate") names the rate study.
bool ServesRateStudy(const std::string& figures);

// The states of the rate cases of a study folder.
struct RateCases {
  bool any = false;  // whether a row of the table serves the rate study
  std::vector<RateState> states;
  std::vector<DrainedState> drained;
};
// Reads the case folders of the rows of the state table that serve the rate
// study (a row without a result or stage, and an ensemble row, is left out).
RateCases ReadRateCases(const std::string& directory, const std::vector<StateRow>& rows);

// The quasi-static set's other cases (QuasiStaticSelection::other_cases,
// issue 39 §3): the cases of the state table's rows that do not serve the
// rate study, have a result, and whose detector stage runs at the
// selection's E under the inertial rule at I* at most the selection's (e.g.
// quasi_static_extension.toml's compression paths at I* = 1e-3, which give
// the compression side of the quasi-static ASBS); and the study's NCL case
// (study.toml `ncl`) where no rate case of the selection is a ψ_ε = 0° path,
// the isotropic state the set then has. Each case once, in the rows' order.
std::vector<std::string> QuasiStaticCompanions(const std::string& directory,
                                               const std::vector<StateRow>& rows,
                                               const RateStudy& study,
                                               const QuasiStaticSelection& selection);

// Reads the rate cases of the study folder against the rows of its state
// table, analyses them and writes the rate files; returns nullopt, and
// removes rate files of an earlier run, when there are no rate cases.
std::optional<RateStudy> WriteRateStudy(const std::string& directory,
                                        const std::vector<StateRow>& rows,
                                        const RateStudyOptions& options = {});

}  // namespace granasym::analysis
