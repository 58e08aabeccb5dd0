// Whether two calibration configurations agree in everything the calibration
// file can say (calibration/calibration_config.h): for the round trip through
// CalibrationConfigText and for configurations built in code.
#pragma once

#include <gtest/gtest.h>

#include "calibration/calibration_config.h"

namespace granasym::calibration::testing {

inline void ExpectSameConfig(const CalibrationConfig& a, const CalibrationConfig& b) {
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.predictor.method, b.predictor.method);
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (size_t k = 0; k < a.parameters.size(); ++k) {
    const ParameterChoice &p = a.parameters[k], &q = b.parameters[k];
    EXPECT_EQ(p.name, q.name);
    EXPECT_EQ(p.free, q.free) << p.name;
    EXPECT_EQ(p.has_value, q.has_value) << p.name;
    EXPECT_EQ(p.has_lower, q.has_lower) << p.name;
    EXPECT_EQ(p.has_upper, q.has_upper) << p.name;
    if (p.has_value) {
      EXPECT_EQ(p.value, q.value) << p.name;
    }
    if (p.has_lower) {
      EXPECT_EQ(p.lower, q.lower) << p.name;
    }
    if (p.has_upper) {
      EXPECT_EQ(p.upper, q.upper) << p.name;
    }
  }
  ASSERT_EQ(a.datasets.size(), b.datasets.size());
  for (size_t k = 0; k < a.datasets.size(); ++k) {
    const DatasetConfig &d = a.datasets[k], &e = b.datasets[k];
    SCOPED_TRACE("dataset " + d.name);
    EXPECT_EQ(d.name, e.name);
    EXPECT_EQ(d.path, e.path);
    EXPECT_EQ(d.paths, e.paths);
    EXPECT_EQ(d.is_dem, e.is_dem);
    EXPECT_EQ(d.is_study, e.is_study);
    EXPECT_EQ(d.study.kinds, e.study.kinds);
    EXPECT_EQ(d.study.statuses, e.study.statuses);
    EXPECT_EQ(d.study.exclude_flags, e.study.exclude_flags);
    EXPECT_EQ(d.study.ncl_references, e.study.ncl_references);
    EXPECT_EQ(d.study.cases, e.study.cases);
    EXPECT_EQ(d.study.psi_epsilon_min_deg, e.study.psi_epsilon_min_deg);
    EXPECT_EQ(d.study.psi_epsilon_max_deg, e.study.psi_epsilon_max_deg);
    EXPECT_EQ(d.study.triaxial_kind_tolerance_deg, e.study.triaxial_kind_tolerance_deg);
    EXPECT_EQ(d.study.max_inertial_number, e.study.max_inertial_number);
    EXPECT_EQ(d.study.psi_sigma_uncertainty_deg, e.study.psi_sigma_uncertainty_deg);
    EXPECT_EQ(d.study.ln_volume_uncertainty, e.study.ln_volume_uncertainty);
    EXPECT_EQ(d.study.weight, e.study.weight);
    EXPECT_EQ(d.dem.ncl_min_p_kpa, e.dem.ncl_min_p_kpa);
    EXPECT_EQ(d.dem.max_line_points, e.dem.max_line_points);
    EXPECT_EQ(d.dem.psi_sigma_uncertainty_deg, e.dem.psi_sigma_uncertainty_deg);
    EXPECT_EQ(d.dem.ln_volume_uncertainty, e.dem.ln_volume_uncertainty);
    EXPECT_EQ(d.dem.weight, e.dem.weight);
    EXPECT_EQ(d.dem.asbs_ln_1_plus_e, e.dem.asbs_ln_1_plus_e);
    EXPECT_EQ(d.dem.unloading_weight, e.dem.unloading_weight);
    EXPECT_EQ(d.is_path, e.is_path);
    EXPECT_EQ(d.study_path, e.study_path);
    EXPECT_EQ(d.path_case, e.path_case);
    EXPECT_EQ(d.path_replicate, e.path_replicate);
    EXPECT_EQ(d.path_read.stages, e.path_read.stages);
    EXPECT_EQ(d.path_read.control, e.path_read.control);
    EXPECT_EQ(d.path_read.kind, e.path_read.kind);
    EXPECT_EQ(d.path_read.points, e.path_read.points);
    EXPECT_EQ(d.path_read.weight, e.path_read.weight);
    EXPECT_EQ(d.path_read.ln_p_uncertainty, e.path_read.ln_p_uncertainty);
    EXPECT_EQ(d.path_read.psi_sigma_uncertainty_deg, e.path_read.psi_sigma_uncertainty_deg);
    EXPECT_EQ(d.path_read.ln_volume_uncertainty, e.path_read.ln_volume_uncertainty);
    EXPECT_EQ(d.csv.kind, e.csv.kind);
    EXPECT_EQ(d.csv.ignore_columns, e.csv.ignore_columns);
    EXPECT_EQ(d.csv.psi_sigma_uncertainty_deg, e.csv.psi_sigma_uncertainty_deg);
    EXPECT_EQ(d.csv.ln_volume_uncertainty, e.csv.ln_volume_uncertainty);
    EXPECT_EQ(d.csv.weight, e.csv.weight);
  }
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.fix_undetermined, b.fix_undetermined);
  EXPECT_EQ(a.profiles.enabled, b.profiles.enabled);
  EXPECT_EQ(a.profiles.points_per_side, b.profiles.points_per_side);
  EXPECT_EQ(a.pareto.enabled, b.pareto.enabled);
  EXPECT_EQ(a.pareto.points, b.pareto.points);
  EXPECT_EQ(a.ceres.max_iterations, b.ceres.max_iterations);
  EXPECT_EQ(a.ceres.uncertainty.scale_by_residual_variance,
            b.ceres.uncertainty.scale_by_residual_variance);
  EXPECT_EQ(a.nlopt.algorithm, b.nlopt.algorithm);
  EXPECT_EQ(a.nlopt.starts, b.nlopt.starts);
  EXPECT_EQ(a.nlopt.max_evaluations, b.nlopt.max_evaluations);
  EXPECT_EQ(a.nlopt.seed, b.nlopt.seed);
  EXPECT_EQ(a.nlopt.polish, b.nlopt.polish);
  EXPECT_EQ(a.nlopt.uncertainty.scale_by_residual_variance,
            b.nlopt.uncertainty.scale_by_residual_variance);
  EXPECT_EQ(a.nlopt.ceres.max_iterations, b.nlopt.ceres.max_iterations);
  EXPECT_EQ(a.hdf5_path, b.hdf5_path);
  EXPECT_EQ(a.summary_path, b.summary_path);
  EXPECT_EQ(a.status_path, b.status_path);
  EXPECT_EQ(a.plot_data_dir, b.plot_data_dir);
}

}  // namespace granasym::calibration::testing
