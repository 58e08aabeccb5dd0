// Grain-size distribution (GSD): a table of sieve diameters and mass percent
// passing, turned into sphere radii by deterministic number quantiles.
//
// Between sieves the mass fraction is taken uniform in ln d (the usual
// semi-logarithmic GSD plot), so the number density per unit ln d is
// proportional to d⁻³ and the number CDF is analytic in each segment:
//   dN ∝ c d⁻³ d(ln d)  ⇒  N(d) − N(d_a) ∝ (c/3)(d_a⁻³ − d⁻³),  c = Δm/ln(d_b/d_a).
// Radius k of n is the (k + ½)/n quantile of that CDF.
#pragma once

#include <string>
#include <vector>

namespace granasym::dem {

class GrainSizeDistribution {
 public:
  // Diameters in metres, strictly increasing; percent passing by mass,
  // non-decreasing from 0 to 100. Throws InputError naming `origin` and the
  // row when the table is not a valid GSD.
  GrainSizeDistribution(std::vector<double> diameters, std::vector<double> percent_passing,
                        std::string origin = "GSD table");
  // Reads a CSV table with columns `diameter_mm,percent_passing_by_mass`.
  static GrainSizeDistribution ReadCsv(const std::string& path);
  // The project's default table (Zbraslav sand, reduced GSD; SPEC §4).
  static GrainSizeDistribution Default();
  static std::string DefaultPath();

  // `count` sphere radii (m), descending, from deterministic number quantiles.
  std::vector<double> QuantileRadii(size_t count) const;
  // Mass percent passing each sieve diameter achieved by a set of radii.
  std::vector<double> AchievedPercentPassing(const std::vector<double>& radii) const;

  const std::vector<double>& diameters() const { return diameters_; }
  const std::vector<double>& percent_passing() const { return percent_passing_; }
  double min_diameter() const;  // smallest diameter with mass (m)
  double max_diameter() const;  // largest diameter needed to reach 100 % (m)
  const std::string& origin() const { return origin_; }

 private:
  std::vector<double> diameters_;
  std::vector<double> percent_passing_;
  std::string origin_;
  std::vector<double> number_cdf_;  // unnormalised number CDF at each sieve
};

}  // namespace granasym::dem
