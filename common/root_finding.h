// The Illinois method (modified regula falsi) on a bracket [a, b] with a sign
// change, shared by the root location of the RKF23 and SUNDIALS integrators
// and the ψ_ε → ψ_σ inversion of the asymptote predictor. Each step takes the
// secant point x of (a, f_a) and (b, f_b) (the midpoint where that point is
// not strictly inside the bracket), replaces the end whose f has the sign of
// f(x), and halves the f of the other end when the same end was replaced
// twice in a row (which keeps plain regula falsi from stalling on one end:
// superlinear convergence, order ≈ 1.44). The options reproduce each caller's
// loop exactly: the secant formula, where an exact zero goes, which value of
// f must be zero to stop, whether the stopping tests apply to the initial
// bracket and which point is returned.
#pragma once

#include <cmath>
#include <optional>
#include <type_traits>
#include <utility>

namespace granasym {

// How the secant point of (a, f_a) and (b, f_b) is computed (the two forms
// round differently).
enum class SecantFormula {
  kStepFromA,     // a − f_a (b − a)/(f_b − f_a)
  kWeightedMean,  // (f_b a − f_a b)/(f_b − f_a)
};

// Which exact zero of f ends the iteration.
enum class ZeroTest {
  kAtLastPoint,  // f(x) = 0 at the last evaluated point
  kAtB,          // f_b = 0 (an initial f_b = 0 too, with test_initial_bracket)
};

// The point the result reports as the root.
enum class ReturnedPoint {
  // b: the end past the crossing when f_a ≠ 0 (an integrator restarted there
  // does not see the same crossing again).
  kB,
  // The last evaluated point; before any evaluation the end with the smaller
  // |f| (b on a tie).
  kLastPoint,
};

struct IllinoisOptions {
  // Stop when (b − a)·width_scale ≤ width_tolerance (not > : a NaN width
  // stops); width_scale turns the bracket into the caller's units.
  double width_tolerance = 0.0;
  double width_scale = 1.0;
  // The most evaluations of f.
  int max_iterations = 100;
  // The first point to evaluate instead of the secant point (still replaced
  // by the midpoint where it is not strictly inside the bracket).
  std::optional<double> first_guess;
  SecantFormula formula = SecantFormula::kStepFromA;
  // Whether an exact zero f(x) = 0 replaces b; otherwise it counts as
  // positive: x replaces a where (f(x) < 0) == (f_a < 0), b elsewhere.
  bool zero_replaces_b = false;
  ZeroTest zero_test = ZeroTest::kAtLastPoint;
  // Whether the stopping tests (the bracket width, and f_b = 0 for kAtB) are
  // applied before the first evaluation too; otherwise f is evaluated at
  // least once.
  bool test_initial_bracket = false;
  ReturnedPoint returned = ReturnedPoint::kB;
};

// Which end of the bracket an evaluated point replaced.
enum class BracketEnd { kA, kB };

struct IllinoisResult {
  double root = 0.0;    // as chosen by IllinoisOptions::returned
  double f_root = 0.0;  // f(root), as evaluated (not halved)
  // The final bracket (f_a, f_b as halved by the method, not f(a), f(b)).
  double a = 0.0, f_a = 0.0, b = 0.0, f_b = 0.0;
  int iterations = 0;      // evaluations of f, a failed one included
  bool converged = false;  // a stopping test held
  bool failed = false;     // an evaluation of f failed (the bracket is the one before it)
};

// The Illinois method on [a, b] (a < b) from f_a = f(a) and f_b = f(b) of
// opposite signs (or zero). `f` is either `double f(double x)` or
// `bool f(double x, double* fx)`, which returns false when it cannot be
// evaluated at x (the iteration then ends with `failed`). `on_replace(end)`
// is called after each evaluation with the end that x replaced (callers keep
// the state belonging to an end). Per iteration: the stopping tests (not
// before the first evaluation unless test_initial_bracket), max_iterations,
// the secant point, the evaluation, the replacement and the halving.
template <typename F, typename OnReplace>
IllinoisResult IllinoisRoot(F&& f, double a, double f_a, double b, double f_b,
                            const IllinoisOptions& options, OnReplace&& on_replace) {
  IllinoisResult result;
  double fx = 0.0;
  double f_of_b = f_b;  // f(b) before any halving
  int side = 0;         // −1: a was replaced last, +1: b
  while (true) {
    if (result.iterations > 0 || options.test_initial_bracket) {
      const bool zero =
          options.zero_test == ZeroTest::kAtB ? f_b == 0.0 : result.iterations > 0 && fx == 0.0;
      if (zero || !((b - a) * options.width_scale > options.width_tolerance)) {
        result.converged = true;
        break;
      }
    }
    if (result.iterations >= options.max_iterations) break;
    double x;
    if (result.iterations == 0 && options.first_guess) {
      x = *options.first_guess;
    } else if (options.formula == SecantFormula::kStepFromA) {
      x = a - f_a * (b - a) / (f_b - f_a);
    } else {
      x = (f_b * a - f_a * b) / (f_b - f_a);
    }
    if (!(x > a && x < b)) x = 0.5 * (a + b);
    ++result.iterations;
    if constexpr (std::is_invocable_r_v<bool, F&, double, double*>) {
      if (!f(x, &fx)) {
        result.failed = true;
        break;
      }
    } else {
      fx = f(x);
    }
    if ((fx < 0) == (f_a < 0) && !(options.zero_replaces_b && fx == 0.0)) {
      a = x;
      f_a = fx;
      on_replace(BracketEnd::kA);
      if (side == -1) f_b *= 0.5;
      side = -1;
    } else {
      b = x;
      f_b = f_of_b = fx;
      on_replace(BracketEnd::kB);
      if (side == 1) f_a *= 0.5;
      side = 1;
    }
    result.root = x;
    result.f_root = fx;
  }
  result.a = a;
  result.f_a = f_a;
  result.b = b;
  result.f_b = f_b;
  if (options.returned == ReturnedPoint::kB) {
    result.root = b;
    result.f_root = f_of_b;
  } else if (result.iterations == 0 || (result.failed && result.iterations == 1)) {
    const bool take_a = std::abs(f_a) < std::abs(f_b);
    result.root = take_a ? a : b;
    result.f_root = take_a ? f_a : f_b;
  }
  return result;
}

template <typename F>
IllinoisResult IllinoisRoot(F&& f, double a, double f_a, double b, double f_b,
                            const IllinoisOptions& options) {
  return IllinoisRoot(std::forward<F>(f), a, f_a, b, f_b, options, [](BracketEnd) {});
}

}  // namespace granasym
