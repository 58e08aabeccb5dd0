// RKF23 with step control (Mašín's reference scheme) and root location.
#include "constitutive/rkf23_integrator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/root_finding.h"
#include "common/stopwatch.h"

namespace granasym {

namespace {

struct Workspace {
  std::vector<double> k1, k2, k3, stage, low, high;
  explicit Workspace(int n) : k1(n), k2(n), k3(n), stage(n), low(n), high(n) {}
};

// Whether x satisfies the sign constraints (SUNDIALS coding, see OdeSystem).
bool SatisfiesConstraints(const std::vector<double>& codes, const double* x) {
  for (size_t i = 0; i < codes.size(); ++i) {
    const double c = codes[i];
    if ((c == 1.0 && !(x[i] >= 0)) || (c == 2.0 && !(x[i] > 0)) || (c == -1.0 && !(x[i] <= 0)) ||
        (c == -2.0 && !(x[i] < 0))) {
      return false;
    }
  }
  return true;
}

// One RKF23 step of size h from (t, y). Returns false when a stage fails or
// the result violates the sign constraints (`codes`, empty for none).
bool TakeStep(OdeSystem& system, double t, const double* y, double h, Workspace* w,
              long* evaluations, const std::vector<double>& codes = {}) {
  const int n = system.dimension();
  ++*evaluations;
  if (!system.Rhs(t, y, w->k1.data())) return false;
  for (int i = 0; i < n; ++i) w->stage[i] = y[i] + 0.5 * h * w->k1[i];
  ++*evaluations;
  if (!system.Rhs(t + 0.5 * h, w->stage.data(), w->k2.data())) return false;
  for (int i = 0; i < n; ++i) w->stage[i] = y[i] - h * w->k1[i] + 2.0 * h * w->k2[i];
  ++*evaluations;
  if (!system.Rhs(t + h, w->stage.data(), w->k3.data())) return false;
  for (int i = 0; i < n; ++i) {
    w->low[i] = y[i] + h * w->k2[i];
    w->high[i] = y[i] + h * (w->k1[i] + 4.0 * w->k2[i] + w->k3[i]) / 6.0;
    if (!std::isfinite(w->high[i])) return false;
  }
  return SatisfiesConstraints(codes, w->high.data());
}

}  // namespace

IntegrationSummary Rkf23Integrator::Integrate(OdeSystem& system, double t0, double t_end, double* y,
                                              const std::vector<double>& output_times,
                                              const Observer& observer) {
  Stopwatch stopwatch;
  IntegrationSummary summary;
  const int n = system.dimension();
  std::vector<double> scale(n);
  std::vector<double> stops;
  for (double t : output_times) {
    if (t > t0 && t < t_end) stops.push_back(t);
  }
  std::sort(stops.begin(), stops.end());
  stops.push_back(t_end);
  size_t next_stop = 0;

  const int num_roots = system.num_roots();
  std::vector<double> g_old(num_roots), g_new(num_roots);
  if (num_roots > 0) system.Roots(t0, y, g_old.data());

  Workspace w(n);
  std::vector<double> codes(n);
  if (!system.Constraints(codes.data())) codes.clear();
  const bool fixed = options_.fixed_step > 0;
  const double interval = t_end - t0;
  double h = fixed ? options_.fixed_step
                   : (options_.initial_step > 0 ? options_.initial_step : 0.01 * interval);
  const double min_step = options_.rkf23_min_step_fraction * interval;
  double t = t0;
  summary.termination = TerminationType::kReachedEnd;
  while (t < t_end) {
    if (summary.steps >= options_.max_steps) {
      summary.termination = TerminationType::kFailure;
      summary.message = fmt::format("more than max_steps = {} steps", options_.max_steps);
      break;
    }
    const double target = stops[next_stop];
    if (options_.max_step > 0) h = std::min(h, options_.max_step);
    bool hits_stop = false;
    double step = h;
    if (t + step >= target * (1.0 - 1e-15) - 1e-300) {
      step = target - t;
      hits_stop = true;
    }
    const bool ok = TakeStep(system, t, y, step, &w, &summary.rhs_evaluations, codes);
    double error = 0.0;
    if (ok) {
      system.StateScales(y, scale.data());
      for (int i = 0; i < n; ++i) {
        const double tolerance = options_.relative_tolerance * std::abs(w.high[i]) +
                                 options_.absolute_tolerance * scale[i];
        error = std::max(error, std::abs(w.high[i] - w.low[i]) / tolerance);
      }
    }
    if (!ok || (!fixed && error > 1.0)) {
      ++summary.rejected_steps;
      if (fixed) {
        summary.termination = TerminationType::kFailure;
        summary.message = "a fixed step left the model's domain: " + system.last_failure();
        break;
      }
      const double shrink = ok ? std::max(0.25, 0.9 * std::cbrt(1.0 / error)) : 0.25;
      h = step * shrink;
      if (h < min_step) {
        summary.termination = TerminationType::kFailure;
        summary.message =
            fmt::format("step size {:.3g} below the minimum {:.3g} at t = {:.6g}", h, min_step, t);
        if (!ok) summary.message += " (model: " + system.last_failure() + ")";
        break;
      }
      continue;
    }
    // Accepted. Check the root functions on the new state.
    if (num_roots > 0) {
      system.Roots(t + step, w.high.data(), g_new.data());
      int crossed = -1;
      for (int i = 0; i < num_roots; ++i) {
        if ((g_old[i] < 0 && g_new[i] >= 0) || (g_old[i] > 0 && g_new[i] <= 0)) {
          crossed = i;
          break;
        }
      }
      if (crossed >= 0) {
        // Illinois iteration on the fraction θ of the step where g crosses zero.
        IllinoisOptions illinois;
        illinois.width_scale = step;
        illinois.width_tolerance = 1e-14 * std::max(std::abs(t), std::abs(step));
        illinois.max_iterations = 100;
        std::vector<double> g(num_roots);
        auto g_at = [&](double theta, double* value) {
          if (!TakeStep(system, t, y, theta * step, &w, &summary.rhs_evaluations, codes)) {
            return false;
          }
          system.Roots(t + theta * step, w.high.data(), g.data());
          *value = g[crossed];
          return true;
        };
        const IllinoisResult root =
            IllinoisRoot(g_at, 0.0, g_old[crossed], 1.0, g_new[crossed], illinois);
        // The far side of the bracket: a restart from here does not see the
        // same crossing again.
        const double theta = root.b;
        TakeStep(system, t, y, theta * step, &w, &summary.rhs_evaluations);
        std::copy(w.high.begin(), w.high.end(), y);
        t += theta * step;
        ++summary.steps;
        summary.termination = TerminationType::kRootFound;
        summary.root_index = crossed;
        break;
      }
      g_old = g_new;
    }
    std::copy(w.high.begin(), w.high.end(), y);
    t = hits_stop ? target : t + step;
    ++summary.steps;
    if (!fixed) {
      const double grow = error > 0 ? std::min(4.0, 0.9 * std::cbrt(1.0 / error)) : 4.0;
      h = std::max(h, step) * std::max(grow, 0.25);
      if (!hits_stop) h = step * std::max(grow, 0.25);
    }
    if (hits_stop) {
      if (observer && next_stop + 1 < stops.size()) observer(t, y);
      ++next_stop;
      if (next_stop >= stops.size()) break;
    }
  }
  summary.final_time = t;
  summary.wall_time_s = stopwatch.Seconds();
  return summary;
}

}  // namespace granasym
