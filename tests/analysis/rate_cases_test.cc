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

}  // namespace
}  // namespace granasym::analysis
