#include "dem/simulation.h"

#include <algorithm>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/progress.h"
#include "common/state_measures.h"
#include "common/time_series.h"
#include "dem/asymptote_detector.h"
#include "dem/contact_statistics.h"
#include "dem/engine.h"

namespace granasym::dem {
namespace {

volatile std::sig_atomic_t g_interrupt = 0;

extern "C" void HandleSignal(int) { g_interrupt = 1; }

// Restores the previous signal handlers when a run ends.
class SignalGuard {
 public:
  SignalGuard() {
    g_interrupt = 0;
    previous_int_ = std::signal(SIGINT, HandleSignal);
    previous_term_ = std::signal(SIGTERM, HandleSignal);
  }
  ~SignalGuard() {
    std::signal(SIGINT, previous_int_);
    std::signal(SIGTERM, previous_term_);
  }

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

const std::vector<TimeSeries::Column>& SeriesColumns() {
  static const std::vector<TimeSeries::Column> columns = {
      {"time_s", "s", "simulated time"},
      {"step", "1", "time step index"},
      {"stage", "1", "stage index (0-based)"},
      {"cell_x_m", "m", "cell side along axis 1 (vertical)"},
      {"cell_y_m", "m", "cell side along axis 2"},
      {"cell_z_m", "m", "cell side along axis 3"},
      {"sigma_11_kpa", "kPa", "Love-Weber stress, compression positive"},
      {"sigma_22_kpa", "kPa", ""},
      {"sigma_33_kpa", "kPa", ""},
      {"sigma_12_kpa", "kPa", ""},
      {"sigma_13_kpa", "kPa", ""},
      {"sigma_23_kpa", "kPa", ""},
      {"sigma_a_kpa", "kPa", "axial stress sigma_11"},
      {"sigma_r_kpa", "kPa", "radial stress (sigma_22 + sigma_33)/2"},
      {"p_kpa", "kPa", "mean stress"},
      {"q_kpa", "kPa", "deviator sigma_a - sigma_r"},
      {"psi_sigma_deg", "deg", "stress obliquity angle in the Rendulic plane"},
      {"psi_epsilon_deg", "deg", "stretching direction in the Rendulic plane"},
      {"rate_a_per_s", "1/s", "axial strain rate, compression positive"},
      {"rate_r_per_s", "1/s", "radial strain rate, compression positive"},
      {"stretching_rate_per_s", "1/s", "norm of the stretching tensor |D|"},
      {"eps_a", "1", "axial logarithmic strain since the run start, compression positive"},
      {"eps_r", "1", "radial logarithmic strain"},
      {"eps_v", "1", "volumetric strain eps_a + 2 eps_r"},
      {"eps_s", "1", "shear strain 2 (eps_a - eps_r)/3"},
      {"e", "1", "void ratio V_cell/V_solid - 1"},
      {"ln_1_plus_e", "1", "ln(1 + e)"},
      {"contacts", "1", "number of contacts"},
      {"coordination", "1", "coordination number 2C/N"},
      {"mechanical_coordination", "1", "coordination without rattlers"},
      {"overlap_max", "1", "largest relative overlap u/(r_i + r_j)"},
      {"overlap_mean", "1", "mean relative overlap"},
      {"overlap_p50", "1", "median relative overlap"},
      {"overlap_p90", "1", "90th percentile of relative overlaps"},
      {"overlap_p99", "1", "99th percentile of relative overlaps"},
      {"inertial_number_dmin", "1", "|D| d sqrt(2 rho_s / p) for the smallest diameter"},
      {"inertial_number_dmax", "1", "same for the largest diameter"},
      {"kinetic_energy_j", "J", "kinetic energy of the fluctuating motion"},
      {"unbalanced_force", "1", "mean net force / mean contact force"},
  };
  return columns;
}

struct StageRecord {
  int64_t first_row = 0, last_row = 0;
  std::string stop_reason;
  AsymptoteDetector::Result asymptote;
  double asymptote_p_kpa = 0, asymptote_e = 0;
};

// Everything besides the engine that determines how a run continues.
struct RunnerState {
  int64_t stage = 0;
  bool stage_started = false;
  int64_t stage_start_step = 0;
  double stage_start_time = 0;
  std::array<double, 3> stage_start_cell{};
  double stage_start_p = std::numeric_limits<double>::quiet_NaN();
  double stage_strain_norm = 0;
  double next_sample_strain = 0;
  double strain_since_output = 0;
  int64_t steps_since_output = 0;
  int64_t stage_first_row = 0;
  std::array<double, 3> controlled_rate{};  // compression-positive rates of controllers
  std::array<double, 3> integral{};         // integral terms of the controllers (strain)
  std::vector<StageRecord> records;
};

class Simulation {
 public:
  Simulation(const Scene& scene, const RunOptions& options)
      : scene_(scene), options_(options), series_(SeriesColumns()) {}

  RunSummary Run();

 private:
  void Setup();
  void PrepareMeasurements();
  void StartStage();
  bool StageNeedsStressEveryStep(const Stage& stage) const;
  void Control(const Stage& stage, bool have_stress);
  std::optional<std::string> CheckStop(const Stage& stage, bool have_stress, bool sampled);
  bool StrainStopReached(const Stage& stage) const;
  bool StepsOrTimeDone(const Stage& stage) const;
  void AddRow();
  void FinishStage(const std::string& reason);
  void WriteResults(const std::string& path, const RunSummary& summary) const;
  void WriteCheckpoint() const;
  void LoadCheckpoint();
  void ReportProgress();
  template <typename Finish>
  RunSummary Loop(RunSummary& summary, Finish& finish, double& loop_seconds);
  std::array<double, 3> Strains() const;  // eps_a, eps_r, per axis from the run start
  double MeanStressKpa() const { return AxisymmetricFromTensor(engine_->sums().stress).mean() / kKiloPascal; }

  const Scene& scene_;
  RunOptions options_;
  Packing initial_;
  GenerationReport generation_;
  bool generated_ = false;
  std::optional<Engine> engine_;
  std::array<double, 3> initial_cell_{};
  double min_diameter_ = 0, max_diameter_ = 0;
  TimeSeries series_;
  std::vector<double> histogram_edges_;
  std::vector<double> histogram_rows_;  // rows x bins
  RunnerState state_;
  AsymptoteDetector detector_;
  Progress progress_;
  double last_p_kpa_ = 0, last_psi_deg_ = 0;
  Stopwatch stage_clock_;  // for the ETA only; not part of the state
  int64_t stage_clock_start_step_ = 0;
  int64_t eta_stage_ = -1;
  double eta_p0_ = 0;
  int threads_ = 1;
};

std::array<double, 3> Simulation::Strains() const {
  std::array<double, 3> strain;
  for (int d = 0; d < 3; ++d) strain[d] = -std::log(engine_->cell()[d] / initial_cell_[d]);
  return strain;
}

void Simulation::Setup() {
  initial_ = scene_.BuildSample(&generation_);
  generated_ = scene_.generate.has_value();
  Engine::Options engine_options;
  engine_options.time_step = scene_.TimeStep(initial_);
  engine_options.skin_fraction = scene_.skin_fraction;
  engine_options.threads = options_.threads > 0 ? options_.threads : scene_.threads;
  engine_.emplace(initial_, scene_.material, engine_options);
  initial_cell_ = initial_.cell;
}

void Simulation::PrepareMeasurements() {
  const auto [smallest, largest] = std::minmax_element(initial_.radii.begin(), initial_.radii.end());
  min_diameter_ = 2 * *smallest;
  max_diameter_ = 2 * *largest;
  if (scene_.output.overlap_histogram) {
    histogram_edges_ = LogarithmicEdges(scene_.output.histogram_min, scene_.output.histogram_max,
                                        scene_.output.histogram_bins);
  }
  Progress::Options progress_options;
  progress_options.plain_interval_s = scene_.output.progress_interval_s;
  progress_options.quiet = options_.quiet;
  progress_ = Progress(progress_options);
}

void Simulation::StartStage() {
  const Stage& stage = scene_.stages[state_.stage];
  state_.stage_started = true;
  state_.stage_start_step = engine_->step();
  state_.stage_start_time = engine_->time();
  state_.stage_start_cell = engine_->cell();
  state_.stage_start_p = std::numeric_limits<double>::quiet_NaN();
  state_.stage_strain_norm = 0;
  state_.next_sample_strain = 0;
  state_.stage_first_row = static_cast<int64_t>(series_.rows());
  state_.integral = {0.0, 0.0, 0.0};
  detector_ = AsymptoteDetector(stage.asymptote);
  switch (stage.type) {
    case StageType::kStrainPath: {
      const AxisymmetricRate rate =
          AxisymmetricRate::FromAngle(stage.psi_epsilon, stage.stretching_rate);
      engine_->SetVelocityGradient({-rate.axial, -rate.radial, -rate.radial});
      break;
    }
    case StageType::kTriaxial:
      // Start by holding the radial strain; the controller takes over at once.
      state_.controlled_rate = {stage.axial_strain_rate, 0.0, 0.0};
      engine_->SetVelocityGradient({-stage.axial_strain_rate, 0.0, 0.0});
      break;
    case StageType::kRest:
      state_.controlled_rate = {0.0, 0.0, 0.0};
      engine_->SetVelocityGradient({0.0, 0.0, 0.0});
      break;
  }
}

bool Simulation::StageNeedsStressEveryStep(const Stage& stage) const {
  return stage.type != StageType::kStrainPath || stage.stop.mean_stress_kpa.has_value() ||
         std::isnan(state_.stage_start_p);
}

// Stress controllers. Rates are compression positive; the affine (Voigt)
// stiffness C of the contact network converts a stress error into a strain
// increment, so the law is dimensionally consistent and independent of the
// material's scale:  Δε = gain · (σ* − σ) / C  per step, plus (triaxial) the
// feed-forward −(C_ra/C_rr) ε̇_a that keeps σ_r constant under the axial rate.
void Simulation::Control(const Stage& stage, bool have_stress) {
  if (stage.type == StageType::kStrainPath || !have_stress) return;
  const Engine::Sums& sums = engine_->sums();
  const double dt = engine_->time_step();
  const double gain = stage.control.gain;
  const double max_rate = stage.control.max_rate_factor * stage.stretching_rate;
  const auto& c = sums.stiffness;  // 11-11, 22-22, 33-33, 11-22, 11-33, 22-33
  auto clamp = [&](double rate) { return std::clamp(rate, -max_rate, max_rate); };
  if (stage.type == StageType::kTriaxial) {
    const double target = stage.radial_stress_kpa * kKiloPascal;
    const double radial = 0.5 * (sums.stress[1] + sums.stress[2]);
    const double c_rr = 0.5 * (c[1] + c[2] + 2.0 * c[5]);
    const double c_ra = 0.5 * (c[3] + c[4]);
    double rate;
    if (c_rr > 0) {
      // Integral action removes the steady error left by the affine
      // estimate of the feed-forward (the relaxed network is softer).
      const double strain_error = (target - radial) / c_rr;
      state_.integral[1] += stage.control.integral_gain * strain_error;
      rate = -c_ra / c_rr * stage.axial_strain_rate +
             (gain * strain_error + state_.integral[1]) / dt;
    } else {
      rate = target > radial ? max_rate : -max_rate;
    }
    rate = clamp(rate);
    state_.controlled_rate = {stage.axial_strain_rate, rate, rate};
    engine_->SetVelocityGradient({-stage.axial_strain_rate, -rate, -rate});
  } else {
    const double target = stage.mean_stress_kpa * kKiloPascal;
    const std::array<double, 3> row = {c[0] + c[3] + c[4], c[3] + c[1] + c[5], c[4] + c[5] + c[2]};
    std::array<double, 3> gradient;
    for (int d = 0; d < 3; ++d) {
      const double error = target - sums.stress[d];
      double rate;
      if (row[d] > 0) {
        const double strain_error = error / row[d];
        state_.integral[d] += stage.control.integral_gain * strain_error;
        rate = clamp((gain * strain_error + state_.integral[d]) / dt);
      } else {
        rate = error > 0 ? max_rate : -max_rate;
      }
      state_.controlled_rate[d] = rate;
      gradient[d] = -rate;
    }
    engine_->SetVelocityGradient(gradient);
  }
}

bool Simulation::StepsOrTimeDone(const Stage& stage) const {
  const StopConditions& stop = stage.stop;
  if (stop.steps && engine_->step() - state_.stage_start_step >= *stop.steps) return true;
  const double elapsed = engine_->time() - state_.stage_start_time;
  return stop.time_s && elapsed >= *stop.time_s * (1 - 1e-12);
}

bool Simulation::StrainStopReached(const Stage& stage) const {
  const StopConditions& stop = stage.stop;
  std::array<double, 3> strain;
  for (int d = 0; d < 3; ++d) {
    strain[d] = -std::log(engine_->cell()[d] / state_.stage_start_cell[d]);
  }
  const double axial = strain[0], radial = 0.5 * (strain[1] + strain[2]);
  auto reached = [](std::optional<double> target, double value) {
    if (!target) return false;
    return *target >= 0 ? value >= *target : value <= *target;
  };
  if (reached(stop.axial_strain, axial)) return true;
  if (reached(stop.volumetric_strain, axial + 2 * radial)) return true;
  if (reached(stop.shear_strain, 2.0 * (axial - radial) / 3.0)) return true;
  if (stop.strain_norm && state_.stage_strain_norm >= *stop.strain_norm) return true;
  return StepsOrTimeDone(stage);
}

std::optional<std::string> Simulation::CheckStop(const Stage& stage, bool have_stress,
                                                 bool sampled) {
  const StopConditions& stop = stage.stop;
  if (have_stress && stop.mean_stress_kpa) {
    const double p = MeanStressKpa();
    Direction direction = stop.mean_stress_direction;
    if (direction == Direction::kAuto) {
      direction = state_.stage_start_p < *stop.mean_stress_kpa ? Direction::kRising
                                                               : Direction::kFalling;
    }
    if ((direction == Direction::kRising && p >= *stop.mean_stress_kpa) ||
        (direction == Direction::kFalling && p <= *stop.mean_stress_kpa)) {
      return fmt::format("mean stress reached {:.6g} kPa (target {:.6g} kPa, {})", p,
                         *stop.mean_stress_kpa,
                         direction == Direction::kRising ? "rising" : "falling");
    }
  }
  if (sampled && stop.asymptote) {
    const AsymptoteDetector::Result result = detector_.Evaluate();
    if (result.detected) {
      return fmt::format("asymptotic state detected (psi_sigma {:.3f} deg, change {:.3f} deg, "
                         "ln p half-window difference {:.4f})",
                         result.psi_sigma / kDegree, result.psi_change_deg,
                         result.lnp_half_difference);
    }
  }
  if (stage.type == StageType::kRest && have_stress &&
      (engine_->step() - state_.stage_start_step) % stage.control.check_interval == 0) {
    const double target = stage.mean_stress_kpa * kKiloPascal;
    bool at_target = engine_->sums().contacts > 0;
    for (int d = 0; d < 3; ++d) {
      at_target = at_target &&
                  std::abs(engine_->sums().stress[d] - target) <= stop.stress_tolerance * target;
    }
    if (at_target) {
      const double unbalanced = UnbalancedForceRatio(*engine_);
      if (unbalanced <= stop.unbalanced_force) {
        return fmt::format("equilibrium at p = {:.6g} kPa, unbalanced force {:.3g}",
                           MeanStressKpa(), unbalanced);
      }
    }
  }
  if (StrainStopReached(stage)) {
    const auto& s = stage.stop;
    if (StepsOrTimeDone(stage)) {
      return s.steps ? fmt::format("{} steps done", *s.steps)
                     : fmt::format("stage time {:.6g} s reached", *s.time_s);
    }
    return std::string("strain target reached");
  }
  return std::nullopt;
}

void Simulation::AddRow() {
  const Engine& engine = *engine_;
  const Engine::Sums& sums = engine.sums();
  const SymTensor& stress = sums.stress;
  const AxisymmetricStress axisymmetric = AxisymmetricFromTensor(stress);
  const auto& gradient = engine.velocity_gradient();
  const AxisymmetricRate rate{-gradient[0], -0.5 * (gradient[1] + gradient[2])};
  const double stretching =
      std::sqrt(gradient[0] * gradient[0] + gradient[1] * gradient[1] + gradient[2] * gradient[2]);
  const std::array<double, 3> strain = Strains();
  const double eps_a = strain[0], eps_r = 0.5 * (strain[1] + strain[2]);
  const double e = engine.void_ratio();
  const ContactStatistics contacts =
      MeasureContacts(engine, histogram_edges_.empty() ? nullptr : &histogram_edges_);
  const double p = axisymmetric.mean();
  const double rho = engine.material().density;
  auto inertial = [&](double d) {
    return p > 0 ? InertialNumber(stretching, d, rho, p) : std::numeric_limits<double>::infinity();
  };
  const std::vector<double> row = {
      engine.time(), static_cast<double>(engine.step()), static_cast<double>(state_.stage),
      engine.cell()[0], engine.cell()[1], engine.cell()[2],
      stress[0] / kKiloPascal, stress[1] / kKiloPascal, stress[2] / kKiloPascal,
      stress[3] / kKiloPascal, stress[4] / kKiloPascal, stress[5] / kKiloPascal,
      axisymmetric.axial / kKiloPascal, axisymmetric.radial / kKiloPascal, p / kKiloPascal,
      axisymmetric.deviator() / kKiloPascal, axisymmetric.psi() / kDegree, rate.psi() / kDegree,
      rate.axial, rate.radial, stretching,
      eps_a, eps_r, eps_a + 2 * eps_r, 2.0 * (eps_a - eps_r) / 3.0,
      e, std::log1p(e),
      static_cast<double>(contacts.contacts), contacts.coordination,
      contacts.mechanical_coordination,
      contacts.overlap_max, contacts.overlap_mean, contacts.overlap_p50, contacts.overlap_p90,
      contacts.overlap_p99,
      inertial(min_diameter_), inertial(max_diameter_),
      KineticEnergy(engine), UnbalancedForceRatio(engine)};
  series_.AddRow(row);
  for (int64_t count : contacts.histogram) histogram_rows_.push_back(static_cast<double>(count));
  state_.strain_since_output = 0;
  state_.steps_since_output = 0;
  last_p_kpa_ = p / kKiloPascal;
  last_psi_deg_ = axisymmetric.psi() / kDegree;
}

void Simulation::FinishStage(const std::string& reason) {
  const Stage& stage = scene_.stages[state_.stage];
  StageRecord record;
  record.first_row = state_.stage_first_row;
  record.last_row = static_cast<int64_t>(series_.rows()) - 1;
  record.stop_reason = reason;
  if (stage.detect_asymptote) {
    record.asymptote = detector_.Evaluate();
    record.asymptote_p_kpa = series_.Last("p_kpa");
    record.asymptote_e = series_.Last("e");
  }
  state_.records.push_back(record);
  progress_.Finish();
  if (!options_.quiet) {
    std::fprintf(stderr, "stage %lld '%s' done after %lld steps: %s\n",
                 static_cast<long long>(state_.stage + 1), stage.name.c_str(),
                 static_cast<long long>(engine_->step() - state_.stage_start_step), reason.c_str());
  }
  ++state_.stage;
  state_.stage_started = false;
}

void Simulation::ReportProgress() {
  const Stopwatch& clock = stage_clock_;
  if (!progress_.Due()) return;
  const Stage& stage = scene_.stages[state_.stage];
  // Fraction of the stage done, from the stop condition closest to completion.
  double fraction = 0;
  const StopConditions& stop = stage.stop;
  if (stop.steps) fraction = std::max(fraction, double(engine_->step() - state_.stage_start_step) / *stop.steps);
  if (stop.time_s) fraction = std::max(fraction, (engine_->time() - state_.stage_start_time) / *stop.time_s);
  if (stop.strain_norm) fraction = std::max(fraction, state_.stage_strain_norm / *stop.strain_norm);
  // From a contact-free start, progress in ln p counts from the first
  // positive pressure seen in the stage.
  if (eta_stage_ != state_.stage) {
    eta_stage_ = state_.stage;
    eta_p0_ = state_.stage_start_p;
  }
  if (!(eta_p0_ > 0) && last_p_kpa_ > 0) eta_p0_ = last_p_kpa_;
  if (stop.mean_stress_kpa && last_p_kpa_ > 0 && eta_p0_ > 0) {
    const double done = std::log(last_p_kpa_ / eta_p0_);
    const double total = std::log(*stop.mean_stress_kpa / eta_p0_);
    if (total != 0) fraction = std::max(fraction, done / total);
  }
  const double steps_per_second = static_cast<double>(engine_->step() - stage_clock_start_step_) /
                                  std::max(1e-9, clock.Seconds());
  std::string eta = "?";
  if (fraction > 1e-3 && fraction < 1) {
    const double stage_seconds = clock.Seconds();
    const double remaining = stage_seconds * (1 - fraction) / fraction;
    eta = fmt::format("{:.0f}s", remaining);
  }
  progress_.Report(fmt::format("stage {}/{} '{}' | step {} | {:.0f} steps/s | ETA {} | p {:.4g} kPa "
                               "| e {:.4f} | psi_sigma {:.2f} deg",
                               state_.stage + 1, scene_.stages.size(), stage.name, engine_->step(),
                               steps_per_second, eta, last_p_kpa_, engine_->void_ratio(),
                               last_psi_deg_));
}


namespace {

std::vector<double> Flatten(const std::vector<Vec4>& values) {
  std::vector<double> flat;
  flat.reserve(values.size() * 4);
  for (const Vec4& v : values) flat.insert(flat.end(), {v.x, v.y, v.z, v.w});
  return flat;
}

std::vector<Vec4> Unflatten4(const std::vector<double>& flat) {
  std::vector<Vec4> values(flat.size() / 4);
  for (size_t i = 0; i < values.size(); ++i) {
    values[i] = {flat[4 * i], flat[4 * i + 1], flat[4 * i + 2], flat[4 * i + 3]};
  }
  return values;
}

std::vector<double> Flatten(const std::vector<Vec3>& values) {
  std::vector<double> flat;
  flat.reserve(values.size() * 3);
  for (const Vec3& v : values) flat.insert(flat.end(), {v.x, v.y, v.z});
  return flat;
}

std::vector<Vec3> Unflatten3(const std::vector<double>& flat) {
  std::vector<Vec3> values(flat.size() / 3);
  for (size_t i = 0; i < values.size(); ++i) values[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  return values;
}

std::vector<double> ToVector(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
std::array<double, 3> ToArray(const std::vector<double>& v) {
  GRANASYM_CHECK(v.size() == 3) << "expected 3 values, got " << v.size();
  return {v[0], v[1], v[2]};
}

void WritePacking(Hdf5File& file, const std::string& group, const Packing& packing) {
  std::vector<double> positions;
  positions.reserve(packing.size() * 3);
  for (const auto& x : packing.positions) positions.insert(positions.end(), {x[0], x[1], x[2]});
  file.WriteDoubles(group + "/cell", ToVector(packing.cell), "m");
  file.WriteMatrix(group + "/positions", positions, packing.size(), 3, "m");
  file.WriteDoubles(group + "/radii", packing.radii, "m");
}

Packing ReadPacking(const Hdf5File& file, const std::string& group) {
  Packing packing;
  packing.cell = ToArray(file.ReadDoubles(group + "/cell"));
  size_t rows = 0, cols = 0;
  const std::vector<double> positions = file.ReadMatrix(group + "/positions", &rows, &cols);
  packing.radii = file.ReadDoubles(group + "/radii");
  GRANASYM_CHECK(cols == 3 && rows == packing.radii.size());
  packing.positions.resize(rows);
  for (size_t i = 0; i < rows; ++i) {
    packing.positions[i] = {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
  }
  return packing;
}

}  // namespace

void Simulation::WriteResults(const std::string& path, const RunSummary& summary) const {
  Hdf5File file = Hdf5File::CreateAtomic(path);
  file.WriteString("/scene", scene_.text);
  file.SetAttribute("/scene", "origin", scene_.origin);
  series_.Write(file, "/series");
  if (!histogram_edges_.empty()) {
    const size_t bins = histogram_edges_.size() - 1;
    file.WriteDoubles("/series_histogram/edges", histogram_edges_, "1");
    file.WriteMatrix("/series_histogram/counts", histogram_rows_, histogram_rows_.size() / bins,
                     bins, "1");
    file.SetAttribute("/series_histogram", "description",
                      "relative overlap u/(r_i + r_j) counts per output row and bin");
  }
  file.CreateGroup("/stages");
  for (size_t k = 0; k < state_.records.size(); ++k) {
    const Stage& stage = scene_.stages[k];
    const StageRecord& record = state_.records[k];
    const std::string group = fmt::format("/stages/{:03d}", k);
    file.CreateGroup(group);
    file.SetAttribute(group, "name", stage.name);
    file.SetAttribute(group, "type", ToString(stage.type));
    file.SetAttribute(group, "first_row", record.first_row);
    file.SetAttribute(group, "last_row", record.last_row);
    file.SetAttribute(group, "stop_reason", record.stop_reason);
    if (stage.detect_asymptote) {
      file.SetAttribute(group, "asymptote_criterion", stage.asymptote.Describe());
      file.SetAttribute(group, "asymptote_detected", int64_t{record.asymptote.detected});
      file.SetAttribute(group, "asymptote_psi_sigma_deg", record.asymptote.psi_sigma / kDegree);
      file.SetAttribute(group, "asymptote_psi_change_deg", record.asymptote.psi_change_deg);
      file.SetAttribute(group, "asymptote_lnp_half_difference",
                        record.asymptote.lnp_half_difference);
      file.SetAttribute(group, "asymptote_dlnp_dstrain", record.asymptote.slope_lnp);
      file.SetAttribute(group, "asymptote_dln1pe_dlnp", record.asymptote.slope_lnv_lnp);
      file.SetAttribute(group, "asymptote_p_kpa", record.asymptote_p_kpa);
      file.SetAttribute(group, "asymptote_e", record.asymptote_e);
    }
    if (stage.type == StageType::kStrainPath) {
      file.SetAttribute(group, "psi_epsilon_deg", stage.psi_epsilon / kDegree);
      file.SetAttribute(group, "stretching_rate_per_s", stage.stretching_rate);
    }
  }
  const std::string s = "/summary";
  file.CreateGroup(s);
  file.SetAttribute(s, "termination", ToString(summary.termination));
  file.SetAttribute(s, "message", summary.message);
  file.SetAttribute(s, "report", summary.OneLine());
  file.SetAttribute(s, "steps", summary.steps);
  file.SetAttribute(s, "particles", summary.particles);
  file.SetAttribute(s, "simulated_time_s", summary.simulated_time);
  file.SetAttribute(s, "wall_s", summary.wall_seconds);
  file.SetAttribute(s, "loop_wall_s", summary.loop_seconds);
  file.SetAttribute(s, "particle_steps_per_s", summary.particle_steps_per_second);
  file.SetAttribute(s, "neighbor_builds", summary.neighbor_builds);
  file.SetAttribute(s, "threads", static_cast<int64_t>(summary.threads));
  file.SetAttribute(s, "stages_completed", static_cast<int64_t>(state_.records.size()));
  file.SetAttribute(s, "time_step_s", engine_->time_step());
  const ContactDurations durations = ComputeContactDurations(initial_.radii, scene_.material);
  file.SetAttribute(s, "contact_duration_min_reduced_mass_s", durations.smallest_reduced_mass);
  file.SetAttribute(s, "contact_duration_max_reduced_mass_s", durations.largest_reduced_mass);
  file.SetAttribute(s, "contact_duration_min_single_mass_s", durations.smallest_single_mass);
  file.SetAttribute(s, "contact_duration_max_single_mass_s", durations.largest_single_mass);
  file.SetAttribute(s, "critical_time_step_s", durations.critical_time_step);
  file.SetAttribute(s, "time_step_over_min_contact_duration",
                    engine_->time_step() / durations.smallest_reduced_mass);

  const Packing current = engine_->CurrentPacking();
  WritePacking(file, "/final_state", current);
  std::vector<Vec4> velocity(engine_->size()), spin(engine_->size());
  for (size_t k = 0; k < engine_->size(); ++k) {
    velocity[engine_->ids()[k]] = engine_->velocities()[k];
    spin[engine_->ids()[k]] = engine_->spins()[k];
  }
  std::vector<double> v, w;
  for (size_t i = 0; i < velocity.size(); ++i) {
    v.insert(v.end(), {velocity[i].x, velocity[i].y, velocity[i].z});
    w.insert(w.end(), {spin[i].x, spin[i].y, spin[i].z});
  }
  file.WriteMatrix("/final_state/velocities", v, velocity.size(), 3, "m/s");
  file.WriteMatrix("/final_state/spins", w, spin.size(), 3, "rad/s");
  WritePacking(file, "/sample", initial_);
  if (generated_) {
    file.WriteDoubles("/sample/gsd_diameters", generation_.sieve_diameters, "m");
    file.WriteDoubles("/sample/gsd_target_percent", generation_.target_passing, "%");
    file.WriteDoubles("/sample/gsd_achieved_percent", generation_.achieved_passing, "%");
  }
  file.Commit();
}

void Simulation::WriteCheckpoint() const {
  Hdf5File file = Hdf5File::CreateAtomic(options_.output_path + ".ckpt");
  file.WriteString("/scene", scene_.text);
  WritePacking(file, "/sample", initial_);
  const Engine::State engine = engine_->Save();
  file.WriteDoubles("/engine/position", Flatten(engine.position));
  file.WriteDoubles("/engine/velocity", Flatten(engine.velocity));
  file.WriteDoubles("/engine/spin", Flatten(engine.spin));
  file.WriteInts("/engine/id", engine.id);
  file.WriteDoubles("/engine/cell", ToVector(engine.cell));
  file.WriteDoubles("/engine/gradient", ToVector(engine.gradient));
  file.SetAttribute("/engine", "time", engine.time);
  file.SetAttribute("/engine", "step", engine.step);
  file.SetAttribute("/engine", "max_displacement", engine.max_displacement);
  file.SetAttribute("/engine", "threads", static_cast<int64_t>(threads_));
  const NeighborList::State& list = engine.neighbors;
  file.WriteInts("/engine/list/offsets", list.offsets);
  file.WriteInts("/engine/list/neighbors", std::vector<int64_t>(list.neighbors.begin(), list.neighbors.end()));
  file.WriteDoubles("/engine/list/shear", Flatten(list.shear));
  file.WriteDoubles("/engine/list/build_positions", Flatten(list.build_positions));
  file.WriteDoubles("/engine/list/build_cell", ToVector(list.build_cell));
  file.SetAttribute("/engine/list", "skin", list.skin);
  file.SetAttribute("/engine/list", "max_radius", list.max_radius);
  file.SetAttribute("/engine/list", "builds", list.builds);

  const std::string r = "/runner";
  file.CreateGroup(r);
  file.SetAttribute(r, "stage", state_.stage);
  file.SetAttribute(r, "stage_started", int64_t{state_.stage_started});
  file.SetAttribute(r, "stage_start_step", state_.stage_start_step);
  file.SetAttribute(r, "stage_start_time", state_.stage_start_time);
  file.SetAttribute(r, "stage_start_p", state_.stage_start_p);
  file.SetAttribute(r, "stage_strain_norm", state_.stage_strain_norm);
  file.SetAttribute(r, "next_sample_strain", state_.next_sample_strain);
  file.SetAttribute(r, "strain_since_output", state_.strain_since_output);
  file.SetAttribute(r, "steps_since_output", state_.steps_since_output);
  file.SetAttribute(r, "stage_first_row", state_.stage_first_row);
  file.WriteDoubles(r + "/stage_start_cell", ToVector(state_.stage_start_cell));
  file.WriteDoubles(r + "/controlled_rate", ToVector(state_.controlled_rate));
  file.WriteDoubles(r + "/integral", ToVector(state_.integral));
  std::vector<double> samples;
  for (const auto& sample : detector_.samples()) {
    samples.insert(samples.end(), {sample.strain, sample.psi_sigma, sample.log_p, sample.log_volume});
  }
  file.WriteDoubles(r + "/detector_samples", samples);
  for (size_t k = 0; k < state_.records.size(); ++k) {
    const StageRecord& record = state_.records[k];
    const std::string g = fmt::format("{}/records/{:03d}", r, k);
    file.CreateGroup(g);
    file.SetAttribute(g, "first_row", record.first_row);
    file.SetAttribute(g, "last_row", record.last_row);
    file.SetAttribute(g, "stop_reason", record.stop_reason);
    file.WriteDoubles(g + "/asymptote",
                      {double(record.asymptote.detected), record.asymptote.psi_sigma,
                       record.asymptote.psi_change_deg, record.asymptote.lnp_half_difference,
                       record.asymptote.slope_lnp, record.asymptote.slope_lnv_lnp,
                       record.asymptote_p_kpa, record.asymptote_e});
  }
  series_.Write(file, "/series");
  file.WriteDoubles("/histogram_rows", histogram_rows_);
  if (generated_) {
    file.WriteDoubles("/generation/diameters", generation_.sieve_diameters);
    file.WriteDoubles("/generation/target", generation_.target_passing);
    file.WriteDoubles("/generation/achieved", generation_.achieved_passing);
  }
  file.Commit();
}

void Simulation::LoadCheckpoint() {
  const std::string path = options_.output_path + ".ckpt";
  if (!std::filesystem::exists(path)) {
    throw InputError("--restart: no checkpoint '" + path +
                     "' (it is written next to --out during a run)");
  }
  const Hdf5File file = Hdf5File::OpenRead(path);
  if (file.ReadString("/scene") != scene_.text) {
    throw InputError("--restart: the scene '" + scene_.origin +
                     "' differs from the scene stored in the checkpoint '" + path +
                     "': restart with the same scene file");
  }
  initial_ = ReadPacking(file, "/sample");
  generated_ = file.Exists("/generation");
  if (generated_) {
    generation_.sieve_diameters = file.ReadDoubles("/generation/diameters");
    generation_.target_passing = file.ReadDoubles("/generation/target");
    generation_.achieved_passing = file.ReadDoubles("/generation/achieved");
  }
  const int64_t threads = file.ReadIntAttribute("/engine", "threads");
  if (threads != threads_ && !options_.quiet) {
    std::fprintf(stderr,
                 "warning: the checkpoint was written with %lld threads, continuing with %d: the "
                 "result will not be bit-identical to an uninterrupted run\n",
                 static_cast<long long>(threads), threads_);
  }
  Engine::State engine;
  engine.position = Unflatten4(file.ReadDoubles("/engine/position"));
  engine.velocity = Unflatten4(file.ReadDoubles("/engine/velocity"));
  engine.spin = Unflatten4(file.ReadDoubles("/engine/spin"));
  engine.id = file.ReadInts("/engine/id");
  engine.cell = ToArray(file.ReadDoubles("/engine/cell"));
  engine.gradient = ToArray(file.ReadDoubles("/engine/gradient"));
  engine.time = file.ReadDoubleAttribute("/engine", "time");
  engine.step = file.ReadIntAttribute("/engine", "step");
  engine.max_displacement = file.ReadDoubleAttribute("/engine", "max_displacement");
  NeighborList::State& list = engine.neighbors;
  list.offsets = file.ReadInts("/engine/list/offsets");
  const std::vector<int64_t> neighbors = file.ReadInts("/engine/list/neighbors");
  list.neighbors.assign(neighbors.begin(), neighbors.end());
  list.shear = Unflatten3(file.ReadDoubles("/engine/list/shear"));
  list.build_positions = Unflatten4(file.ReadDoubles("/engine/list/build_positions"));
  list.build_cell = ToArray(file.ReadDoubles("/engine/list/build_cell"));
  list.skin = file.ReadDoubleAttribute("/engine/list", "skin");
  list.max_radius = file.ReadDoubleAttribute("/engine/list", "max_radius");
  list.builds = file.ReadIntAttribute("/engine/list", "builds");

  Engine::Options engine_options;
  engine_options.time_step = scene_.TimeStep(initial_);
  engine_options.skin_fraction = scene_.skin_fraction;
  engine_options.threads = threads_;
  engine_.emplace(initial_, scene_.material, engine_options);
  engine_->Restore(std::move(engine));
  initial_cell_ = initial_.cell;

  const std::string r = "/runner";
  state_.stage = file.ReadIntAttribute(r, "stage");
  state_.stage_started = file.ReadIntAttribute(r, "stage_started") != 0;
  state_.stage_start_step = file.ReadIntAttribute(r, "stage_start_step");
  state_.stage_start_time = file.ReadDoubleAttribute(r, "stage_start_time");
  state_.stage_start_p = file.ReadDoubleAttribute(r, "stage_start_p");
  state_.stage_strain_norm = file.ReadDoubleAttribute(r, "stage_strain_norm");
  state_.next_sample_strain = file.ReadDoubleAttribute(r, "next_sample_strain");
  state_.strain_since_output = file.ReadDoubleAttribute(r, "strain_since_output");
  state_.steps_since_output = file.ReadIntAttribute(r, "steps_since_output");
  state_.stage_first_row = file.ReadIntAttribute(r, "stage_first_row");
  state_.stage_start_cell = ToArray(file.ReadDoubles(r + "/stage_start_cell"));
  state_.controlled_rate = ToArray(file.ReadDoubles(r + "/controlled_rate"));
  state_.integral = ToArray(file.ReadDoubles(r + "/integral"));
  if (state_.stage < static_cast<int64_t>(scene_.stages.size())) {
    detector_ = AsymptoteDetector(scene_.stages[state_.stage].asymptote);
  }
  const std::vector<double> samples = file.ReadDoubles(r + "/detector_samples");
  std::vector<AsymptoteDetector::Sample> detector_samples;
  for (size_t k = 0; k + 3 < samples.size(); k += 4) {
    detector_samples.push_back({samples[k], samples[k + 1], samples[k + 2], samples[k + 3]});
  }
  detector_.set_samples(detector_samples);
  if (file.Exists(r + "/records")) {
    for (const std::string& name : file.List(r + "/records")) {
      const std::string g = r + "/records/" + name;
      StageRecord record;
      record.first_row = file.ReadIntAttribute(g, "first_row");
      record.last_row = file.ReadIntAttribute(g, "last_row");
      record.stop_reason = file.ReadStringAttribute(g, "stop_reason");
      const std::vector<double> a = file.ReadDoubles(g + "/asymptote");
      record.asymptote.detected = a[0] != 0;
      record.asymptote.psi_sigma = a[1];
      record.asymptote.psi_change_deg = a[2];
      record.asymptote.lnp_half_difference = a[3];
      record.asymptote.slope_lnp = a[4];
      record.asymptote.slope_lnv_lnp = a[5];
      record.asymptote_p_kpa = a[6];
      record.asymptote_e = a[7];
      state_.records.push_back(record);
    }
  }
  series_ = TimeSeries::Read(file, "/series");
  histogram_rows_ = file.ReadDoubles("/histogram_rows");
}

RunSummary Simulation::Run() {
  Stopwatch wall;
  SignalGuard guard;
  threads_ = options_.threads > 0 ? options_.threads : scene_.threads;
  if (options_.restart) {
    LoadCheckpoint();
  } else {
    Setup();
    if (generated_ && !options_.quiet) std::fprintf(stderr, "%s", generation_.Table().c_str());
  }
  PrepareMeasurements();
  if (!options_.quiet) {
    const ContactDurations d = ComputeContactDurations(initial_.radii, scene_.material);
    std::fprintf(stderr,
                 "%zu spheres, %d threads; time step %.4g s = %.3f of the smallest contact "
                 "duration %.4g s (reduced mass; %.4g s with one sphere's mass; largest %.4g / "
                 "%.4g s); stability limit %.4g s\n",
                 initial_.size(), threads_, engine_->time_step(),
                 engine_->time_step() / d.smallest_reduced_mass, d.smallest_reduced_mass,
                 d.smallest_single_mass, d.largest_reduced_mass, d.largest_single_mass,
                 d.critical_time_step);
  }
  RunSummary summary;
  summary.particles = static_cast<int64_t>(engine_->size());
  summary.threads = threads_;
  summary.time_step = engine_->time_step();
  const int64_t first_step = engine_->step();
  double loop_seconds = 0;
  auto finish = [&](Termination termination, const std::string& message) {
    summary.termination = termination;
    summary.message = message;
    summary.steps = engine_->step();
    summary.simulated_time = engine_->time();
    summary.loop_seconds = loop_seconds;
    summary.wall_seconds = wall.Seconds();
    summary.particle_steps_per_second =
        loop_seconds > 0 ? double(engine_->step() - first_step) * engine_->size() / loop_seconds : 0;
    summary.neighbor_builds = engine_->neighbors().builds();
    summary.rows = static_cast<int64_t>(series_.rows());
    progress_.Finish();
    if (termination != Termination::kCompleted) WriteCheckpoint();
    WriteResults(options_.output_path, summary);
    if (termination == Termination::kCompleted && !options_.keep_checkpoint) {
      std::remove((options_.output_path + ".ckpt").c_str());
    }
    return summary;
  };

  try {
    return Loop(summary, finish, loop_seconds);
  } catch (const RuntimeError& error) {
    // Keep what was computed: results and a checkpoint of the last state.
    return finish(Termination::kFailed, error.what());
  }
}

template <typename Finish>
RunSummary Simulation::Loop(RunSummary& summary, Finish& finish, double& loop_seconds) {
  Stopwatch since_checkpoint;
  const double dt = engine_->time_step();
  const OutputOptions& output = scene_.output;
  while (state_.stage < static_cast<int64_t>(scene_.stages.size())) {
    Stopwatch step_clock;
    const Stage& stage = scene_.stages[state_.stage];
    if (!state_.stage_started) {
      StartStage();
      stage_clock_ = Stopwatch();
      stage_clock_start_step_ = engine_->step();
    }
    const bool strain_stop = StrainStopReached(stage);
    const bool output_due = series_.rows() == 0 || engine_->step() == state_.stage_start_step ||
                            state_.strain_since_output >= output.interval_strain * (1 - 1e-9) ||
                            (output.interval_steps > 0 &&
                             state_.steps_since_output >= output.interval_steps);
    const bool sample_due =
        stage.detect_asymptote && state_.stage_strain_norm >= state_.next_sample_strain;
    const bool rest_check = stage.type == StageType::kRest &&
                            (engine_->step() - state_.stage_start_step) % stage.control.check_interval == 0;
    const bool need_stress = output_due || sample_due || strain_stop || rest_check ||
                             StageNeedsStressEveryStep(stage);
    engine_->ComputeForces({need_stress, stage.type != StageType::kStrainPath});
    if (need_stress) {
      const double p = MeanStressKpa();
      if (!std::isfinite(p)) {
        loop_seconds += step_clock.Seconds();
        return finish(Termination::kFailed,
                      fmt::format("non-finite stress at step {}: the motion became unstable "
                                  "(time step {:.3g} s too large for the contact stiffness?)",
                                  engine_->step(), dt));
      }
      if (std::isnan(state_.stage_start_p)) state_.stage_start_p = p;
    }
    Control(stage, need_stress);
    if (sample_due) {
      const AxisymmetricStress stress = AxisymmetricFromTensor(engine_->sums().stress);
      const double p = stress.mean() / kKiloPascal;
      detector_.Add({state_.stage_strain_norm, stress.psi(),
                     p > 0 ? std::log(p) : std::numeric_limits<double>::quiet_NaN(),
                     std::log1p(engine_->void_ratio())});
      state_.next_sample_strain += stage.asymptote.sample_strain;
    }
    const std::optional<std::string> reason = CheckStop(stage, need_stress, sample_due);
    if (output_due || reason) {
      AddRow();
      if (series_.Last("overlap_max") > 0.5) {
        loop_seconds += step_clock.Seconds();
        return finish(Termination::kFailed,
                      fmt::format("relative overlap {:.3g} above 0.5 at step {}: spheres "
                                  "interpenetrate (loading too fast or time step too large)",
                                  series_.Last("overlap_max"), engine_->step()));
      }
    }
    if (reason) {
      // The stage ends at the state that met its condition (its last row);
      // the next stage starts from the same state: the engine re-evaluates
      // its forces there without advancing the shear history.
      FinishStage(*reason);
    } else {
      engine_->Integrate();
      const auto& g = engine_->velocity_gradient();
      const double increment = dt * std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      state_.stage_strain_norm += increment;
      state_.strain_since_output += increment;
      ++state_.steps_since_output;
    }
    loop_seconds += step_clock.Seconds();

    if (state_.stage < static_cast<int64_t>(scene_.stages.size())) ReportProgress();
    const bool test_interrupt = options_.interrupt_after_steps >= 0 &&
                                engine_->step() >= options_.interrupt_after_steps;
    if (g_interrupt || test_interrupt) {
      return finish(Termination::kInterrupted,
                    fmt::format("interrupted at step {}; continue with --restart", engine_->step()));
    }
    if ((engine_->step() & 255) == 0 && since_checkpoint.Seconds() >= output.checkpoint_interval_s) {
      WriteCheckpoint();
      RunSummary partial = summary;
      partial.termination = Termination::kInterrupted;
      partial.message = "run in progress (partial results at the last checkpoint)";
      partial.steps = engine_->step();
      WriteResults(options_.output_path, partial);
      since_checkpoint = Stopwatch();
    }
  }
  return finish(Termination::kCompleted, "all stages completed");
}

}  // namespace

std::string ToString(Termination termination) {
  switch (termination) {
    case Termination::kCompleted: return "completed";
    case Termination::kInterrupted: return "interrupted";
    case Termination::kFailed: return "failed";
  }
  return "unknown";
}

bool RunOptions::IsValid(std::string* why) const {
  if (output_path.empty()) return *why = "output_path is empty", false;
  if (threads < 0) return *why = "threads must be >= 0 (0: the scene's)", false;
  return true;
}

std::string RunSummary::OneLine() const {
  return fmt::format("{}: {} steps, {} particles, {:.4g} s simulated, {:.1f} s wall ({:.1f} s "
                     "loop), {:.3g} particle-steps/s ({:.3f} us per particle-step), {} threads, "
                     "{} list builds, {} rows: {}",
                     ToString(termination), steps, particles, simulated_time, wall_seconds,
                     loop_seconds, particle_steps_per_second,
                     particle_steps_per_second > 0 ? 1e6 / particle_steps_per_second : 0.0,
                     threads, neighbor_builds, rows, message);
}

RunSummary RunScene(const Scene& scene, const RunOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("run options: " + why);
  Simulation simulation(scene, options);
  return simulation.Run();
}

Packing ReadResultPacking(const std::string& result_path, const std::string& group) {
  const Hdf5File file = Hdf5File::OpenRead(result_path);
  if (!file.Exists(group + "/positions")) {
    throw InputError(result_path + ": no packing in '" + group +
                     "' (expected a granasym DEM result file)");
  }
  return ReadPacking(file, group);
}

}  // namespace granasym::dem
