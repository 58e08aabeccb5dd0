// The weighted-sum Pareto sweep over two groups of residuals.
#include "calibration/pareto.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

#include "common/error.h"

namespace granasym::calibration {

namespace {

// The group costs C_g and the other residuals' cost at `values`; false when
// the model is undefined there.
bool GroupCosts(const CalibrationProblem& problem, const ResidualGroups& groups,
                const std::vector<double>& values, std::array<double, 2>* cost) {
  const std::vector<int>& free = problem.free_indices();
  std::vector<double> x;
  for (int i : free) x.push_back(values[i]);
  std::vector<double> r(static_cast<size_t>(problem.num_residuals()));
  std::string why;
  if (!problem.Residuals(x.data(), r.data(), &why)) return false;
  // The asymptotic states' residuals come first, one run per fitted point
  // (ResidualPoints); the unloading and path residuals after them belong to
  // neither group: they keep their weight in every fit of the sweep.
  const std::vector<std::pair<int, int>> owners = problem.ResidualPoints();
  GRANASYM_CHECK(owners.size() <= r.size())
      << owners.size() << " grouped residuals, " << r.size() << " residuals";
  *cost = {0, 0};
  for (size_t j = 0; j < owners.size(); ++j) {
    const int g = groups.point_group[owners[j].first][owners[j].second];
    if (g >= 0) (*cost)[g] += 0.5 * r[j] * r[j];
  }
  if (groups.path_group >= 0) {
    const ResidualRange paths = problem.Group(ResidualGroup::kPath);
    for (int j = paths.begin; j < paths.begin + paths.count; ++j) {
      (*cost)[groups.path_group] += 0.5 * r[j] * r[j];
    }
  }
  return std::isfinite((*cost)[0]) && std::isfinite((*cost)[1]);
}

// The problem with group 0's points weighted by 2w and group 1's by 2(1 − w),
// starting from `start` (a full vector).
CalibrationProblem Weighted(const CalibrationProblem& problem, const ResidualGroups& groups,
                            double w, const std::vector<double>& start) {
  std::vector<StateDataset> datasets = problem.datasets();
  for (size_t d = 0; d < datasets.size(); ++d) {
    for (size_t k = 0; k < datasets[d].points.size(); ++k) {
      const int g = groups.point_group[d][k];
      if (g >= 0) datasets[d].points[k].weight *= 2.0 * (g == 0 ? w : 1.0 - w);
    }
  }
  ModelParameters parameters = problem.parameters();
  for (int i : problem.free_indices()) {
    ParameterSpec& spec = parameters.mutable_specs()[i];
    spec.value = std::min(std::max(start[i], spec.lower), spec.upper);
  }
  CalibrationProblem weighted(std::move(datasets), std::move(parameters),
                              problem.predictor().options(), problem.paths());
  double path_weight = problem.group_weight(ResidualGroup::kPath);
  if (groups.path_group >= 0) path_weight *= 2.0 * (groups.path_group == 0 ? w : 1.0 - w);
  weighted.SetGroupWeights(problem.group_weight(ResidualGroup::kAsymptotic), path_weight);
  return weighted;
}

}  // namespace

int ResidualGroups::Residuals(const CalibrationProblem& problem, int g) const {
  int count = 0;
  for (const auto& [d, k] : problem.ResidualPoints()) count += point_group[d][k] == g ? 1 : 0;
  if (path_group == g) count += problem.Group(ResidualGroup::kPath).count;
  return count;
}

ResidualGroups DefaultResidualGroups(const CalibrationProblem& problem) {
  ResidualGroups groups;
  groups.names = {"ncl_compression", "csl_extension"};
  groups.descriptions = {"NCL, compression and ASBS states", "critical and extension states"};
  for (const StateDataset& dataset : problem.datasets()) {
    std::vector<int> row;
    for (const AsymptoticStatePoint& point : dataset.points) {
      switch (point.kind) {
        case StateKind::kNcl:
        case StateKind::kCompression:
        case StateKind::kAsbs:
          row.push_back(0);
          break;
        case StateKind::kCsl:
        case StateKind::kExtension:
          row.push_back(1);
          break;
        case StateKind::kUnloading:
          row.push_back(-1);
          break;
      }
    }
    groups.point_group.push_back(std::move(row));
  }
  return groups;
}

ResidualGroups AsymptoticPathGroups(const CalibrationProblem& problem) {
  const int paths = problem.Group(ResidualGroup::kPath).count;
  GRANASYM_CHECK(paths > 0) << "asymptotic states against whole paths: the problem has no paths";
  ResidualGroups groups;
  groups.names = {"asymptotic_states", "whole_paths"};
  groups.descriptions = {"asymptotic states (NCL, CSL, compression, extension, ASBS)",
                         "whole paths (unloading branches and path datasets)"};
  for (const StateDataset& dataset : problem.datasets()) {
    std::vector<int> row;
    for (const AsymptoticStatePoint& point : dataset.points) {
      // An unloading point's residual (a branch) is a path residual.
      row.push_back(point.kind == StateKind::kUnloading ? -1 : 0);
    }
    groups.point_group.push_back(std::move(row));
  }
  groups.path_group = 1;
  groups.choice = fmt::format(
      "asymptotic states against whole paths ({} path residuals: unloading branches and path "
      "datasets): the two kinds of data the model cannot match at once",
      paths);
  return groups;
}

ResidualGroups ChooseResidualGroups(const CalibrationProblem& problem) {
  if (problem.Group(ResidualGroup::kPath).count > 0) return AsymptoticPathGroups(problem);
  ResidualGroups groups = DefaultResidualGroups(problem);
  groups.choice =
      "the compression side against the critical and extension states: the data hold no "
      "whole paths or fitted unloading branches to trade against the asymptotic states";
  return groups;
}

bool ParetoOptions::IsValid(std::string* why) const {
  if (points < 5 || points % 2 == 0 || points > 101) {
    *why = fmt::format(
        "pareto points = {} must be odd and in [5, 101] (the middle one is the "
        "ordinary fit)",
        points);
    return false;
  }
  if (!(max_weight_ratio > 1 && max_weight_ratio <= 1e8)) {
    *why = fmt::format("pareto max_weight_ratio = {} must be in (1, 1e8]", max_weight_ratio);
    return false;
  }
  if (min_distinct < 0 || max_refinements < 0 || !(min_refine_decades > 0) ||
      !(merge_tolerance >= 0 && merge_tolerance < 1)) {
    *why = fmt::format(
        "pareto refinement: min_distinct = {} and max_refinements = {} must be >= 0, "
        "min_refine_decades = {} > 0 and merge_tolerance = {} in [0, 1)",
        min_distinct, max_refinements, min_refine_decades, merge_tolerance);
    return false;
  }
  return true;
}

std::string ParetoPoint::Label() const {
  if (weight_low == weight_high) return fmt::format("w = {:.3g}", weight_low);
  return fmt::format("w = {:.3g} to {:.3g}", weight_low, weight_high);
}

void MergeDistinctPoints(ParetoFront* front, double merge_tolerance, double label_spacing) {
  std::vector<ParetoPoint>& points = front->points;
  front->distinct = 0;
  if (points.empty()) return;
  std::array<double, 2> low, high, rms_low, rms_high;
  for (int g = 0; g < 2; ++g) {
    low[g] = high[g] = points.front().cost[g];
    rms_low[g] = rms_high[g] = points.front().rms[g];
    for (const ParetoPoint& p : points) {
      low[g] = std::min(low[g], p.cost[g]), high[g] = std::max(high[g], p.cost[g]);
      rms_low[g] = std::min(rms_low[g], p.rms[g]), rms_high[g] = std::max(rms_high[g], p.rms[g]);
    }
  }
  // Neighbours within the tolerance of the distinct point's first one.
  size_t first = 0;
  for (size_t j = 0; j < points.size(); ++j) {
    bool same = j > 0;
    for (int g = 0; g < 2 && same; ++g) {
      const double scale = std::max(high[g] - low[g], 1e-12 * std::max(std::abs(high[g]), 1e-300));
      same = std::abs(points[j].cost[g] - points[first].cost[g]) <= merge_tolerance * scale;
    }
    if (!same) {
      first = j;
      ++front->distinct;
    }
    points[j].distinct = front->distinct - 1;
  }
  for (ParetoPoint& p : points) {
    p.weight_low = p.weight_high = p.weight;
    p.labelled = false;
  }
  std::vector<size_t> firsts;  // the first point of each distinct point
  for (size_t j = 0; j < points.size(); ++j) {
    if (j == 0 || points[j].distinct != points[j - 1].distinct) firsts.push_back(j);
  }
  for (size_t d = 0; d < firsts.size(); ++d) {
    const size_t end = d + 1 < firsts.size() ? firsts[d + 1] : points.size();
    for (size_t j = firsts[d]; j < end; ++j) {
      points[j].weight_low = points[firsts[d]].weight;
      points[j].weight_high = points[end - 1].weight;
    }
  }
  // Labels: the compromise's, the ordinary fit's and the ends' first, then
  // any far enough from every label drawn.
  std::vector<size_t> order;
  const auto first_of = [&](int j) { return firsts[static_cast<size_t>(points[j].distinct)]; };
  if (front->compromise >= 0 && front->compromise < static_cast<int>(points.size())) {
    order.push_back(first_of(front->compromise));
  }
  if (front->ordinary >= 0 && front->ordinary < static_cast<int>(points.size())) {
    order.push_back(first_of(front->ordinary));
  }
  order.push_back(firsts.front());
  order.push_back(firsts.back());
  const size_t always = order.size();
  order.insert(order.end(), firsts.begin(), firsts.end());
  std::vector<std::array<double, 2>> drawn;
  for (size_t k = 0; k < order.size(); ++k) {
    ParetoPoint& p = points[order[k]];
    if (p.labelled) continue;
    std::array<double, 2> at;
    for (int g = 0; g < 2; ++g) {
      at[g] = rms_high[g] > rms_low[g] ? (p.rms[g] - rms_low[g]) / (rms_high[g] - rms_low[g]) : 0;
    }
    bool apart = true;
    for (const auto& other : drawn) {
      apart = apart && std::hypot(at[0] - other[0], at[1] - other[1]) >= label_spacing;
    }
    if (k < always || apart) {
      p.labelled = true;
      drawn.push_back(at);
    }
  }
}

bool ParetoFront::Monotone(double tolerance) const {
  for (size_t j = 1; j < points.size(); ++j) {
    const ParetoPoint &a = points[j - 1], &b = points[j];
    if (b.cost[0] > a.cost[0] + tolerance * std::max(a.cost[0], b.cost[0])) return false;
    if (b.cost[1] < a.cost[1] - tolerance * std::max(a.cost[1], b.cost[1])) return false;
  }
  return true;
}

ParetoFront ComputeParetoFront(const CalibrationProblem& problem, const FitResult& fit,
                               const ResidualGroups& groups, const CeresFitter::Options& ceres,
                               const ParetoOptions& options) {
  std::string why;
  GRANASYM_CHECK(options.IsValid(&why)) << why;
  GRANASYM_CHECK(groups.point_group.size() == problem.datasets().size());
  const auto t0 = std::chrono::steady_clock::now();
  ParetoFront front;
  front.groups = groups;
  for (int g = 0; g < 2; ++g) front.residuals[g] = groups.Residuals(problem, g);
  for (int g = 0; g < 2; ++g) {
    if (front.residuals[g] == 0) {
      front.not_computed =
          fmt::format("no trade-off to compute: the group {} ({}) has no fitted residuals",
                      groups.names[g], groups.descriptions[g]);
      return front;
    }
  }
  if (!fit.summary.success()) {
    front.not_computed = "no successful fit to start the sweep from";
    return front;
  }
  // The sweep's fits run to Ceres's tolerances, not to a stall
  // (CeresFitter::Options::stall_deviance): the front's points are compared
  // with one another (duplicates merged, monotone costs) far more finely
  // than a profile's threshold.
  CeresFitter::Options refit_options = CeresFitter::CostRefitOptions(ceres, options.fast_refits);
  refit_options.stall_deviance = 0;
  const int n = options.points, mid = n / 2;
  const double span = std::log10(options.max_weight_ratio);
  front.points.resize(static_cast<size_t>(n));
  // Written by both sides of the sweep at distinct indices: not vector<bool>.
  std::vector<char> done(static_cast<size_t>(n), 0);
  std::vector<std::string> side_warnings[2];
  std::mutex shared_problem;  // GroupCosts evaluates `problem` (its evaluation counter)
  std::atomic<long> evaluations{0};
  // The fit at point->weight from `start` (a full vector), with its group
  // costs; false, with a warning, when it fails or the model is undefined there.
  const auto fit_at = [&](ParetoPoint* point, const std::vector<double>& start,
                          std::vector<std::string>* warnings) {
    try {
      const CalibrationProblem weighted = Weighted(problem, groups, point->weight, start);
      const FitResult result = CeresFitter(refit_options).Fit(weighted);
      evaluations += result.summary.evaluations;
      if (!result.summary.success()) {
        warnings->push_back(fmt::format("pareto: the fit at w = {:.4g} failed: {}", point->weight,
                                        result.summary.message));
        return false;
      }
      point->values = result.values;
      point->converged = result.summary.termination == FitTermination::kConverged;
    } catch (const std::exception& error) {
      warnings->push_back(
          fmt::format("pareto: the fit at w = {:.4g} failed: {}", point->weight, error.what()));
      return false;
    }
    return true;
  };
  const auto costs_at = [&](ParetoPoint* point, std::vector<std::string>* warnings) {
    bool defined;
    {
      const std::lock_guard<std::mutex> lock(shared_problem);
      defined = GroupCosts(problem, groups, point->values, &point->cost);
    }
    if (!defined) {
      warnings->push_back(
          fmt::format("pareto: the model is undefined at the fit for w = {:.4g}", point->weight));
      return false;
    }
    for (int g = 0; g < 2; ++g) {
      point->rms[g] = std::sqrt(2.0 * point->cost[g] / front.residuals[g]);
    }
    return true;
  };
  const auto solve = [&](int j, const std::vector<double>& start) {
    std::vector<std::string>& warnings = side_warnings[j < mid ? 1 : 0];
    ParetoPoint& point = front.points[j];
    const double ratio = std::pow(10.0, -span + 2.0 * span * j / (n - 1));
    point.weight = j == mid ? 0.5 : ratio / (1.0 + ratio);
    if (j == mid) {
      point.values = fit.values;  // the ordinary fit itself
      point.converged = fit.summary.termination == FitTermination::kConverged;
    } else if (!fit_at(&point, start, &warnings)) {
      return false;
    }
    if (!costs_at(&point, &warnings)) return false;
    done[j] = 1;
    return true;
  };
  solve(mid, fit.values);
  // The two sides of the sweep, each warm-started outwards from the ordinary
  // fit, are independent: the lower side on a second thread where there is
  // one (the points do not depend on it).
  const auto side = [&](int step) {
    std::vector<double> start = fit.values;
    for (int j = mid + step; j >= 0 && j < n; j += step) {
      if (solve(j, start)) start = front.points[j].values;
    }
  };
  // Runs a and b, on two threads where there are two; rethrows what either threw.
  const auto both = [](const std::function<void()>& a, const std::function<void()>& b) {
    if (std::thread::hardware_concurrency() < 2) {
      a();
      b();
      return;
    }
    std::exception_ptr b_error;
    std::thread second([&] {
      try {
        b();
      } catch (...) {
        b_error = std::current_exception();
      }
    });
    try {
      a();
    } catch (...) {
      second.join();
      throw;
    }
    second.join();
    if (b_error) std::rethrow_exception(b_error);
  };
  both([&] { side(+1); }, [&] { side(-1); });
  for (int k : {0, 1}) {
    front.warnings.insert(front.warnings.end(), side_warnings[k].begin(), side_warnings[k].end());
  }
  std::vector<ParetoPoint> kept;
  for (int j = 0; j < n; ++j) {
    if (done[j]) kept.push_back(front.points[j]);
  }
  front.points = std::move(kept);
  const auto find_ordinary = [&] {
    front.ordinary = -1;
    for (size_t j = 0; j < front.points.size(); ++j) {
      if (!front.points[j].refined && front.points[j].weight == 0.5)
        front.ordinary = static_cast<int>(j);
    }
  };
  find_ordinary();
  if (front.points.empty() || front.ordinary < 0) {
    front.evaluations = evaluations;
    front.not_computed = "no point of the sweep could be computed (its warnings say why)";
    front.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return front;
  }
  // Refinement where the front moves, while it has too few distinct points.
  const auto x_of = [](double w) { return std::log10(w / (1.0 - w)); };
  std::vector<double> failed_x;
  for (;;) {
    MergeDistinctPoints(&front, options.merge_tolerance);
    if (front.distinct >= options.min_distinct) {
      if (front.refinements > 0) {
        front.refinement = fmt::format(
            "the uniform sweep gave fewer than {} distinct points: {} fits added where the front "
            "moves (bisecting w/(1 - w) between neighbouring distinct points)",
            options.min_distinct, front.refinements);
      }
      break;
    }
    if (front.refinements >= options.max_refinements) {
      front.refinement = fmt::format(
          "{} distinct points, fewer than {}: the refinement stopped at its limit of {} added "
          "fits",
          front.distinct, options.min_distinct, options.max_refinements);
      break;
    }
    std::array<double, 2> low, high;
    for (int g = 0; g < 2; ++g) {
      low[g] = high[g] = front.points.front().cost[g];
      for (const ParetoPoint& p : front.points) {
        low[g] = std::min(low[g], p.cost[g]), high[g] = std::max(high[g], p.cost[g]);
      }
    }
    struct Gap {
      size_t j;
      double distance, x;
    };
    std::vector<Gap> gaps;
    for (size_t j = 0; j + 1 < front.points.size(); ++j) {
      const ParetoPoint &a = front.points[j], &b = front.points[j + 1];
      if (a.distinct == b.distinct) continue;
      const double xa = x_of(a.weight), xb = x_of(b.weight), x = 0.5 * (xa + xb);
      if (xb - xa < 2 * options.min_refine_decades) continue;
      if (std::any_of(failed_x.begin(), failed_x.end(),
                      [&](double f) { return std::abs(f - x) < 1e-12; })) {
        continue;
      }
      double distance = 0;
      for (int g = 0; g < 2; ++g) {
        const double range = high[g] > low[g] ? high[g] - low[g] : 1.0;
        distance = std::hypot(distance, (b.cost[g] - a.cost[g]) / range);
      }
      gaps.push_back({j, distance, x});
    }
    if (gaps.empty()) {
      front.refinement = fmt::format(
          "{} distinct points, fewer than {}: no two neighbouring distinct points lie more than "
          "{:g} decades of w/(1 - w) apart, so the refinement stopped after {} added fits (the "
          "front jumps there: a weighted sum finds no point in between)",
          front.distinct, options.min_distinct, 2 * options.min_refine_decades, front.refinements);
      break;
    }
    std::stable_sort(gaps.begin(), gaps.end(),
                     [](const Gap& a, const Gap& b) { return a.distance > b.distance; });
    const size_t count = std::min<size_t>(
        {gaps.size(), 2, static_cast<size_t>(options.max_refinements - front.refinements)});
    std::vector<ParetoPoint> added(count);
    std::vector<std::vector<double>> starts(count);
    std::vector<std::vector<std::string>> refine_warnings(count);
    std::vector<char> ok(count, 0);
    for (size_t k = 0; k < count; ++k) {
      const double ratio = std::pow(10.0, gaps[k].x);
      added[k].weight = ratio / (1.0 + ratio);
      added[k].refined = true;
      // From the neighbour of lower weighted cost at the new weight.
      const ParetoPoint &a = front.points[gaps[k].j], &b = front.points[gaps[k].j + 1];
      const double w = added[k].weight;
      const auto weighted = [w](const ParetoPoint& p) {
        return w * p.cost[0] + (1 - w) * p.cost[1];
      };
      starts[k] = weighted(a) <= weighted(b) ? a.values : b.values;
    }
    const auto refine = [&](size_t k) {
      if (k >= count) return;
      ok[k] = fit_at(&added[k], starts[k], &refine_warnings[k]) &&
              costs_at(&added[k], &refine_warnings[k]);
    };
    both([&] { refine(0); }, [&] { refine(1); });
    front.refinements += static_cast<int>(count);
    for (size_t k = 0; k < count; ++k) {
      front.warnings.insert(front.warnings.end(), refine_warnings[k].begin(),
                            refine_warnings[k].end());
      if (ok[k]) {
        front.points.push_back(added[k]);
      } else {
        failed_x.push_back(gaps[k].x);
      }
    }
    std::stable_sort(
        front.points.begin(), front.points.end(),
        [](const ParetoPoint& a, const ParetoPoint& b) { return a.weight < b.weight; });
    find_ordinary();
  }
  front.evaluations = evaluations;
  for (const ParetoPoint& point : front.points) {
    if (!point.converged) {
      front.warnings.push_back(
          fmt::format("pareto: the fit at w = {:.4g} stopped before converging", point.weight));
    }
  }
  // Normalised costs and the knee.
  std::array<double, 2> low, high;
  for (int g = 0; g < 2; ++g) {
    low[g] = high[g] = front.points[front.ordinary].cost[g];
    for (const ParetoPoint& point : front.points) {
      low[g] = std::min(low[g], point.cost[g]);
      high[g] = std::max(high[g], point.cost[g]);
    }
  }
  front.trade_off = true;
  for (int g = 0; g < 2; ++g) {
    if (!(high[g] - low[g] > 1e-6 * std::max(high[g], 1e-300))) front.trade_off = false;
  }
  double best = std::numeric_limits<double>::infinity();
  for (size_t j = 0; j < front.points.size(); ++j) {
    ParetoPoint& point = front.points[j];
    for (int g = 0; g < 2; ++g) {
      point.normalised[g] = front.trade_off ? (point.cost[g] - low[g]) / (high[g] - low[g]) : 0.0;
    }
    const double distance = std::hypot(point.normalised[0], point.normalised[1]);
    if (front.trade_off && distance < best) {
      best = distance;
      front.compromise = static_cast<int>(j);
    }
  }
  if (!front.trade_off) {
    front.compromise = front.ordinary;
    front.rule =
        "no trade-off: the two groups' costs change by less than 1e-6 over the front (the "
        "groups agree), so the compromise is the ordinary fit";
  } else {
    const ParetoPoint& c = front.points[front.compromise];
    front.rule = fmt::format(
        "the knee: the point closest to the utopia point (each group's least cost on the front) "
        "in costs normalised by their range on the front (w = {:.4g}, normalised costs {:.3f} "
        "and {:.3f}); it gives up equal fractions of what each group can gain, whatever the "
        "groups' sizes and units{}",
        c.weight, c.normalised[0], c.normalised[1],
        front.compromise == front.ordinary ? "; it is the ordinary fit (w = 0.5)" : "");
  }
  MergeDistinctPoints(&front, options.merge_tolerance);  // the labels, with the compromise's
  front.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return front;
}

std::string ParetoCsv(const ParetoFront& front, const ModelParameters& parameters) {
  const std::string &a = front.groups.names[0], &b = front.groups.names[1];
  std::string csv = fmt::format(
      "weight,cost_{0},cost_{1},rms_{0},rms_{1},normalised_{0},normalised_{1},converged,"
      "compromise,ordinary,distinct,weight_low,weight_high,label,labelled,refined,group_0,"
      "group_1",
      a, b);
  for (const ParameterSpec& spec : parameters.specs()) csv += "," + spec.name;
  csv += "\n";
  for (size_t j = 0; j < front.points.size(); ++j) {
    const ParetoPoint& p = front.points[j];
    csv += fmt::format("{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{},{},{}", p.weight,
                       p.cost[0], p.cost[1], p.rms[0], p.rms[1], p.normalised[0], p.normalised[1],
                       p.converged ? 1 : 0, static_cast<int>(j) == front.compromise ? 1 : 0,
                       static_cast<int>(j) == front.ordinary ? 1 : 0);
    csv += fmt::format(",{},{:.10g},{:.10g},{},{},{}", p.distinct, p.weight_low, p.weight_high,
                       p.Label(), p.labelled ? 1 : 0, p.refined ? 1 : 0);
    csv += "," + a + "," + b;
    for (double v : p.values) csv += fmt::format(",{:.10g}", v);
    csv += "\n";
  }
  return csv;
}

std::string ParetoText(const ParetoFront& front, const ModelParameters& parameters) {
  if (!front.computed()) return "pareto front: not computed: " + front.not_computed + "\n";
  std::string s = fmt::format(
      "pareto front: {} (group 0, {} residuals) against {} (group 1, {} residuals), "
      "weighted-sum sweep of {} points ({} refined), {} evaluations, {:.2f} s\n"
      "  (w weights group 0; cost_g = 1/2 sum r^2 over group g, rms_g its RMS weighted "
      "residual)\n",
      front.groups.names[0], front.residuals[0], front.groups.names[1], front.residuals[1],
      front.points.size(), front.refinements, front.evaluations, front.wall_seconds);
  if (!front.groups.choice.empty()) s += "  groups traded: " + front.groups.choice + "\n";
  // The distinct points, and the weight ranges that gave one point.
  std::string merged;
  for (size_t j = 0; j < front.points.size(); ++j) {
    const ParetoPoint& p = front.points[j];
    if (p.weight_low != p.weight_high && p.weight == p.weight_low) {
      merged += (merged.empty() ? "" : "; ") + p.Label();
    }
  }
  s += fmt::format("  distinct points: {} of {}{}\n", front.distinct, front.points.size(),
                   merged.empty() ? std::string()
                                  : " (one point each, the fits being the same within the "
                                    "merging tolerance: " +
                                        merged + ")");
  if (!front.refinement.empty()) s += "  refinement: " + front.refinement + "\n";
  s += fmt::format("  {:>10} {:>12} {:>12} {:>10} {:>10}", "w", "cost_0", "cost_1", "rms_0",
                   "rms_1");
  for (const ParameterSpec& spec : parameters.specs()) {
    if (spec.free) s += fmt::format(" {:>11}", spec.name);
  }
  s += "\n";
  for (size_t j = 0; j < front.points.size(); ++j) {
    const ParetoPoint& p = front.points[j];
    s += fmt::format("  {:>10.4g} {:>12.6g} {:>12.6g} {:>10.4g} {:>10.4g}", p.weight, p.cost[0],
                     p.cost[1], p.rms[0], p.rms[1]);
    for (size_t i = 0; i < parameters.specs().size(); ++i) {
      if (parameters.specs()[i].free) s += fmt::format(" {:>11.5g}", p.values[i]);
    }
    const bool c = static_cast<int>(j) == front.compromise,
               o = static_cast<int>(j) == front.ordinary;
    s += c && o ? "  compromise, ordinary fit" : c ? "  compromise" : o ? "  ordinary fit" : "";
    s += p.refined ? "  (refined)" : "";
    s += "\n";
  }
  s += "  compromise: " + front.rule + "\n";
  for (const std::string& w : front.warnings) s += "  WARNING: " + w + "\n";
  return s;
}

}  // namespace granasym::calibration
