#include "common/root_finding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace granasym {
namespace {

double Cubic(double x) { return x * x * x - 2.0 * x - 5.0; }
// The real root of x³ − 2x − 5 (Newton's example), to double precision.
constexpr double kCubicRoot = 2.0945514815423265;

IllinoisOptions WidthTolerance(double tolerance) {
  IllinoisOptions options;
  options.width_tolerance = tolerance;
  return options;
}

TEST(IllinoisRoot, FindsTheRootOfACubicToTheTolerance) {
  for (SecantFormula formula : {SecantFormula::kStepFromA, SecantFormula::kWeightedMean}) {
    IllinoisOptions options = WidthTolerance(1e-12);
    options.formula = formula;
    const IllinoisResult result = IllinoisRoot(Cubic, 2.0, Cubic(2.0), 3.0, Cubic(3.0), options);
    EXPECT_TRUE(result.converged);
    EXPECT_FALSE(result.failed);
    EXPECT_LE(result.b - result.a, 1e-12);
    EXPECT_LE(result.a, kCubicRoot);
    EXPECT_GE(result.b, kCubicRoot);
    EXPECT_EQ(result.root, result.b);
    EXPECT_EQ(result.f_root, Cubic(result.root));  // as evaluated, not halved
    EXPECT_NEAR(result.root, kCubicRoot, 1e-12);
  }
}

TEST(IllinoisRoot, FindsTheRootOfASteepExponentialToTheTolerance) {
  // e^{20x} − 10⁵ rises by 4.9·10⁸ over [0, 1]: its root is at 0.58.
  auto steep = [](double x) { return std::exp(20.0 * x) - 1e5; };
  const IllinoisResult result =
      IllinoisRoot(steep, 0.0, steep(0.0), 1.0, steep(1.0), WidthTolerance(1e-12));
  EXPECT_TRUE(result.converged);
  EXPECT_NEAR(result.root, std::log(1e5) / 20.0, 1e-12);
  EXPECT_LT(result.iterations, 40);
}

TEST(IllinoisRoot, MeasuresTheBracketInTheCallersUnitsWithTheWidthScale) {
  IllinoisOptions options = WidthTolerance(1e-9);
  options.width_scale = 1e3;  // a step of 1000 s, x its fraction
  const IllinoisResult result = IllinoisRoot(Cubic, 2.0, Cubic(2.0), 3.0, Cubic(3.0), options);
  EXPECT_TRUE(result.converged);
  EXPECT_LE((result.b - result.a) * 1e3, 1e-9);
  EXPECT_NEAR(result.root, kCubicRoot, 1e-12);
}

TEST(IllinoisRoot, CountsEveryEvaluationAsAnIteration) {
  int evaluations = 0;
  auto counted = [&evaluations](double x) {
    ++evaluations;
    return Cubic(x);
  };
  const IllinoisResult result =
      IllinoisRoot(counted, 2.0, Cubic(2.0), 3.0, Cubic(3.0), WidthTolerance(1e-12));
  EXPECT_EQ(result.iterations, evaluations);
  EXPECT_GT(result.iterations, 0);
}

TEST(IllinoisRoot, ReportsNonConvergenceWhenMaxIterationsIsTooSmall) {
  IllinoisOptions options = WidthTolerance(1e-12);
  options.max_iterations = 3;
  const IllinoisResult result = IllinoisRoot(Cubic, 2.0, Cubic(2.0), 3.0, Cubic(3.0), options);
  EXPECT_FALSE(result.converged);
  EXPECT_FALSE(result.failed);
  EXPECT_EQ(result.iterations, 3);
  EXPECT_LT(result.a, kCubicRoot);
  EXPECT_GT(result.b, kCubicRoot);
  EXPECT_GT(result.b - result.a, 1e-12);
}

TEST(IllinoisRoot, EndsWithTheBracketBeforeAnEvaluationThatFails) {
  // The first three secant points are 2.059, 2.081 and 2.098: the third fails.
  std::vector<double> evaluated;
  auto fails_above = [&evaluated](double x, double* f) {
    evaluated.push_back(x);
    if (x > 2.095) return false;
    *f = Cubic(x);
    return true;
  };
  const IllinoisResult result =
      IllinoisRoot(fails_above, 2.0, Cubic(2.0), 3.0, Cubic(3.0), WidthTolerance(1e-12));
  ASSERT_EQ(evaluated.size(), 3u);
  EXPECT_TRUE(result.failed);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 3);
  EXPECT_EQ(result.a, evaluated[1]);
  EXPECT_EQ(result.b, 3.0);
}

TEST(IllinoisRoot, ConvergesToARootAtABracketEndByHalvingTheBracket) {
  // f_b = 0: the secant point is b itself, so every step takes the midpoint.
  auto line = [](double x) { return x - 1.0; };
  const IllinoisResult result = IllinoisRoot(line, 0.0, -1.0, 1.0, 0.0, WidthTolerance(1e-12));
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 40);  // 2⁻⁴⁰ ≤ 10⁻¹² < 2⁻³⁹
  EXPECT_EQ(result.root, 1.0);
  EXPECT_EQ(result.f_root, 0.0);
}

TEST(IllinoisRoot, ReturnsARootAtABracketEndWithoutEvaluatingWhenTheInitialBracketIsTested) {
  IllinoisOptions options = WidthTolerance(1e-12);
  options.zero_test = ZeroTest::kAtB;
  options.test_initial_bracket = true;
  int evaluations = 0;
  auto line = [&evaluations](double x) {
    ++evaluations;
    return x - 1.0;
  };
  const IllinoisResult result = IllinoisRoot(line, 0.0, -1.0, 1.0, 0.0, options);
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_EQ(evaluations, 0);
  EXPECT_EQ(result.root, 1.0);
}

TEST(IllinoisRoot, StopsOnAnExactZeroAtTheEvaluatedPoint) {
  auto line = [](double x) { return 2.0 * x - 1.0; };
  IllinoisOptions options = WidthTolerance(1e-12);
  options.returned = ReturnedPoint::kLastPoint;
  const IllinoisResult result = IllinoisRoot(line, 0.0, -1.0, 1.0, 1.0, options);
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 1);
  EXPECT_EQ(result.root, 0.5);
  EXPECT_EQ(result.f_root, 0.0);
}

TEST(IllinoisRoot, CountsAnExactZeroAsPositiveUnlessItIsToReplaceB) {
  // f falls through zero at 0.5, the first secant point: a zero counted
  // positive replaces a (f_a > 0) and b stays past the crossing.
  auto falling = [](double x) { return 0.5 - x; };
  IllinoisOptions options = WidthTolerance(1e-12);
  IllinoisResult result = IllinoisRoot(falling, 0.0, 0.5, 1.0, -0.5, options);
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 1);
  EXPECT_EQ(result.a, 0.5);
  EXPECT_EQ(result.root, 1.0);
  options.zero_replaces_b = true;
  result = IllinoisRoot(falling, 0.0, 0.5, 1.0, -0.5, options);
  EXPECT_EQ(result.a, 0.0);
  EXPECT_EQ(result.root, 0.5);
  EXPECT_EQ(result.f_root, 0.0);
}

TEST(IllinoisRoot, EvaluatesTheFirstGuessFirstOrTheMidpointWhereItIsOutsideTheBracket) {
  for (const auto& [guess, expected] : {std::pair{2.25, 2.25}, std::pair{7.0, 2.5}}) {
    std::vector<double> evaluated;
    auto recorded = [&evaluated](double x) {
      evaluated.push_back(x);
      return Cubic(x);
    };
    IllinoisOptions options = WidthTolerance(1e-12);
    options.first_guess = guess;
    const IllinoisResult result = IllinoisRoot(recorded, 2.0, Cubic(2.0), 3.0, Cubic(3.0), options);
    ASSERT_FALSE(evaluated.empty());
    EXPECT_EQ(evaluated.front(), expected);
    EXPECT_NEAR(result.root, kCubicRoot, 1e-12);
  }
}

TEST(IllinoisRoot, ReportsWhichEndEachEvaluatedPointReplaced) {
  std::vector<double> evaluated;
  auto recorded = [&evaluated](double x) {
    evaluated.push_back(x);
    return Cubic(x);
  };
  double a = 2.0, b = 3.0;
  auto track = [&](BracketEnd end) { (end == BracketEnd::kA ? a : b) = evaluated.back(); };
  const IllinoisResult result =
      IllinoisRoot(recorded, 2.0, Cubic(2.0), 3.0, Cubic(3.0), WidthTolerance(1e-12), track);
  EXPECT_EQ(a, result.a);
  EXPECT_EQ(b, result.b);
}

TEST(IllinoisRoot, ReturnsTheEndWithTheSmallerResidualWhenNothingIsEvaluated) {
  IllinoisOptions options = WidthTolerance(2.0);  // wider than the bracket
  options.test_initial_bracket = true;
  options.returned = ReturnedPoint::kLastPoint;
  const IllinoisResult result = IllinoisRoot(Cubic, 2.0, Cubic(2.0), 3.0, Cubic(3.0), options);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_EQ(result.root, 2.0);  // |f(2)| = 1 < |f(3)| = 16
  EXPECT_EQ(result.f_root, -1.0);
}

TEST(IllinoisRoot, HalvingConvergesSuperlinearlyWherePlainRegulaFalsiStalls) {
  // x¹⁰ − 1/2 on [0, 1.5]: convex, so plain regula falsi keeps b = 1.5 and
  // creeps up on the root from below, linearly.
  auto f = [](double x) { return std::pow(x, 10) - 0.5; };
  const double root = std::pow(0.5, 0.1);
  // The evaluations from the first within 10⁻² of the root to the first
  // within 10⁻¹².
  auto count_from_1e2_to_1e12 = [root](const std::vector<double>& points) {
    int first = -1;
    for (int i = 0; i < static_cast<int>(points.size()); ++i) {
      const double error = std::abs(points[i] - root);
      if (first < 0 && error < 1e-2) first = i;
      if (error < 1e-12) return first < 0 ? -1 : i - first;
    }
    return -1;
  };

  std::vector<double> plain;
  double a = 0.0, b = 1.5, f_a = f(a), f_b = f(b);
  for (int iteration = 0; iteration < 1000; ++iteration) {
    const double x = a - f_a * (b - a) / (f_b - f_a);
    const double fx = f(x);
    plain.push_back(x);
    if ((fx < 0) == (f_a < 0)) {
      a = x;
      f_a = fx;
    } else {
      b = x;
      f_b = fx;
    }
  }
  EXPECT_EQ(b, 1.5);  // stalled on one end
  EXPECT_GT(b - a, 0.5);
  EXPECT_GT(count_from_1e2_to_1e12(plain), 300);

  std::vector<double> illinois;
  auto recorded = [&](double x) {
    illinois.push_back(x);
    return f(x);
  };
  const IllinoisResult result =
      IllinoisRoot(recorded, 0.0, f(0.0), 1.5, f(1.5), WidthTolerance(1e-12));
  EXPECT_TRUE(result.converged);
  EXPECT_NEAR(result.root, root, 1e-12);
  // Ten decades in at most 10 evaluations; bisection would take 33.
  const int evaluations = count_from_1e2_to_1e12(illinois);
  EXPECT_GT(evaluations, 0);
  EXPECT_LE(evaluations, 10);
}

}  // namespace
}  // namespace granasym
