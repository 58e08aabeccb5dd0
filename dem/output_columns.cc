#include "dem/output_columns.h"

#include <cmath>
#include <limits>
#include <string>

#include "dem/contact_laws.h"
#include "dem/run_record_names.h"

namespace granasym::dem {
namespace {

double Kpa(double pascal) { return pascal / kKiloPascal; }

double InertialAt(const RowMeasures& row, double diameter) {
  const double p = row.stress.mean();
  return p > 0 ? InertialNumber(row.stretching, diameter, row.engine.material().density, p)
               : std::numeric_limits<double>::infinity();
}

}  // namespace

RowMeasures::RowMeasures(const Engine& engine, int64_t stage,
                         const std::array<double, 3>& reference_cell, double min_diameter,
                         double max_diameter, const std::vector<double>* histogram_edges)
    : engine(engine),
      stage(stage),
      stress(AxisymmetricFromTensor(engine.sums().stress)),
      min_diameter(min_diameter),
      max_diameter(max_diameter) {
  const auto& gradient = engine.velocity_gradient();
  rate = AxisymmetricRate{-gradient[0], -0.5 * (gradient[1] + gradient[2])};
  stretching =
      std::sqrt(gradient[0] * gradient[0] + gradient[1] * gradient[1] + gradient[2] * gradient[2]);
  std::array<double, 3> strain;
  for (int d = 0; d < 3; ++d) strain[d] = -std::log(engine.cell()[d] / reference_cell[d]);
  eps_a = strain[0];
  eps_r = 0.5 * (strain[1] + strain[2]);
  void_ratio = engine.void_ratio();
  contacts = MeasureContacts(engine, histogram_edges);
}

const std::vector<OutputColumn>& OutputColumns() {
  using R = const RowMeasures&;
  static const std::string stiffness_number =
      "kappa: " + StiffnessNumberDescriptions() + " (1/relative overlap)";
  static const std::vector<OutputColumn> columns = {
      {record::kColumnTime, "s", "simulated time", [](R r) { return r.engine.time(); }},
      {record::kColumnStep, "1", "time step index",
       [](R r) { return static_cast<double>(r.engine.step()); }},
      {record::kColumnTimeStep, "s", "time step Delta t of the step from this row's state",
       [](R r) { return r.engine.time_step(); }},
      {record::kColumnContactDurationMin, "s",
       "shortest undamped duration pi sqrt(m_12/k_n) of the touching pairs at their overlap "
       "(inf: no contact)",
       [](R r) { return r.engine.SmallestContactDuration(); }},
      {record::kColumnStage, "1", "stage index (0-based)",
       [](R r) { return static_cast<double>(r.stage); }},
      {record::kColumnCellX, "m", "cell side along axis 1 (vertical)",
       [](R r) { return r.engine.cell()[0]; }},
      {record::kColumnCellY, "m", "cell side along axis 2", [](R r) { return r.engine.cell()[1]; }},
      {record::kColumnCellZ, "m", "cell side along axis 3", [](R r) { return r.engine.cell()[2]; }},
      {record::kColumnStress11, "kPa", "Love-Weber stress, compression positive",
       [](R r) { return Kpa(r.engine.sums().stress[0]); }},
      {record::kColumnStress22, "kPa", "", [](R r) { return Kpa(r.engine.sums().stress[1]); }},
      {record::kColumnStress33, "kPa", "", [](R r) { return Kpa(r.engine.sums().stress[2]); }},
      {record::kColumnStress12, "kPa", "", [](R r) { return Kpa(r.engine.sums().stress[3]); }},
      {record::kColumnStress13, "kPa", "", [](R r) { return Kpa(r.engine.sums().stress[4]); }},
      {record::kColumnStress23, "kPa", "", [](R r) { return Kpa(r.engine.sums().stress[5]); }},
      {record::kColumnAxialStress, "kPa", "axial stress sigma_11",
       [](R r) { return Kpa(r.stress.axial); }},
      {record::kColumnRadialStress, "kPa", "radial stress (sigma_22 + sigma_33)/2",
       [](R r) { return Kpa(r.stress.radial); }},
      {record::kColumnMeanStress, "kPa", "mean stress", [](R r) { return Kpa(r.stress.mean()); }},
      {record::kColumnDeviator, "kPa", "deviator sigma_a - sigma_r",
       [](R r) { return Kpa(r.stress.deviator()); }},
      {record::kColumnPsiSigma, "deg", "stress obliquity angle in the Rendulic plane",
       [](R r) { return r.stress.psi() / kDegree; }},
      {record::kColumnPsiEpsilon, "deg", "stretching direction in the Rendulic plane",
       [](R r) { return r.rate.psi() / kDegree; }},
      {record::kColumnAxialRate, "1/s", "axial strain rate, compression positive",
       [](R r) { return r.rate.axial; }},
      {record::kColumnRadialRate, "1/s", "radial strain rate, compression positive",
       [](R r) { return r.rate.radial; }},
      {record::kColumnStretchingRate, "1/s", "norm of the stretching tensor |D|",
       [](R r) { return r.stretching; }},
      {record::kColumnAxialStrain, "1",
       "axial logarithmic strain since the run start, compression positive",
       [](R r) { return r.eps_a; }},
      {record::kColumnRadialStrain, "1", "radial logarithmic strain", [](R r) { return r.eps_r; }},
      {record::kColumnVolumetricStrain, "1", "volumetric strain eps_a + 2 eps_r",
       [](R r) { return r.eps_a + 2 * r.eps_r; }},
      {record::kColumnShearStrain, "1", "shear strain 2 (eps_a - eps_r)/3",
       [](R r) { return 2.0 * (r.eps_a - r.eps_r) / 3.0; }},
      {record::kColumnVoidRatio, "1", "void ratio V_cell/V_solid - 1",
       [](R r) { return r.void_ratio; }},
      {record::kColumnLnVolume, "1", "ln(1 + e)", [](R r) { return std::log1p(r.void_ratio); }},
      {record::kColumnContacts, "1", "number of contacts",
       [](R r) { return static_cast<double>(r.contacts.contacts); }},
      {record::kColumnCoordination, "1", "coordination number 2C/N",
       [](R r) { return r.contacts.coordination; }},
      {record::kColumnMechanicalCoordination, "1", "coordination without rattlers",
       [](R r) { return r.contacts.mechanical_coordination; }},
      {record::kColumnOverlapMax, "1", "largest relative overlap u/(r_i + r_j)",
       [](R r) { return r.contacts.overlap_max; }},
      {record::kColumnOverlapMean, "1", "mean relative overlap",
       [](R r) { return r.contacts.overlap_mean; }},
      {record::kColumnOverlapP50, "1", "median relative overlap",
       [](R r) { return r.contacts.overlap_p50; }},
      {record::kColumnOverlapP90, "1", "90th percentile of relative overlaps",
       [](R r) { return r.contacts.overlap_p90; }},
      {record::kColumnOverlapP99, "1", "99th percentile of relative overlaps",
       [](R r) { return r.contacts.overlap_p99; }},
      {record::kColumnInertialNumberDmin, "1", "|D| d sqrt(2 rho_s / p) for the smallest diameter",
       [](R r) { return InertialAt(r, r.min_diameter); }},
      {record::kColumnInertialNumberDmax, "1", "same for the largest diameter",
       [](R r) { return InertialAt(r, r.max_diameter); }},
      {record::kColumnStiffnessNumber, "1", stiffness_number.c_str(),
       [](R r) { return r.engine.material().StiffnessNumber(r.stress.mean()); }},
      {record::kColumnKineticEnergy, "J", "kinetic energy of the fluctuating motion",
       [](R r) { return KineticEnergy(r.engine); }},
      {record::kColumnUnbalancedForce, "1", "mean net force / mean contact force",
       [](R r) { return UnbalancedForceRatio(r.engine); }},
  };
  return columns;
}

std::vector<TimeSeries::Column> SeriesColumns() {
  std::vector<TimeSeries::Column> columns;
  for (const OutputColumn& column : OutputColumns()) {
    columns.push_back({column.name, column.units, column.description});
  }
  return columns;
}

std::vector<double> RowValues(const RowMeasures& row) {
  std::vector<double> values;
  values.reserve(OutputColumns().size());
  for (const OutputColumn& column : OutputColumns()) values.push_back(column.value(row));
  return values;
}

}  // namespace granasym::dem
