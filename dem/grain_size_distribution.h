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

// Sphere diameters the DEM accepts, in GSD tables and packing files alike
// (m): 1 nm to 1 km. Outside, a value is in another unit (or garbage), and
// d³ and d⁻³ (volumes, masses, the number CDF) leave the range where double
// arithmetic is safe: 1e-300 mm gives d⁻³ = inf and NaN radii.
inline constexpr double kMinSphereDiameter = 1e-9;
inline constexpr double kMaxSphereDiameter = 1e3;
// Largest d_max/d_min of the sieves that carry mass. The number of spheres
// per unit ln d grows as d⁻³, so a table spanning a ratio R needs of order R³
// small spheres per large one: above 100 (10⁶) no DEM sample represents the
// coarse fraction, and a wide range usually means diameters in another unit
// (the default table spans 5; DEM samples use a reduced GSD, SPEC §4).
inline constexpr double kMaxDiameterRatio = 100.0;

class GrainSizeDistribution {
 public:
  // Diameters in metres, strictly increasing, each in [kMinSphereDiameter,
  // kMaxSphereDiameter]; percent passing by mass, non-decreasing from 0 to
  // 100; the sieves with mass spanning at most kMaxDiameterRatio. Throws
  // InputError naming `origin` and the row (its line, where `line_numbers`
  // gives the source line of each row) when the table is not a valid GSD.
  GrainSizeDistribution(std::vector<double> diameters, std::vector<double> percent_passing,
                        std::string origin = "GSD table", std::vector<int> line_numbers = {});
  // Reads a CSV table with exactly the columns `diameter_mm,percent_passing_by_mass`
  // (any order; other columns are errors, common/csv_table.h).
  static GrainSizeDistribution ReadCsv(const std::string& path);
  // The project's default table (Zbraslav sand, reduced GSD; SPEC §4).
  static GrainSizeDistribution Default();
  static std::string DefaultPath();

  // `count` sphere radii (m), descending, from deterministic number quantiles.
  std::vector<double> QuantileRadii(size_t count) const;
  // Radius k of QuantileRadii(count), alone (k = 0: the largest), without
  // computing the others.
  double QuantileRadius(size_t k, size_t count) const;
  // Mean sphere volume d³π/6 of the number distribution (m³): what
  // QuantileRadii approaches for large counts.
  double MeanSphereVolume() const;
  // Mass percent passing each sieve diameter achieved by a set of radii.
  std::vector<double> AchievedPercentPassing(const std::vector<double>& radii) const;

  const std::vector<double>& diameters() const { return diameters_; }
  const std::vector<double>& percent_passing() const { return percent_passing_; }
  double min_diameter() const;  // smallest diameter with mass (m)
  double max_diameter() const;  // largest diameter needed to reach 100 % (m)
  const std::string& origin() const { return origin_; }
  // Where sieve k came from, for messages: "line 5" (from a file) or "row 2".
  std::string RowName(size_t k) const;
  // Index of the sieve of max_diameter().
  size_t MaxDiameterRow() const;

 private:
  std::vector<double> diameters_;
  std::vector<double> percent_passing_;
  std::string origin_;
  std::vector<int> line_numbers_;   // source line of each sieve; empty: not from a file
  std::vector<double> number_cdf_;  // unnormalised number CDF at each sieve
};

}  // namespace granasym::dem
