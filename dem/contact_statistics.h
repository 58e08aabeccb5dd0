// Contact statistics at an output step (paper Fig. 8): contact count,
// coordination numbers, relative overlaps u_N/(r_i + r_j) and, on request,
// their histogram; and the kinetic measures of the particles.
#pragma once

#include <cstdint>
#include <vector>

#include "dem/engine.h"

namespace granasym::dem {

struct ContactStatistics {
  int64_t contacts = 0;
  double coordination = 0;  // Z = 2 C / N
  // Z_m = (2C − N_1)/(N − N_0 − N_1): rattlers (0 or 1 contact) excluded
  // (Thornton 2000).
  double mechanical_coordination = 0;
  double overlap_max = 0;  // relative overlaps u_N/(r_i + r_j)
  double overlap_mean = 0;
  double overlap_p50 = 0, overlap_p90 = 0, overlap_p99 = 0;
  std::vector<int64_t> histogram;  // counts per bin of `edges` (when asked)
};

// Logarithmic bin edges for relative-overlap histograms: `bins` bins from
// `low` to `high` (underflow goes to the first bin, overflow to the last).
std::vector<double> LogarithmicEdges(double low, double high, int bins);

// Measures the current contacts; fills `histogram` only when `edges` is given.
ContactStatistics MeasureContacts(const Engine& engine, const std::vector<double>* edges);

// Kinetic energy of the fluctuating motion, translational + rotational (J).
double KineticEnergy(const Engine& engine);

// Mean |net force| over particles divided by the mean contact force (the
// unbalanced-force ratio, 0 in static equilibrium); needs a force evaluation
// with stress sums.
double UnbalancedForceRatio(const Engine& engine);

}  // namespace granasym::dem
