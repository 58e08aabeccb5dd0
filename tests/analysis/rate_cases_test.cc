#include "analysis/rate_cases.h"

#include <gtest/gtest.h>

#include "common/error.h"

namespace granasym::analysis {
namespace {

TEST(ServesRateStudy, NamesTheRateFigureKey) {
  EXPECT_TRUE(ServesRateStudy("rate"));
  EXPECT_TRUE(ServesRateStudy("10, rate"));
  EXPECT_FALSE(ServesRateStudy("10, 16"));
  // An entry that names nothing the paper has is an error, not "no".
  EXPECT_THROW(ServesRateStudy("rates"), InputError);
}

// An ensemble row of a rate case (the replicates' mean path, case
// mean/<name>) has no case folder and is no replicate: it is not read.
TEST(ReadRateCases, LeavesTheEnsembleRowsOut) {
  study::StateRow row;
  row.case_id = "mean/nc100_psi90_I0.1";
  row.case_name = "nc100_psi90_I0.1";
  row.stage = "psi90";
  row.figures = "rate";
  row.replicate = 0;
  row.source = study::TableSource::kEnsemble;
  row.kind = study::TableKind::kCsl;
  row.status = study::TableStatus::kDetected;
  const RateCases cases = ReadRateCases("/nonexistent-study", {row});
  EXPECT_TRUE(cases.states.empty());
  row.source = study::TableSource::kReplicate;  // a replicate's row is read: its folder is missing
  EXPECT_ANY_THROW(ReadRateCases("/nonexistent-study", {row}));
}

}  // namespace
}  // namespace granasym::analysis
