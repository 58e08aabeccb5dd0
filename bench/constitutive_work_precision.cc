// Run time against error for the constitutive integrators (issue 3, §6): a
// work-precision study on fixed element-test paths.
//
// For each path and model a reference solution is computed by CVODE BDF with
// rtol 1e-12; its convergence is verified by repeating it with the tolerances
// divided by 10 and by an independent method (ARKODE ERK order 8, or for Cam
// clay the return mapping with tiny increments) — both differences are printed
// and must be far below the errors that are compared. Every integrator is
// then run over a sweep of tolerances; the error is the largest relative
// deviation from the reference over the recorded points of the path:
//   max over records of max(‖T − T_ref‖/‖T_ref‖, |e − e_ref|/(1 + e_ref),
//                           |p_c − p_c,ref|/p_c,ref),
// and the time is the median wall time of `--repeats` runs of ElementTest::Run.
// A plain program (not Google Benchmark's loop), because every configuration
// needs its error as well as its time; it prints the table and writes it as
// CSV for plots/work_precision.gp, then prints, for every path, the fastest
// configuration at an error of ~1e-6 against RKF23 (Mašín's baseline) at the
// same error, interpolated log–log along each curve.
//
//   build-models/bench/constitutive_work_precision [--csv FILE]
//       [--repeats N] [--quick] [--model hypoplastic_clay|modified_cam_clay|hypoplastic_sand]
//       [--path NAME] [--target-error E]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/state_measures.h"
#include "constitutive/element_driver.h"
#include "constitutive/hypoplastic_clay.h"
#include "constitutive/hypoplastic_sand.h"
#include "constitutive/modified_cam_clay.h"

namespace granasym {
namespace {

// London clay (Mašín 2005, Table 2) and a Cam clay with the same NCL.
HypoplasticClay::Parameters LondonClay() { return HypoplasticClay::Parameters::LondonClay(); }

ModifiedCamClay::Parameters CamClay() { return ModifiedCamClay::Parameters::LondonClayNcl(); }

struct PathCase {
  std::string name;
  double mean_stress;  // kPa, initial
  double ocr;          // initial p_e*/p
  std::vector<LoadingStage> stages;
};

// Stages end at their duration (‖D‖ = 1/s, so the duration is the strain
// path): the records of every run then lie at the same times.
std::vector<PathCase> Paths() {
  constexpr int kOutputs = 10;
  auto with_outputs = [](LoadingStage stage) {
    stage.output_points = kOutputs;
    return stage;
  };
  const double axial_isochoric = 1.0;
  std::vector<PathCase> paths;
  paths.push_back(
      {"isotropic_nc", 100.0, 1.0, {with_outputs(LoadingStage::Proportional(0.0, 1.0, 0.15))}});
  paths.push_back(
      {"isochoric_nc", 100.0, 1.0, {with_outputs(LoadingStage::Isochoric(axial_isochoric, 0.3))}});
  paths.push_back({"isochoric_ocr8",
                   100.0,
                   8.0,
                   {with_outputs(LoadingStage::Isochoric(axial_isochoric, 0.3))}});
  paths.push_back({"drained_triaxial",
                   100.0,
                   1.0,
                   {with_outputs(LoadingStage::ConstantRadialStress(1.0, 0.25))}});
  paths.push_back({"proportional_45",
                   100.0,
                   1.0,
                   {with_outputs(LoadingStage::Proportional(45.0 * kDegree, 1.0, 0.3))}});
  paths.push_back({"proportional_100",
                   100.0,
                   1.0,
                   {with_outputs(LoadingStage::Proportional(100.0 * kDegree, 1.0, 0.2))}});
  // Isotropic unloading to p ≈ 100/e^{1.6} then reloading past the start.
  paths.push_back({"unload_reload",
                   100.0,
                   1.0,
                   {with_outputs(LoadingStage::Proportional(kPi, 1.0, 0.015)),
                    with_outputs(LoadingStage::Proportional(0.0, 1.0, 0.04))}});
  return paths;
}

// The sand's paths: Hochstetten sand is far stiffer than London clay and its
// OCR is measured from e_i (OCR 1: loosest, 10: near e_c, 300: e = 0.61,
// dense), so the strains are shorter than above and the densities span the
// range of f_d; extension and unloading stop well before p → 0.
std::vector<PathCase> SandPaths() {
  constexpr int kOutputs = 10;
  auto with_outputs = [](LoadingStage stage) {
    stage.output_points = kOutputs;
    return stage;
  };
  std::vector<PathCase> paths;
  paths.push_back(
      {"isotropic_loose", 100.0, 1.0, {with_outputs(LoadingStage::Proportional(0.0, 1.0, 0.05))}});
  paths.push_back({"isotropic_dense",
                   100.0,
                   300.0,
                   {with_outputs(LoadingStage::Proportional(0.0, 1.0, 0.03))}});
  paths.push_back(
      {"isochoric_loose", 100.0, 1.0, {with_outputs(LoadingStage::Isochoric(1.0, 0.1))}});
  paths.push_back(
      {"isochoric_dense", 100.0, 300.0, {with_outputs(LoadingStage::Isochoric(1.0, 0.2))}});
  paths.push_back({"drained_triaxial_loose",
                   100.0,
                   1.0,
                   {with_outputs(LoadingStage::ConstantRadialStress(1.0, 0.15))}});
  paths.push_back({"drained_triaxial_dense",
                   100.0,
                   300.0,
                   {with_outputs(LoadingStage::ConstantRadialStress(1.0, 0.15))}});
  paths.push_back({"proportional_45",
                   100.0,
                   10.0,
                   {with_outputs(LoadingStage::Proportional(45.0 * kDegree, 1.0, 0.05))}});
  paths.push_back({"proportional_100",
                   100.0,
                   10.0,
                   {with_outputs(LoadingStage::Proportional(100.0 * kDegree, 1.0, 0.02))}});
  paths.push_back({"unload_reload",
                   100.0,
                   1.0,
                   {with_outputs(LoadingStage::Proportional(kPi, 1.0, 0.002)),
                    with_outputs(LoadingStage::Proportional(0.0, 1.0, 0.005))}});
  return paths;
}

// One configuration of the sweep.
struct Method {
  std::string label;  // curve name in the table and the figure
  DriveMethod drive = DriveMethod::kRateIntegration;
  IntegratorKind kind = IntegratorKind::kCvodeBdf;
  JacobianKind jacobian = JacobianKind::kExact;
  CamClayStressPoint::Method stress_point = CamClayStressPoint::Method::kModifiedEuler;
  int order = 0;  // ARKODE ERK/DIRK order; 0: the IntegratorOptions default
};

std::vector<Method> Methods(const ConstitutiveModel& model) {
  std::vector<Method> methods = {
      {"cvode_bdf_exact", DriveMethod::kRateIntegration, IntegratorKind::kCvodeBdf,
       JacobianKind::kExact},
      {"cvode_bdf_fd", DriveMethod::kRateIntegration, IntegratorKind::kCvodeBdf,
       JacobianKind::kFiniteDifference},
      {"cvode_adams", DriveMethod::kRateIntegration, IntegratorKind::kCvodeAdams},
      {"arkode_erk", DriveMethod::kRateIntegration, IntegratorKind::kArkodeErk,
       JacobianKind::kExact, CamClayStressPoint::Method::kModifiedEuler, 4},
      {"arkode_erk_order3", DriveMethod::kRateIntegration, IntegratorKind::kArkodeErk,
       JacobianKind::kExact, CamClayStressPoint::Method::kModifiedEuler, 3},
      {"arkode_erk_order5", DriveMethod::kRateIntegration, IntegratorKind::kArkodeErk,
       JacobianKind::kExact, CamClayStressPoint::Method::kModifiedEuler, 5},
      {"arkode_erk_order8", DriveMethod::kRateIntegration, IntegratorKind::kArkodeErk,
       JacobianKind::kExact, CamClayStressPoint::Method::kModifiedEuler, 8},
      {"arkode_dirk", DriveMethod::kRateIntegration, IntegratorKind::kArkodeDirk,
       JacobianKind::kExact, CamClayStressPoint::Method::kModifiedEuler, 4},
      {"rkf23", DriveMethod::kRateIntegration, IntegratorKind::kRkf23},
  };
  if (HasStressPointMethod(model)) {
    methods.push_back({"stress_point_modified_euler", DriveMethod::kStressPoint,
                       IntegratorKind::kCvodeBdf, JacobianKind::kExact,
                       CamClayStressPoint::Method::kModifiedEuler});
    methods.push_back({"stress_point_return_mapping", DriveMethod::kStressPoint,
                       IntegratorKind::kCvodeBdf, JacobianKind::kExact,
                       CamClayStressPoint::Method::kReturnMapping});
  }
  return methods;
}

// The options for a method at a tolerance. For the rate form both tolerances
// are `tolerance` (the absolute one relative to each component's scale, p for
// stresses). Modified Euler: its local error tolerance, with increments of
// ‖Δε‖ ≤ 0.01. Return mapping (first order, no error control): the increment
// ‖Δε‖ is the knob, 10·tolerance^(1/2) clipped to [1e-5, 0.05].
ElementTestOptions OptionsFor(const Method& method, double tolerance) {
  ElementTestOptions options;
  options.method = method.drive;
  options.integrator.kind = method.kind;
  options.integrator.jacobian = method.jacobian;
  options.integrator.relative_tolerance = tolerance;
  options.integrator.absolute_tolerance = tolerance;
  if (method.order > 0) options.integrator.arkode_order = method.order;
  options.stress_point.method = method.stress_point;
  if (method.drive == DriveMethod::kStressPoint) {
    if (method.stress_point == CamClayStressPoint::Method::kModifiedEuler) {
      options.stress_point.tolerance = tolerance;
      options.max_strain_increment = 0.01;
    } else {
      options.max_strain_increment = std::clamp(10.0 * std::sqrt(tolerance), 1e-5, 0.05);
    }
  }
  return options;
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Largest relative deviation of `run` from `reference` over the records.
double PathError(const ElementTestResult& run, const ElementTestResult& reference) {
  if (!run.summary.success() || run.history.size() != reference.history.size()) {
    return std::numeric_limits<double>::infinity();
  }
  double error = 0.0;
  for (size_t k = 0; k < run.history.size(); ++k) {
    const ElementTestRecord& a = run.history[k];
    const ElementTestRecord& b = reference.history[k];
    const Vector6 stress_a = ToVector(a.stress), stress_b = ToVector(b.stress);
    error = std::max(error, (stress_a - stress_b).norm() / stress_b.norm());
    error = std::max(error, std::abs(a.void_ratio - b.void_ratio) / (1.0 + b.void_ratio));
    for (size_t i = 0; i < b.internal.size() && i < a.internal.size(); ++i) {
      error = std::max(error, std::abs(a.internal[i] - b.internal[i]) / std::abs(b.internal[i]));
    }
    if (!std::isfinite(error)) return std::numeric_limits<double>::infinity();
  }
  return error;
}

struct Row {
  std::string path, model, method;
  double tolerance = 0.0;
  double error = 0.0;
  double median_time_s = 0.0;
  long rhs_evaluations = 0;
  long steps = 0;
  std::string status;
};

struct Settings {
  std::string csv = "constitutive_work_precision.csv";
  int repeats = 5;
  bool quick = false;
  std::string only_model, only_path;
  double target_error = 1e-6;
};

// log–log interpolation of the time a curve needs for `error`; NaN when the
// curve does not bracket it. Rows of one curve, any order.
double TimeAtError(std::vector<Row> curve, double error) {
  curve.erase(std::remove_if(curve.begin(), curve.end(),
                             [](const Row& r) { return !(r.error > 0 && std::isfinite(r.error)); }),
              curve.end());
  std::sort(curve.begin(), curve.end(),
            [](const Row& a, const Row& b) { return a.error > b.error; });
  for (size_t k = 0; k + 1 < curve.size(); ++k) {
    const Row& coarse = curve[k];
    const Row& fine = curve[k + 1];
    if (coarse.error >= error && fine.error <= error) {
      const double span = std::log(coarse.error / fine.error);
      const double w = span > 0 ? std::log(coarse.error / error) / span : 0.0;
      return std::exp((1 - w) * std::log(coarse.median_time_s) + w * std::log(fine.median_time_s));
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

int Main(int argc, char** argv) {
  Settings settings;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", arg.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--csv") {
      settings.csv = value();
    } else if (arg == "--repeats") {
      settings.repeats = std::max(1, std::atoi(value().c_str()));
    } else if (arg == "--quick") {
      settings.quick = true;
    } else if (arg == "--model") {
      settings.only_model = value();
    } else if (arg == "--path") {
      settings.only_path = value();
    } else if (arg == "--target-error") {
      settings.target_error = std::atof(value().c_str());
    } else {
      std::fprintf(stderr,
                   "usage: %s [--csv FILE] [--repeats N] [--quick] [--model NAME] [--path NAME] "
                   "[--target-error E]\n",
                   argv[0]);
      return 2;
    }
  }
  const std::vector<double> tolerances =
      settings.quick ? std::vector<double>{1e-3, 1e-5, 1e-7}
                     : std::vector<double>{1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5,
                                           3e-6, 1e-6, 3e-7, 1e-7, 1e-8, 1e-9, 1e-10};

  const HypoplasticClay hypoplastic(LondonClay());
  const ModifiedCamClay cam_clay(CamClay());
  const HypoplasticSand sand(HypoplasticSand::Parameters::HochstettenSand());
  const std::vector<const ConstitutiveModel*> models = {&hypoplastic, &cam_clay, &sand};

  std::vector<Row> rows;
  std::printf("%-18s %-18s %-28s %9s %10s %12s %9s %8s %s\n", "path", "model", "integrator",
              "tolerance", "error", "time_s", "rhs", "steps", "status");
  for (const ConstitutiveModel* model : models) {
    const std::string model_name = ToString(model->kind());
    if (!settings.only_model.empty() && settings.only_model != model_name) continue;
    for (const PathCase& path :
         model->kind() == ModelKind::kHypoplasticSand ? SandPaths() : Paths()) {
      if (!settings.only_path.empty() && settings.only_path != path.name) continue;
      const ModelState initial = InitialStateFromOcr(*model, path.mean_stress, 0.0, path.ocr);
      auto run = [&](const ElementTestOptions& options) {
        return ElementTest(*model, options).Run(initial, path.stages);
      };
      // Reference and its verification.
      Method reference_method;  // CVODE BDF with the exact Jacobian
      ElementTestOptions reference_options = OptionsFor(reference_method, 1e-12);
      reference_options.integrator.absolute_tolerance = 1e-14;
      const ElementTestResult reference = run(reference_options);
      if (!reference.summary.success()) {
        std::fprintf(stderr, "reference failed on %s/%s: %s\n", path.name.c_str(),
                     model_name.c_str(), reference.summary.Report().c_str());
        return 3;
      }
      ElementTestOptions tighter = reference_options;
      tighter.integrator.relative_tolerance = 1e-13;
      tighter.integrator.absolute_tolerance = 1e-15;
      const double self_difference = PathError(run(tighter), reference);
      ElementTestOptions independent;
      if (!HasStressPointMethod(*model)) {
        independent.integrator.kind = IntegratorKind::kArkodeErk;
        independent.integrator.arkode_order = 8;
        independent.integrator.relative_tolerance = 1e-12;
        independent.integrator.absolute_tolerance = 1e-14;
      } else {
        independent.method = DriveMethod::kStressPoint;
        independent.stress_point.method = CamClayStressPoint::Method::kModifiedEuler;
        independent.stress_point.tolerance = 1e-12;
        independent.max_strain_increment = 1e-3;
      }
      const double independent_difference = PathError(run(independent), reference);
      std::printf(
          "# reference %s/%s: cvode_bdf rtol 1e-12 (%ld RHS); vs rtol 1e-13: %.2e; vs %s: "
          "%.2e\n",
          path.name.c_str(), model_name.c_str(), reference.summary.totals.rhs_evaluations,
          self_difference,
          !HasStressPointMethod(*model) ? "arkode_erk order 8 rtol 1e-12"
                                        : "modified Euler tol 1e-12",
          independent_difference);
      rows.push_back({path.name, model_name, "reference_self_check", 1e-13, self_difference, 0.0, 0,
                      0, "check"});
      rows.push_back({path.name, model_name, "reference_independent_check", 1e-12,
                      independent_difference, 0.0, 0, 0, "check"});

      for (const Method& method : Methods(*model)) {
        for (double tolerance : tolerances) {
          const ElementTestOptions options = OptionsFor(method, tolerance);
          std::vector<double> times;
          ElementTestResult result;
          for (int r = 0; r < settings.repeats; ++r) {
            const auto start = std::chrono::steady_clock::now();
            result = run(options);
            times.push_back(
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
            if (!result.summary.success()) break;
          }
          Row row;
          row.path = path.name;
          row.model = model_name;
          row.method = method.label;
          row.tolerance = method.drive == DriveMethod::kStressPoint &&
                                  method.stress_point == CamClayStressPoint::Method::kReturnMapping
                              ? options.max_strain_increment
                              : tolerance;
          row.error = PathError(result, reference);
          row.median_time_s = Median(times);
          row.rhs_evaluations = result.summary.totals.rhs_evaluations;
          row.steps = result.summary.totals.steps;
          row.status = result.summary.success() ? "ok" : "failed";
          std::printf("%-18s %-18s %-28s %9.1e %10.3e %12.4e %9ld %8ld %s\n", row.path.c_str(),
                      row.model.c_str(), row.method.c_str(), row.tolerance, row.error,
                      row.median_time_s, row.rhs_evaluations, row.steps, row.status.c_str());
          if (!result.summary.success()) {
            std::printf("#   %s\n", result.summary.message.c_str());
          }
          std::fflush(stdout);
          rows.push_back(row);
        }
      }
    }
  }

  std::ofstream csv(settings.csv);
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", settings.csv.c_str());
    return 2;
  }
  csv << "path,model,integrator,tolerance,error,median_time_s,rhs_evaluations,steps,status\n";
  for (const Row& row : rows) {
    csv << fmt::format("{},{},{},{:.3e},{:.6e},{:.6e},{},{},{}\n", row.path, row.model, row.method,
                       row.tolerance, row.error, row.median_time_s, row.rhs_evaluations, row.steps,
                       row.status);
  }
  csv.close();
  std::printf("# wrote %s\n", settings.csv.c_str());

  // At the target error: the fastest method against RKF23 per path and model,
  // and the geometric mean over paths per method (what the default is chosen by).
  std::printf("\n# time at error %.1e (log-log interpolated along each curve)\n",
              settings.target_error);
  std::printf("%-18s %-18s %-28s %12s %12s %8s\n", "path", "model", "fastest", "time_s", "rkf23_s",
              "ratio");
  std::map<std::string, std::map<std::string, std::vector<Row>>> curves;  // key path|model
  for (const Row& row : rows) {
    if (row.status == "check") continue;
    curves[row.path + "|" + row.model][row.method].push_back(row);
  }
  std::map<std::string, std::vector<double>> speedups;  // method → rkf23 time / its time
  for (const auto& [key, methods] : curves) {
    const std::string path = key.substr(0, key.find('|'));
    const std::string model = key.substr(key.find('|') + 1);
    const double rkf23 =
        methods.count("rkf23") ? TimeAtError(methods.at("rkf23"), settings.target_error) : NAN;
    std::string fastest = "-";
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [method, curve] : methods) {
      const double time = TimeAtError(curve, settings.target_error);
      if (std::isfinite(time) && time < best) {
        best = time;
        fastest = method;
      }
      speedups[model + "|" + method].push_back(std::isfinite(time) ? rkf23 / time : NAN);
    }
    std::printf("%-18s %-18s %-28s %12.4e %12.4e %8.2f\n", path.c_str(), model.c_str(),
                fastest.c_str(), best, rkf23, rkf23 / best);
  }
  std::printf(
      "\n# RKF23 time / method time at error %.1e, geometric mean over paths "
      "(paths where the curve does not reach the error are left out)\n",
      settings.target_error);
  for (const auto& [key, values] : speedups) {
    double log_sum = 0.0;
    int count = 0;
    for (double v : values) {
      if (std::isfinite(v) && v > 0) {
        log_sum += std::log(v);
        ++count;
      }
    }
    std::printf("%-48s %8.2f  (%d of %zu paths)\n", key.c_str(),
                count > 0 ? std::exp(log_sum / count) : NAN, count, values.size());
  }
  return 0;
}

}  // namespace
}  // namespace granasym

int main(int argc, char** argv) { return granasym::Main(argc, argv); }
