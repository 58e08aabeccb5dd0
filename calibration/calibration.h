// granasym calibration: fit hypoplastic clay, Modified Cam clay and hypoplastic
// sand parameters to asymptotic states (study tables, DEM results, CSV) with
// Ceres and NLopt (issues 4, 9).
#pragma once

#include "calibration/asymptote_predictor.h"
#include "calibration/calibration_config.h"
#include "calibration/calibration_problem.h"
#include "calibration/calibration_report.h"
#include "calibration/ceres_fitter.h"
#include "calibration/csv_state_reader.h"
#include "calibration/dem_state_reader.h"
#include "calibration/fit_result.h"
#include "calibration/model_parameters.h"
#include "calibration/nlopt_fitter.h"
#include "calibration/pareto.h"
#include "calibration/profile_likelihood.h"
#include "calibration/starting_values.h"
#include "calibration/state_dataset.h"
#include "calibration/study_state_reader.h"
