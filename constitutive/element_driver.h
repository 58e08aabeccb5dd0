// Element tests with general mixed control: each of the six components
// (Voigt 11, 22, 33, 12, 13, 23) has either its stretching prescribed or its
// stress rate prescribed (zero holds the stress). The unknown stretchings come
// from T̊_s(D) = target_s, solved by Newton with the model tangent at every
// right-hand-side evaluation, so that any integrator follows exactly the path
// the DEM follows. Stages end at their duration or at the exact crossing of a
// stop condition (root finding). Cam clay can instead be driven by strain
// increments through its stress-point algorithms.
//
// Everything here that a user sees is compression positive (SPEC §1): stage
// rates, targets, recorded stresses and strains; FlipSign converts at the boundary.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "common/state_measures.h"
#include "constitutive/cam_clay_stress_point.h"
#include "constitutive/constitutive_model.h"
#include "constitutive/integrator.h"

namespace granasym {

enum class ComponentControl { kStretching, kStressRate };
template <>
struct EnumNames<ComponentControl> {
  static constexpr EnumEntry<ComponentControl> kEntries[] = {
      {ComponentControl::kStretching, "stretching", "the stretching is prescribed"},
      {ComponentControl::kStressRate, "stress_rate", "the stress rate is prescribed"},
  };
};

enum class StopKind {
  kMeanStress,        // p reaches value (kPa)
  kAxialStrain,       // ε_a reaches value
  kVolumetricStrain,  // ε_v reaches value
  kShearStrain,       // ε_s = 2(ε_a − ε_r)/3 reaches value
  kStrainPath,        // ∫‖D‖dt reaches value
  kStressRatio,       // q/p reaches value
  kAsymptote,         // |dψ_σ/ds| + |d ln OCR/ds| falls to value (per unit strain path)
};
template <>
struct EnumNames<StopKind> {
  static constexpr EnumEntry<StopKind> kEntries[] = {
      {StopKind::kMeanStress, "mean_stress", "p reaches the value (kPa)"},
      {StopKind::kAxialStrain, "axial_strain", "the axial strain reaches the value"},
      {StopKind::kVolumetricStrain, "volumetric_strain", "the volumetric strain reaches the value"},
      {StopKind::kShearStrain, "shear_strain", "2(eps_a - eps_r)/3 reaches the value"},
      {StopKind::kStrainPath, "strain_path", "the strain path length reaches the value"},
      {StopKind::kStressRatio, "stress_ratio", "q/p reaches the value"},
      {StopKind::kAsymptote, "asymptote",
       "|dpsi_sigma/ds| + |d ln OCR/ds| falls to the value (per unit strain path)"},
  };
};

struct StopCondition {
  StopKind kind = StopKind::kMeanStress;
  double value = 0.0;
};

struct LoadingStage {
  std::string name;
  std::array<ComponentControl, 6> control{
      ComponentControl::kStretching, ComponentControl::kStretching, ComponentControl::kStretching,
      ComponentControl::kStretching, ComponentControl::kStretching, ComponentControl::kStretching};
  // Compression positive: stretching (1/s) for kStretching components, stress
  // rate (kPa/s) for kStressRate components.
  SymTensor rate{0, 0, 0, 0, 0, 0};
  double duration = 1.0;  // s; the stage ends here unless a stop fires first
  std::vector<StopCondition> stops;
  int output_points = 100;  // records per stage, evenly spaced in time

  // Axisymmetric helpers (axis 1 vertical). Rates compression positive.
  // Proportional stretching at angle ψ_ε (rad) and magnitude ‖D‖ (1/s).
  static LoadingStage Proportional(double psi_epsilon, double stretching_rate, double duration);
  // Drained triaxial: axial stretching prescribed, σ_2 = σ_3 held.
  static LoadingStage ConstantRadialStress(double axial_rate, double duration);
  // Isochoric: ε̇_r = −ε̇_a/2.
  static LoadingStage Isochoric(double axial_rate, double duration);
  // Oedometric: ε̇_r = 0.
  static LoadingStage Oedometric(double axial_rate, double duration);
  // Isotropic loading (target above p) or unloading (target below p) at ‖D‖ to
  // the target mean stress; the driver picks the direction from the mean
  // stress at the start of the stage.
  static LoadingStage IsotropicToMeanStress(double target_mean_stress, double stretching_rate);

  // > 0 for IsotropicToMeanStress stages: the target p (kPa); `rate` then holds
  // ‖D‖ in its first component until the driver resolves the direction.
  double isotropic_target = 0.0;
};

// Initial states, compression positive inputs: mean stress p (kPa), ψ_σ (rad).
// Throw InputError when the state is outside the model's domain (e.g. outside
// the Cam clay yield surface).
ModelState InitialStateFromVoidRatio(const ConstitutiveModel& model, double mean_stress,
                                     double psi_sigma, double void_ratio);
ModelState InitialStateFromOcr(const ConstitutiveModel& model, double mean_stress, double psi_sigma,
                               double ocr);
// Axisymmetric tension-positive stress tensor for p and ψ_σ.
Vector6 AxisymmetricStressTensor(double mean_stress, double psi_sigma);

enum class DriveMethod {
  kRateIntegration,  // the rate form with an Integrator (all models)
  kStressPoint,      // strain increments through CamClayStressPoint (Cam clay only)
};
template <>
struct EnumNames<DriveMethod> {
  static constexpr EnumEntry<DriveMethod> kEntries[] = {
      {DriveMethod::kRateIntegration, "rate_integration", "the rate form with an integrator"},
      {DriveMethod::kStressPoint, "stress_point",
       "strain increments through a stress-point algorithm (Cam clay only)"},
  };
};
// Whether `model` has a stress-point algorithm (CamClayStressPoint: Modified
// Cam clay).
bool HasStressPointMethod(const ConstitutiveModel& model);

// The default integrator of each model, chosen from the work-precision study
// (bench/README.md, "Chosen defaults"; bench/constitutive_work_precision):
// ARKODE ERK order 5 for every model, at rtol = atol of the model's traits
// (ModelTraits::integrator_tolerance): 1e-8 for the hypoplastic clay and
// sand and 1e-9 for Modified Cam clay (for the sand on
// its own paths, SandPaths in the benchmark, ERK 5 at 1e-8 is 2.0–6.8 times
// faster than RKF23 at equal error on every path). Cam clay's rate form has
// kinks at the yield surface and, at 1e-8, ERK 5 is slower than RKF23 at
// equal error on some paths (drained triaxial, unloading–reloading); at 1e-9
// it is at least level with RKF23 at equal error on every path of the study.
IntegratorOptions DefaultIntegratorOptions(ModelKind model);

struct ElementTestOptions {
  DriveMethod method = DriveMethod::kRateIntegration;
  // Rate integration. A tolerance left at 0 (as here by default) is replaced
  // by the model's DefaultIntegratorOptions when the ElementTest is made; set
  // both to choose them yourself.
  IntegratorOptions integrator = ModelDefaultTolerances();
  CamClayStressPoint::Options stress_point;
  // Mixed control: Newton on the unknown stretchings stops when the residual
  // of the controlled stress rates is below this fraction of the rate scale.
  double control_tolerance = 1e-13;
  int control_max_iterations = 50;
  // Mixed control: a stage fails at a limit point, where the block of ∂T̊/∂D
  // of the stress-controlled components has σ_min below this fraction of
  // ‖∂T̊/∂D‖_F or has lost the orientation (det > 0) it has in elasticity
  // (StageOde::Accept). Elasticity alone gives about 2G/3K for all three
  // normal components (1.3e-3 at Poisson's ratio 0.499).
  double limit_point_condition = 1e-4;
  // Stress-point method: largest strain increment ‖Δε‖ per increment (at most
  // integrator.max_steps increments per stage).
  double max_strain_increment = 1e-3;
  // Stress-point method: stops are located to this fraction of an increment.
  double stop_location_tolerance = 1e-10;

  bool IsValid(std::string* why) const;
  // IntegratorOptions with both tolerances 0: "the model's default".
  static IntegratorOptions ModelDefaultTolerances() {
    IntegratorOptions options;
    options.relative_tolerance = options.absolute_tolerance = 0.0;
    return options;
  }
};

// One recorded point, compression positive.
struct ElementTestRecord {
  double time = 0.0;   // s, cumulative over stages
  SymTensor stress{};  // kPa
  double void_ratio = 0.0;
  SymTensor strain{};        // logarithmic strain ∫D dt
  double strain_path = 0.0;  // ∫‖D‖ dt
  SymTensor stretching{};    // D at this point (1/s)
  std::vector<double> internal;
  double ocr = 0.0;  // p_e*/p
  int stage = 0;
};

struct StageSummary {
  std::string name;
  IntegrationSummary integration;
  std::string stop;  // "duration", or the stop that fired, e.g. "mean_stress=100"
};

struct ElementTestSummary {
  TerminationType termination = TerminationType::kNotRun;
  std::string message = "not run";
  IntegrationSummary totals;  // counters over all stages
  std::vector<StageSummary> stages;
  bool success() const {
    return termination == TerminationType::kReachedEnd ||
           termination == TerminationType::kRootFound;
  }
  std::string Report() const;  // one line
};

struct ElementTestResult {
  std::vector<ElementTestRecord> history;
  ModelState final_state;  // tension positive, the last valid state
  ElementTestSummary summary;
};

class ElementTest {
 public:
  // `model` must outlive the test. The options must be valid (GRANASYM_CHECK).
  ElementTest(const ConstitutiveModel& model, const ElementTestOptions& options);
  ElementTestResult Run(const ModelState& initial, const std::vector<LoadingStage>& stages) const;

 private:
  const ConstitutiveModel& model_;
  ElementTestOptions options_;
};

// Derived axisymmetric measures of a record.
AxisymmetricStress RecordStress(const ElementTestRecord& record);
AxisymmetricRate RecordStretching(const ElementTestRecord& record);

}  // namespace granasym
