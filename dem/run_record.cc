#include "dem/run_record.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "common/config.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "dem/run_record_names.h"
#include "dem/strain_path_stage.h"

namespace granasym::dem {

namespace {
constexpr bool SameText(const char* a, const char* b) {
  while (*a != '\0' && *a == *b) ++a, ++b;
  return *a == *b;
}
template <size_t k>
constexpr bool TerminationIs(Termination value, const char* name) {
  return EnumNames<Termination>::kEntries[k].value == value &&
         SameText(EnumNames<Termination>::kEntries[k].name, name);
}
}  // namespace
// The spellings readers outside dem/ use (run_record_names.h).
static_assert(TerminationIs<0>(Termination::kNotRun, record::kTerminationNotRun) &&
              TerminationIs<1>(Termination::kCompleted, record::kTerminationCompleted) &&
              TerminationIs<2>(Termination::kInterrupted, record::kTerminationInterrupted) &&
              TerminationIs<3>(Termination::kFailed, record::kTerminationFailed));

namespace {

std::string Join(const std::string& group, const char* name) { return group + "/" + name; }

// Vec3 and Vec4 are plain rows of 3 and 4 doubles, stored as N×3 and N×4.
template <typename Vec>
constexpr size_t kWidth = sizeof(Vec) / sizeof(double);

template <typename Vec>
void WriteRows(Hdf5File& file, const std::string& name, const std::vector<Vec>& values) {
  static_assert(sizeof(Vec) == kWidth<Vec> * sizeof(double), "rows of doubles only");
  std::vector<double> flat(values.size() * kWidth<Vec>);
  if (!flat.empty()) std::memcpy(flat.data(), values.data(), flat.size() * sizeof(double));
  file.WriteMatrix(name, flat, values.size(), kWidth<Vec>);
}

template <typename Vec>
std::vector<Vec> ReadRows(const Hdf5File& file, const std::string& name) {
  size_t rows = 0, cols = 0;
  const std::vector<double> flat = file.ReadMatrix(name, &rows, &cols);
  if (rows > 0 && cols != kWidth<Vec>) {
    throw InputError(
        fmt::format("{}: {} has {} columns, expected {}", file.path(), name, cols, kWidth<Vec>));
  }
  std::vector<Vec> values(rows);
  static_assert(std::is_trivially_copyable_v<Vec>, "rows of doubles only");
  if (rows > 0)
    std::memcpy(static_cast<void*>(values.data()), flat.data(), flat.size() * sizeof(double));
  return values;
}

std::vector<double> ToVector(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

std::array<double, 3> ReadArray3(const Hdf5File& file, const std::string& name) {
  const std::vector<double> v = file.ReadDoubles(name);
  if (v.size() != 3) {
    throw InputError(fmt::format("{}: {} has {} values, expected 3", file.path(), name, v.size()));
  }
  return {v[0], v[1], v[2]};
}

template <typename E>
E ReadEnum(const Hdf5File& file, const std::string& group, const char* name) {
  const std::string text = file.ReadStringAttribute(group, name);
  const std::optional<E> value = FromString<E>(text);
  if (!value) {
    throw InputError(fmt::format("{}: {} attribute {} = '{}' is not one of {}", file.path(), group,
                                 name, text, AllowedNames<E>()));
  }
  return *value;
}

// A comma-separated list of names ("" for none).
template <typename E>
std::vector<E> ParseNames(const Hdf5File& file, const std::string& group, const char* name) {
  const std::string text = file.ReadStringAttribute(group, name);
  std::vector<E> values;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    std::string item = text.substr(start, end - start);
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    const std::optional<E> value = FromString<E>(item);
    if (!value) {
      throw InputError(fmt::format("{}: {} attribute {}: '{}' is not one of {}", file.path(), group,
                                   name, item, AllowedNames<E>()));
    }
    values.push_back(*value);
    start = end + 1;
  }
  return values;
}

// The numbers of an asymptote record with their attribute names (one table
// for the writer and the reader).
std::vector<std::pair<const char*, double*>> AsymptoteDoubles(AsymptoteRecord& a) {
  using namespace record;
  AsymptoteCriterion& c = a.criterion;
  return {
      {kAsymptoteSampleStrain, &c.sample_strain},
      {kAsymptoteCriterionWindowStrain, &c.window_strain},
      {kAsymptoteCriterionWindowLnp, &c.window_lnp},
      {kAsymptotePsiTolerance, &c.psi_tolerance_deg},
      {kAsymptoteLnpTolerance, &c.lnp_tolerance},
      {kAsymptoteSlopeTolerance, &c.slope_tolerance},
      {kAsymptotePsiEpsilonTolerance, &c.psi_epsilon_tolerance_deg},
      {kAsymptoteLnvTolerance, &c.lnv_tolerance},
      {kAsymptoteWindowStrain, &a.window_strain},
      {kAsymptoteWindowLnp, &a.window_lnp},
      {kAsymptoteMeanStressKpa, &a.mean_stress_kpa},
      {kAsymptoteVoidRatio, &a.void_ratio},
      {kAsymptotePsiSigmaDeg, &a.psi_sigma_deg},
      {kAsymptotePsiEpsilonDeg, &a.psi_epsilon_deg},
      {kAsymptoteQOverP, &a.q_over_p},
      {kAsymptoteCoordination, &a.coordination},
      {kAsymptoteMechanicalCoordination, &a.mechanical_coordination},
      {kAsymptoteInertialNumberDmin, &a.inertial_number_dmin},
      {kAsymptoteInertialNumberDmax, &a.inertial_number_dmax},
      {kAsymptoteMaxRelativeOverlap, &a.max_relative_overlap},
      {kAsymptotePsiChangeDeg, &a.psi_change_deg},
      {kAsymptoteLnpChange, &a.lnp_change},
      {kAsymptoteLnpHalfDifference, &a.lnp_half_difference},
      {kAsymptoteSlopeChange, &a.slope_change},
      {kAsymptotePsiEpsilonChangeDeg, &a.psi_epsilon_change_deg},
      {kAsymptoteLnvChange, &a.lnv_change},
      {kAsymptoteDlnpDstrain, &a.dlnp_dstrain},
      {kAsymptoteDln1peDlnp, &a.dln1pe_dlnp},
  };
}

bool Finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool Finite(const Vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

// A dataset whose values break the invariants of what it stores.
[[noreturn]] void Invalid(const Hdf5File& file, const std::string& dataset,
                          const std::string& what) {
  throw InputError(
      fmt::format("{}: dataset {} {} (the file is corrupt, or not written by granasym)",
                  file.path(), dataset, what));
}

// Rows of the form (x, y, z, w): finite, w > 0 (radii) or w >= 0 (inverse
// masses and inertias: 0 holds a sphere fixed).
void CheckRows(const Hdf5File& file, const std::string& dataset, const std::vector<Vec4>& rows,
               bool positive_w, const char* w_name) {
  for (size_t k = 0; k < rows.size(); ++k) {
    const Vec4& v = rows[k];
    if (!Finite(v) || (positive_w ? !(v.w > 0) : !(v.w >= 0))) {
      Invalid(file, dataset,
              fmt::format("row {} = ({:g}, {:g}, {:g}, {:g}) is not finite with {} {} 0", k, v.x,
                          v.y, v.z, v.w, w_name, positive_w ? ">" : ">="));
    }
  }
}

void CheckCell(const Hdf5File& file, const std::string& dataset,
               const std::array<double, 3>& cell) {
  for (double side : cell) {
    if (!(std::isfinite(side) && side > 0)) {
      Invalid(file, dataset,
              fmt::format("holds the cell sides {:g}, {:g}, {:g}: each must be finite and > 0",
                          cell[0], cell[1], cell[2]));
    }
  }
}

// The invariants of an engine state, checked before an engine uses it (a bad
// offset or id would index out of bounds). The checksums catch a flipped bit;
// these catch a file whose checksums match data that cannot be a state.
void CheckEngineState(const Hdf5File& file, const std::string& group, const Engine::State& state) {
  using namespace record;
  const size_t n = state.position.size();
  const std::string p = Join(group, kStatePosition), v = Join(group, kStateVelocity),
                    w = Join(group, kStateSpin), id = Join(group, kStateId);
  if (state.velocity.size() != n)
    Invalid(file, v,
            fmt::format("has {} rows for {} particles (rows of {})", state.velocity.size(), n, p));
  if (state.spin.size() != n)
    Invalid(file, w,
            fmt::format("has {} rows for {} particles (rows of {})", state.spin.size(), n, p));
  if (state.id.size() != n)
    Invalid(file, id,
            fmt::format("has {} ids for {} particles (rows of {})", state.id.size(), n, p));
  CheckRows(file, p, state.position, true, "radius");
  CheckRows(file, v, state.velocity, false, "inverse mass");
  CheckRows(file, w, state.spin, false, "inverse moment of inertia");
  std::vector<char> seen(n, 0);
  for (size_t k = 0; k < n; ++k) {
    const int64_t i = state.id[k];
    if (i < 0 || i >= static_cast<int64_t>(n) || seen[static_cast<size_t>(i)]) {
      Invalid(file, id,
              fmt::format("is not a permutation of 0..{}: entry {} = {} is {}", n - 1, k, i,
                          i < 0 || i >= static_cast<int64_t>(n) ? "out of range" : "repeated"));
    }
    seen[static_cast<size_t>(i)] = 1;
  }
  CheckCell(file, Join(group, kStateCell), state.cell);
  for (double g : state.gradient) {
    if (!std::isfinite(g)) Invalid(file, Join(group, kStateGradient), "is not finite");
  }
  if (!std::isfinite(state.time) || state.step < 0 ||
      !(std::isfinite(state.max_displacement) && state.max_displacement >= 0) ||
      !(std::isfinite(state.time_step) && state.time_step >= 0)) {
    Invalid(file, group,
            fmt::format("has time {:g}, step {}, max_displacement {:g}, time_step {:g} (finite, "
                        ">= 0)",
                        state.time, state.step, state.max_displacement, state.time_step));
  }
  const NeighborList::State& list = state.neighbors;
  const std::string l = Join(group, kListGroup);
  const std::string offsets = Join(l, kListOffsets), neighbors = Join(l, kListNeighbors);
  const int64_t pairs = static_cast<int64_t>(list.neighbors.size());
  if (list.offsets.size() != n + 1) {
    Invalid(file, offsets,
            fmt::format("has {} entries for {} particles (expected {})", list.offsets.size(), n,
                        n + 1));
  }
  if (list.offsets.front() != 0 || list.offsets.back() != pairs) {
    Invalid(file, offsets,
            fmt::format("runs from {} to {}, expected from 0 to the {} entries of {}",
                        list.offsets.front(), list.offsets.back(), pairs, neighbors));
  }
  for (size_t i = 0; i < n; ++i) {
    if (list.offsets[i + 1] < list.offsets[i]) {
      Invalid(file, offsets,
              fmt::format("decreases from {} to {} at particle {} (offsets never decrease)",
                          list.offsets[i], list.offsets[i + 1], i));
    }
  }
  for (size_t i = 0; i < n; ++i) {
    const int64_t begin = list.offsets[i], end = list.offsets[i + 1];
    int64_t previous = static_cast<int64_t>(i);
    for (int64_t k = begin; k < end; ++k) {
      const int64_t j = list.neighbors[static_cast<size_t>(k)];
      if (j <= previous || j >= static_cast<int64_t>(n)) {
        Invalid(file, neighbors,
                fmt::format("entry {} = {} (a neighbour of particle {}): the neighbours of i are "
                            "ascending, > i and < {}",
                            k, j, i, n));
      }
      previous = j;
    }
  }
  for (const auto& [name, history] :
       {std::pair{kListShear, &list.shear}, std::pair{kListRolling, &list.rolling}}) {
    const std::string dataset = Join(l, name);
    if (!history->empty() && static_cast<int64_t>(history->size()) != pairs) {
      Invalid(file, dataset,
              fmt::format("has {} rows for the {} entries of {} (or none)", history->size(), pairs,
                          neighbors));
    }
    for (size_t k = 0; k < history->size(); ++k) {
      if (!Finite((*history)[k])) Invalid(file, dataset, fmt::format("row {} is not finite", k));
    }
  }
  const std::string build_positions = Join(l, kListBuildPositions);
  if (list.build_positions.size() != n) {
    Invalid(file, build_positions,
            fmt::format("has {} rows for {} particles", list.build_positions.size(), n));
  }
  for (size_t k = 0; k < n; ++k) {
    if (!Finite(list.build_positions[k])) {
      Invalid(file, build_positions, fmt::format("row {} is not finite", k));
    }
  }
  CheckCell(file, Join(l, kListBuildCell), list.build_cell);
  if (!(std::isfinite(list.skin) && list.skin > 0) ||
      !(std::isfinite(list.max_radius) && list.max_radius > 0) || list.builds < 0) {
    Invalid(file, l,
            fmt::format("has skin {:g}, max_radius {:g} (finite, > 0) and builds {} (>= 0)",
                        list.skin, list.max_radius, list.builds));
  }
}

}  // namespace

std::string RunSummary::OneLine() const {
  const std::string steps_taken =
      min_time_step == max_time_step
          ? fmt::format("time step {:.4g} s", time_step)
          : fmt::format("time step {:.4g} .. {:.4g} s", min_time_step, max_time_step);
  return fmt::format(
             "{}: {} steps, {} particles, {:.4g} s simulated, {:.1f} s wall ({:.1f} s "
             "loop), {:.3g} particle-steps/s ({:.3f} us per particle-step), {} threads, "
             "{} list builds, {} rows, {}{}: {}",
             ToString(termination), steps, particles, simulated_time, wall_seconds, loop_seconds,
             particle_steps_per_second,
             particle_steps_per_second > 0 ? 1e6 / particle_steps_per_second : 0.0, threads,
             neighbor_builds, rows, steps_taken,
             stiffness_scaling != 1 ? fmt::format(", stiffness scaled by {:g}", stiffness_scaling)
                                    : "",
             message) +
         (validity.empty() ? "" : "; validity: " + validity);
}

void WritePacking(Hdf5File& file, const std::string& group, const Packing& packing) {
  std::vector<double> positions;
  positions.reserve(packing.size() * 3);
  for (const auto& x : packing.positions) positions.insert(positions.end(), {x[0], x[1], x[2]});
  file.WriteDoubles(Join(group, record::kCell), ToVector(packing.cell), "m");
  file.WriteMatrix(Join(group, record::kPositions), positions, packing.size(), 3, "m");
  file.WriteDoubles(Join(group, record::kRadii), packing.radii, "m");
}

Packing ReadPacking(const Hdf5File& file, const std::string& group) {
  if (!file.Exists(Join(group, record::kPositions))) {
    throw InputError(file.path() + ": no packing in '" + group +
                     "' (expected a granasym DEM result file)");
  }
  Packing packing;
  packing.cell = ReadArray3(file, Join(group, record::kCell));
  size_t rows = 0, cols = 0;
  const std::vector<double> positions =
      file.ReadMatrix(Join(group, record::kPositions), &rows, &cols);
  packing.radii = file.ReadDoubles(Join(group, record::kRadii));
  if (cols != 3 || rows != packing.radii.size()) {
    throw InputError(fmt::format("{}: {} holds {}×{} positions for {} radii", file.path(), group,
                                 rows, cols, packing.radii.size()));
  }
  CheckCell(file, Join(group, record::kCell), packing.cell);
  packing.positions.resize(rows);
  for (size_t i = 0; i < rows; ++i) {
    packing.positions[i] = {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
    const double radius = packing.radii[i];
    if (!(std::isfinite(positions[3 * i]) && std::isfinite(positions[3 * i + 1]) &&
          std::isfinite(positions[3 * i + 2]))) {
      Invalid(file, Join(group, record::kPositions), fmt::format("row {} is not finite", i));
    }
    if (!(std::isfinite(radius) && radius > 0)) {
      Invalid(file, Join(group, record::kRadii),
              fmt::format("entry {} = {:g} is not a radius (finite, > 0)", i, radius));
    }
  }
  return packing;
}

void WriteSample(Hdf5File& file, const Packing& packing, const GenerationReport* report) {
  WritePacking(file, record::kSample, packing);
  if (report) {
    file.WriteDoubles(Join(record::kSample, record::kGsdDiameters), report->sieve_diameters, "m");
    file.WriteDoubles(Join(record::kSample, record::kGsdTarget), report->target_passing, "%");
    file.WriteDoubles(Join(record::kSample, record::kGsdAchieved), report->achieved_passing, "%");
  }
}

bool ReadSample(const Hdf5File& file, Packing* packing, GenerationReport* report) {
  *packing = ReadPacking(file, record::kSample);
  const bool generated = file.Exists(Join(record::kSample, record::kGsdDiameters));
  if (generated && report) {
    report->count = packing->size();
    report->sieve_diameters = file.ReadDoubles(Join(record::kSample, record::kGsdDiameters));
    report->target_passing = file.ReadDoubles(Join(record::kSample, record::kGsdTarget));
    report->achieved_passing = file.ReadDoubles(Join(record::kSample, record::kGsdAchieved));
  }
  return generated;
}

void WriteEngineState(Hdf5File& file, const std::string& group, const Engine::State& state,
                      int threads) {
  WriteRows(file, Join(group, record::kStatePosition), state.position);
  WriteRows(file, Join(group, record::kStateVelocity), state.velocity);
  WriteRows(file, Join(group, record::kStateSpin), state.spin);
  file.WriteInts(Join(group, record::kStateId), state.id);
  file.WriteDoubles(Join(group, record::kStateCell), ToVector(state.cell), "m");
  file.WriteDoubles(Join(group, record::kStateGradient), ToVector(state.gradient), "1/s");
  file.SetAttribute(group, record::kStateTime, state.time);
  file.SetAttribute(group, record::kStateStep, state.step);
  file.SetAttribute(group, record::kStateTimeStep, state.time_step);
  file.SetAttribute(group, record::kStateMaxDisplacement, state.max_displacement);
  file.SetAttribute(group, record::kStateForcesCurrent, int64_t{state.forces_current});
  file.SetAttribute(group, record::kStateThreads, static_cast<int64_t>(threads));
  const NeighborList::State& list = state.neighbors;
  const std::string l = Join(group, record::kListGroup);
  file.WriteInts(Join(l, record::kListOffsets), list.offsets);
  file.WriteInts(Join(l, record::kListNeighbors),
                 std::vector<int64_t>(list.neighbors.begin(), list.neighbors.end()));
  WriteRows(file, Join(l, record::kListShear), list.shear);
  WriteRows(file, Join(l, record::kListRolling), list.rolling);
  WriteRows(file, Join(l, record::kListBuildPositions), list.build_positions);
  file.WriteDoubles(Join(l, record::kListBuildCell), ToVector(list.build_cell), "m");
  file.SetAttribute(l, record::kListSkin, list.skin);
  file.SetAttribute(l, record::kListMaxRadius, list.max_radius);
  file.SetAttribute(l, record::kListBuilds, list.builds);
}

Engine::State ReadEngineState(const Hdf5File& file, const std::string& group, int* threads) {
  if (!file.Exists(Join(group, record::kStatePosition))) {
    throw InputError(file.path() + ": no engine state in '" + group + "'");
  }
  Engine::State state;
  state.position = ReadRows<Vec4>(file, Join(group, record::kStatePosition));
  state.velocity = ReadRows<Vec4>(file, Join(group, record::kStateVelocity));
  state.spin = ReadRows<Vec4>(file, Join(group, record::kStateSpin));
  state.id = file.ReadInts(Join(group, record::kStateId));
  state.cell = ReadArray3(file, Join(group, record::kStateCell));
  state.gradient = ReadArray3(file, Join(group, record::kStateGradient));
  state.time = file.ReadDoubleAttribute(group, record::kStateTime);
  state.step = file.ReadIntAttribute(group, record::kStateStep);
  // States written before Δt was stored have none: 0 keeps the engine's.
  if (file.HasAttribute(group, record::kStateTimeStep)) {
    state.time_step = file.ReadDoubleAttribute(group, record::kStateTimeStep);
  }
  state.max_displacement = file.ReadDoubleAttribute(group, record::kStateMaxDisplacement);
  state.forces_current = file.ReadIntAttribute(group, record::kStateForcesCurrent) != 0;
  if (threads) *threads = static_cast<int>(file.ReadIntAttribute(group, record::kStateThreads));
  NeighborList::State& list = state.neighbors;
  const std::string l = Join(group, record::kListGroup);
  list.offsets = file.ReadInts(Join(l, record::kListOffsets));
  const std::vector<int64_t> neighbors = file.ReadInts(Join(l, record::kListNeighbors));
  for (size_t k = 0; k < neighbors.size(); ++k) {
    // Stored as 64-bit, held as 32-bit indices.
    if (neighbors[k] < 0 || neighbors[k] > std::numeric_limits<int32_t>::max()) {
      Invalid(file, Join(l, record::kListNeighbors),
              fmt::format("entry {} = {} is not a particle index", k, neighbors[k]));
    }
  }
  list.neighbors.assign(neighbors.begin(), neighbors.end());
  list.shear = ReadRows<Vec3>(file, Join(l, record::kListShear));
  list.rolling = ReadRows<Vec3>(file, Join(l, record::kListRolling));
  list.build_positions = ReadRows<Vec4>(file, Join(l, record::kListBuildPositions));
  list.build_cell = ReadArray3(file, Join(l, record::kListBuildCell));
  list.skin = file.ReadDoubleAttribute(l, record::kListSkin);
  list.max_radius = file.ReadDoubleAttribute(l, record::kListMaxRadius);
  list.builds = file.ReadIntAttribute(l, record::kListBuilds);
  CheckEngineState(file, group, state);
  return state;
}

void WriteFinalState(Hdf5File& file, const Engine& engine, int threads) {
  const std::string group = record::kFinalState;
  WritePacking(file, group, engine.CurrentPacking());
  const size_t n = engine.size();
  std::vector<double> v(3 * n), w(3 * n);
  for (size_t k = 0; k < n; ++k) {
    const size_t i = static_cast<size_t>(engine.ids()[k]);
    const Vec4& velocity = engine.velocities()[k];
    const Vec4& spin = engine.spins()[k];
    v[3 * i] = velocity.x, v[3 * i + 1] = velocity.y, v[3 * i + 2] = velocity.z;
    w[3 * i] = spin.x, w[3 * i + 1] = spin.y, w[3 * i + 2] = spin.z;
  }
  file.WriteMatrix(Join(group, record::kVelocities), v, n, 3, "m/s");
  file.WriteMatrix(Join(group, record::kSpins), w, n, 3, "rad/s");
  WriteEngineState(file, Join(group, record::kEngineGroup), engine.Save(), threads);
}

void WriteHistograms(Hdf5File& file, const std::vector<double>& edges,
                     const std::vector<double>& rows) {
  if (edges.empty()) return;
  const size_t bins = edges.size() - 1;
  const std::string g = record::kSeriesHistogram;
  file.WriteDoubles(g + "/edges", edges, "1");
  file.WriteMatrix(g + "/counts", rows, rows.size() / bins, bins, "1");
  file.SetAttribute(g, "description",
                    "relative overlap u/(r_i + r_j) counts per output row and bin");
}

std::vector<double> ReadHistogramRows(const Hdf5File& file) {
  const std::string counts = std::string(record::kSeriesHistogram) + "/counts";
  if (!file.Exists(counts)) return {};
  size_t rows = 0, cols = 0;
  return file.ReadMatrix(counts, &rows, &cols);
}

std::string StageGroup(size_t index) { return fmt::format("{}/{:03d}", record::kStages, index); }

void AsymptoteRecord::SetWindow(const AsymptoteDetector::Result& result) {
  window_strain = result.window_strain;
  window_lnp = result.window_lnp;
  if (result.window_strain > 0) {
    mean_stress_kpa = result.mean_stress_kpa;
    void_ratio = result.void_ratio;
    psi_sigma_deg = result.psi_sigma / kDegree;
    psi_epsilon_deg = result.psi_epsilon / kDegree;
    q_over_p = result.q_over_p;
    p_min_kpa = result.p_min_kpa;
    p_max_kpa = result.p_max_kpa;
  }
  psi_change_deg = result.psi_change_deg;
  lnp_change = result.lnp_change;
  lnp_half_difference = result.lnp_half_difference;
  slope_change = result.slope_change;
  psi_epsilon_change_deg = result.psi_epsilon_change_deg;
  lnv_change = result.lnv_change;
  dlnp_dstrain = result.slope_lnp;
  dln1pe_dlnp = result.slope_lnv_lnp;
}

void WriteStageRecord(Hdf5File& file, const std::string& group, const StageRecord& stage,
                      const StageSpec* spec, int threads) {
  using namespace record;
  file.CreateGroup(group);
  file.SetAttribute(group, kStageName, stage.name);
  file.SetAttribute(group, kStageType, stage.type);
  file.SetAttribute(group, kStageFirstRow, stage.first_row);
  file.SetAttribute(group, kStageLastRow, stage.last_row);
  file.SetAttribute(group, kStageStopReason, stage.stop_reason);
  file.SetAttribute(group, kStageFailed, int64_t{stage.failed});
  const StageValidity& v = stage.validity;
  file.SetAttribute(group, kValidityMaxRelativeOverlap, v.max_relative_overlap);
  file.SetAttribute(group, kValidityMaxInertialNumberDmax, v.max_inertial_number_dmax);
  file.SetAttribute(group, kValidityMinMechanicalCoordination, v.min_mechanical_coordination);
  file.SetAttribute(group, kValidityFinalMeanStressKpa, v.final_mean_stress_kpa);
  file.SetAttribute(group, kValidityFlags, v.flags.empty() ? std::string() : v.FlagNames());
  if (stage.asymptote) {
    AsymptoteRecord a = *stage.asymptote;
    file.SetAttribute(group, kAsymptoteCriterion, stage.asymptote_criterion);
    file.SetAttribute(group, kAsymptoteDetected, int64_t{a.detected});
    file.SetAttribute(group, kAsymptotePathKind, std::string(ToString(a.path_kind)));
    file.SetAttribute(group, kAsymptoteStatus, std::string(ToString(a.status)));
    for (const auto& [name, value] : AsymptoteDoubles(a)) file.SetAttribute(group, name, *value);
    file.SetAttribute(group, kAsymptotePMinKpa, a.p_min_kpa);
    file.SetAttribute(group, kAsymptotePMaxKpa, a.p_max_kpa);
    file.SetAttribute(group, kAsymptoteFloorKpa, a.criterion.floor_kpa);
    file.SetAttribute(group, kAsymptoteBeforeEnd, int64_t{a.before_end});
  }
  if (spec) spec->Describe(file, group);
  if (stage.end_state) {
    WriteEngineState(file, Join(group, kStageEndState), *stage.end_state, threads);
  }
}

StageRecord ReadStageRecord(const Hdf5File& file, const std::string& group) {
  using namespace record;
  StageRecord stage;
  stage.name = file.ReadStringAttribute(group, kStageName);
  stage.type = file.ReadStringAttribute(group, kStageType);
  stage.first_row = file.ReadIntAttribute(group, kStageFirstRow);
  stage.last_row = file.ReadIntAttribute(group, kStageLastRow);
  stage.stop_reason = file.ReadStringAttribute(group, kStageStopReason);
  // Records written before the validity guards have none of these.
  if (file.HasAttribute(group, kStageFailed)) {
    stage.failed = file.ReadIntAttribute(group, kStageFailed) != 0;
    StageValidity& v = stage.validity;
    v.max_relative_overlap = file.ReadDoubleAttribute(group, kValidityMaxRelativeOverlap);
    v.max_inertial_number_dmax = file.ReadDoubleAttribute(group, kValidityMaxInertialNumberDmax);
    v.min_mechanical_coordination =
        file.ReadDoubleAttribute(group, kValidityMinMechanicalCoordination);
    v.final_mean_stress_kpa = file.ReadDoubleAttribute(group, kValidityFinalMeanStressKpa);
    v.flags = ParseNames<ValidityFlag>(file, group, kValidityFlags);
  }
  if (file.HasAttribute(group, kAsymptoteDetected)) {
    AsymptoteRecord a;
    stage.asymptote_criterion = file.ReadStringAttribute(group, kAsymptoteCriterion);
    a.detected = file.ReadIntAttribute(group, kAsymptoteDetected) != 0;
    if (file.HasAttribute(group, kAsymptoteStatus)) {
      a.path_kind = ReadEnum<PathKind>(file, group, kAsymptotePathKind);
      a.status = ReadEnum<AsymptoteStatus>(file, group, kAsymptoteStatus);
      a.criterion.kind = a.path_kind;
      for (const auto& [name, value] : AsymptoteDoubles(a)) {
        *value = file.ReadDoubleAttribute(group, name);
      }
      if (file.HasAttribute(group, kAsymptotePMinKpa)) {
        a.p_min_kpa = file.ReadDoubleAttribute(group, kAsymptotePMinKpa);
        a.p_max_kpa = file.ReadDoubleAttribute(group, kAsymptotePMaxKpa);
        a.criterion.floor_kpa = file.ReadDoubleAttribute(group, kAsymptoteFloorKpa);
        a.before_end = file.ReadIntAttribute(group, kAsymptoteBeforeEnd) != 0;
      }
    } else {
      // Written by the single-criterion detector: its state and measures.
      a.status = a.detected ? AsymptoteStatus::kDetected : AsymptoteStatus::kDrifting;
      a.psi_sigma_deg = file.ReadDoubleAttribute(group, kAsymptotePsiSigmaDeg);
      a.psi_change_deg = file.ReadDoubleAttribute(group, kAsymptotePsiChangeDeg);
      a.lnp_half_difference = file.ReadDoubleAttribute(group, kAsymptoteLnpHalfDifference);
      a.dlnp_dstrain = file.ReadDoubleAttribute(group, kAsymptoteDlnpDstrain);
      a.dln1pe_dlnp = file.ReadDoubleAttribute(group, kAsymptoteDln1peDlnp);
      a.mean_stress_kpa = file.ReadDoubleAttribute(group, kAsymptoteMeanStressKpa);
      a.void_ratio = file.ReadDoubleAttribute(group, kAsymptoteVoidRatio);
    }
    stage.asymptote = a;
  }
  const std::string end = Join(group, kStageEndState);
  if (file.Exists(end)) stage.end_state = ReadEngineState(file, end);
  return stage;
}

void WriteStageRecords(Hdf5File& file, const std::vector<StageRecord>& records,
                       const std::vector<Stage>& stages, int threads) {
  file.CreateGroup(record::kStages);
  for (size_t k = 0; k < records.size(); ++k) {
    const StageSpec* spec = k < stages.size() ? stages[k].spec.get() : nullptr;
    WriteStageRecord(file, StageGroup(k), records[k], spec, threads);
  }
}

std::vector<StageRecord> ReadStageRecords(const Hdf5File& file) {
  std::vector<StageRecord> records;
  if (!file.Exists(record::kStages)) return records;
  for (const std::string& name : file.List(record::kStages)) {
    records.push_back(ReadStageRecord(file, std::string(record::kStages) + "/" + name));
  }
  return records;
}

std::optional<int64_t> StageEndStep(const Hdf5File& file, const std::string& stage) {
  if (!file.Exists(record::kStages)) return std::nullopt;
  for (const std::string& name : file.List(record::kStages)) {
    const std::string group = std::string(record::kStages) + "/" + name;
    const std::string end = Join(group, record::kStageEndState);
    if (file.ReadStringAttribute(group, record::kStageName) == stage && file.Exists(end)) {
      return file.ReadIntAttribute(end, record::kStateStep);
    }
  }
  return std::nullopt;
}

void WriteSummary(Hdf5File& file, const RunSummary& summary, const ContactDurations& durations) {
  using namespace record;
  const std::string s = kSummary;
  file.CreateGroup(s);
  file.SetAttribute(s, kTermination, ToString(summary.termination));
  file.SetAttribute(s, kMessage, summary.message);
  file.SetAttribute(s, kValidity, summary.validity);
  file.SetAttribute(s, kReport, summary.OneLine());
  file.SetAttribute(s, kSteps, summary.steps);
  file.SetAttribute(s, kParticles, summary.particles);
  file.SetAttribute(s, kSimulatedTime, summary.simulated_time);
  file.SetAttribute(s, kWallSeconds, summary.wall_seconds);
  file.SetAttribute(s, kLoopSeconds, summary.loop_seconds);
  file.SetAttribute(s, kParticleStepsPerSecond, summary.particle_steps_per_second);
  file.SetAttribute(s, kNeighborBuilds, summary.neighbor_builds);
  file.SetAttribute(s, kThreads, static_cast<int64_t>(summary.threads));
  file.SetAttribute(s, kRows, summary.rows);
  file.SetAttribute(s, kStagesCompleted, summary.stages_completed);
  file.SetAttribute(s, kTimeStep, summary.time_step);
  file.SetAttribute(s, kTimeStepMin, summary.min_time_step);
  file.SetAttribute(s, kTimeStepMax, summary.max_time_step);
  file.SetAttribute(s, kTimeStepRule, summary.time_step_rule);
  file.SetAttribute(s, kStiffnessScaling, summary.stiffness_scaling);
  file.SetAttribute(s, kContactDurationMinReduced, durations.smallest_reduced_mass);
  file.SetAttribute(s, kContactDurationMaxReduced, durations.largest_reduced_mass);
  file.SetAttribute(s, kContactDurationMinSingle, durations.smallest_single_mass);
  file.SetAttribute(s, kContactDurationMaxSingle, durations.largest_single_mass);
  file.SetAttribute(s, kCriticalTimeStep, durations.critical_time_step);
  file.SetAttribute(s, kContactDurationDescription, durations.description);
  file.SetAttribute(s, kTimeStepOverContactDuration,
                    summary.time_step / durations.smallest_reduced_mass);
}

RunSummary ReadSummary(const Hdf5File& file) {
  using namespace record;
  const std::string s = kSummary;
  if (!file.HasAttribute(s, kTermination)) {
    throw InputError(file.path() + ": no " + s + " (expected a granasym DEM result file)");
  }
  RunSummary summary;
  const std::string termination = file.ReadStringAttribute(s, kTermination);
  const std::optional<Termination> known = FromString<Termination>(termination);
  if (!known) {
    throw InputError(fmt::format("{}: {} attribute {} = '{}' is not one of {}", file.path(), s,
                                 kTermination, termination, AllowedNames<Termination>()));
  }
  summary.termination = *known;
  summary.message = file.ReadStringAttribute(s, kMessage);
  if (file.HasAttribute(s, kValidity)) summary.validity = file.ReadStringAttribute(s, kValidity);
  summary.steps = file.ReadIntAttribute(s, kSteps);
  summary.particles = file.ReadIntAttribute(s, kParticles);
  summary.simulated_time = file.ReadDoubleAttribute(s, kSimulatedTime);
  summary.wall_seconds = file.ReadDoubleAttribute(s, kWallSeconds);
  summary.loop_seconds = file.ReadDoubleAttribute(s, kLoopSeconds);
  summary.particle_steps_per_second = file.ReadDoubleAttribute(s, kParticleStepsPerSecond);
  summary.neighbor_builds = file.ReadIntAttribute(s, kNeighborBuilds);
  summary.threads = static_cast<int>(file.ReadIntAttribute(s, kThreads));
  summary.rows = file.ReadIntAttribute(s, kRows);
  summary.stages_completed = file.ReadIntAttribute(s, kStagesCompleted);
  summary.time_step = file.ReadDoubleAttribute(s, kTimeStep);
  // Results of earlier versions: one fixed step, unscaled stiffness.
  summary.min_time_step = summary.max_time_step = summary.time_step;
  if (file.HasAttribute(s, kTimeStepMin)) {
    summary.min_time_step = file.ReadDoubleAttribute(s, kTimeStepMin);
    summary.max_time_step = file.ReadDoubleAttribute(s, kTimeStepMax);
    summary.time_step_rule = file.ReadStringAttribute(s, kTimeStepRule);
  }
  if (file.HasAttribute(s, kStiffnessScaling)) {
    summary.stiffness_scaling = file.ReadDoubleAttribute(s, kStiffnessScaling);
  }
  return summary;
}

void WriteRunner(Hdf5File& file, const RunnerRecord& runner) {
  const std::string r = record::kRunner;
  const StageClock& clock = runner.clock;
  file.CreateGroup(r);
  file.SetAttribute(r, "stage", runner.stage);
  file.SetAttribute(r, "stage_started", int64_t{runner.stage_started});
  file.SetAttribute(r, "stage_start_step", clock.start_step);
  file.SetAttribute(r, "stage_start_time", clock.start_time);
  file.SetAttribute(r, "stage_start_p", clock.start_p_kpa);
  file.SetAttribute(r, "stage_strain_norm", clock.strain_norm);
  file.SetAttribute(r, "next_sample_strain", clock.next_sample_strain);
  file.SetAttribute(r, "stage_first_row", clock.first_row);
  file.WriteDoubles(r + "/stage_start_cell", ToVector(clock.start_cell));
  file.SetAttribute(r, "strain_since_output", runner.strain_since_output);
  file.SetAttribute(r, "steps_since_output", runner.steps_since_output);
  file.WriteDoubles(r + "/controller_state", runner.controller_state);
  std::vector<double> samples;
  for (const auto& sample : runner.detector_samples) {
    samples.insert(samples.end(), {sample.strain, sample.psi_sigma, sample.log_p, sample.log_volume,
                                   sample.eps_a, sample.eps_r, sample.time});
  }
  file.WriteMatrix(r + "/detector_samples", samples, runner.detector_samples.size(), 7);
  if (runner.detector_held)
    file.WriteDoubles(r + "/detector_held", PackResult(*runner.detector_held));
  file.SetAttribute(r, "target_distance", clock.target_distance);
  file.SetAttribute(r, "target_distance_strain", clock.target_distance_strain);
  file.SetAttribute(r, "gas_since_strain", clock.gas_since_strain);
}

RunnerRecord ReadRunner(const Hdf5File& file) {
  const std::string r = record::kRunner;
  RunnerRecord runner;
  StageClock& clock = runner.clock;
  runner.stage = file.ReadIntAttribute(r, "stage");
  runner.stage_started = file.ReadIntAttribute(r, "stage_started") != 0;
  clock.start_step = file.ReadIntAttribute(r, "stage_start_step");
  clock.start_time = file.ReadDoubleAttribute(r, "stage_start_time");
  clock.start_p_kpa = file.ReadDoubleAttribute(r, "stage_start_p");
  clock.strain_norm = file.ReadDoubleAttribute(r, "stage_strain_norm");
  clock.next_sample_strain = file.ReadDoubleAttribute(r, "next_sample_strain");
  clock.first_row = file.ReadIntAttribute(r, "stage_first_row");
  clock.start_cell = ReadArray3(file, r + "/stage_start_cell");
  runner.strain_since_output = file.ReadDoubleAttribute(r, "strain_since_output");
  runner.steps_since_output = file.ReadIntAttribute(r, "steps_since_output");
  runner.controller_state = file.ReadDoubles(r + "/controller_state");
  size_t rows = 0, cols = 0;
  const std::vector<double> samples = file.ReadMatrix(r + "/detector_samples", &rows, &cols);
  if (rows > 0 && cols != 7) {
    throw InputError(
        fmt::format("{}: {}/detector_samples has {} columns, expected 7 (a checkpoint "
                    "of an older granasym cannot be continued)",
                    file.path(), r, cols));
  }
  for (size_t k = 0; k < rows; ++k) {
    const double* v = &samples[7 * k];
    runner.detector_samples.push_back({v[0], v[1], v[2], v[3], v[4], v[5], v[6]});
  }
  clock.target_distance = file.ReadDoubleAttribute(r, "target_distance");
  clock.target_distance_strain = file.ReadDoubleAttribute(r, "target_distance_strain");
  if (file.HasAttribute(r, "gas_since_strain"))
    clock.gas_since_strain = file.ReadDoubleAttribute(r, "gas_since_strain");
  if (file.Exists(r + "/detector_held")) {
    try {
      runner.detector_held = UnpackResult(file.ReadDoubles(r + "/detector_held"));
    } catch (const std::invalid_argument& e) {
      throw InputError(
          fmt::format("{}: {}/detector_held: {} (a checkpoint of another granasym "
                      "cannot be continued)",
                      file.path(), r, e.what()));
    }
  }
  return runner;
}

void WriteProvenance(Hdf5File& file, const Provenance& p) {
  using namespace record;
  const std::string g = kProvenance;
  file.CreateGroup(g);
  file.SetAttribute(g, kProgramVersion, p.program_version);
  file.SetAttribute(g, kSceneSha256, p.scene_sha256);
  file.WriteString(Join(g, kSceneCanonical), p.scene_canonical);
  file.SetAttribute(g, kStartKind, p.start_kind);
  file.SetAttribute(g, kStartSha256, p.start_sha256);
  file.SetAttribute(g, kParentFile, p.parent_file);
  file.SetAttribute(g, kParentStage, p.parent_stage);
  file.SetAttribute(g, kParentSceneSha256, p.parent_scene_sha256);
  file.SetAttribute(g, kThreads, p.threads);
  file.SetAttribute(g, kCpuModel, p.cpu_model);
  if (!p.case_key.empty()) file.SetAttribute(g, kCaseKey, p.case_key);
}

Provenance ReadProvenance(const Hdf5File& file) {
  using namespace record;
  const std::string g = kProvenance;
  if (!file.HasAttribute(g, kSceneSha256)) {
    throw InputError(file.path() + ": no " + g + " (written by granasym since the run layer)");
  }
  Provenance p;
  p.program_version = file.ReadStringAttribute(g, kProgramVersion);
  p.scene_sha256 = file.ReadStringAttribute(g, kSceneSha256);
  p.scene_canonical = file.ReadString(Join(g, kSceneCanonical));
  p.start_kind = file.ReadStringAttribute(g, kStartKind);
  p.start_sha256 = file.ReadStringAttribute(g, kStartSha256);
  p.parent_file = file.ReadStringAttribute(g, kParentFile);
  p.parent_stage = file.ReadStringAttribute(g, kParentStage);
  p.parent_scene_sha256 = file.ReadStringAttribute(g, kParentSceneSha256);
  p.threads = file.ReadIntAttribute(g, kThreads);
  p.cpu_model = file.ReadStringAttribute(g, kCpuModel);
  if (file.HasAttribute(g, kCaseKey)) p.case_key = file.ReadStringAttribute(g, kCaseKey);
  return p;
}

std::string StageRateLabel(const Hdf5File& file, size_t index) {
  using namespace record;
  const std::string group = StageGroup(index);
  if (!file.HasAttribute(group, kStageStretchingRate)) return {};
  const bool inertial =
      file.HasAttribute(group, kStageRateRule) &&
      file.ReadStringAttribute(group, kStageRateRule) == ToString(RateRule::kInertial);
  return inertial
             ? fmt::format("I* = {:g}", file.ReadDoubleAttribute(group, kStageRateInertialNumber))
             : fmt::format("‖D‖ = {:g} 1/s", file.ReadDoubleAttribute(group, kStageStretchingRate));
}

Material ReadMaterial(const Hdf5File& file) {
  // The canonical scene is "key = value" lines in TOML's notation; the
  // material's keys are ParseMaterial's, prefixed "material.".
  const std::string canonical = ReadProvenance(file).scene_canonical;
  const std::string prefix = "material.";
  std::string text = "[material]\n";
  size_t at = 0;
  while (at < canonical.size()) {
    size_t end = canonical.find('\n', at);
    if (end == std::string::npos) end = canonical.size();
    if (canonical.compare(at, prefix.size(), prefix) == 0) {
      text += canonical.substr(at + prefix.size(), end - at - prefix.size()) + "\n";
    }
    at = end + 1;
  }
  const ConfigTable root =
      ConfigTable::ParseString(text, file.path() + ": the canonical scene of /provenance");
  return ParseMaterial(root.GetTable("material"));
}

namespace {

std::string StringAttributeOr(const Hdf5File& file, const std::string& object, const char* name,
                              const std::string& fallback) {
  return file.HasAttribute(object, name) ? file.ReadStringAttribute(object, name) : fallback;
}

}  // namespace

std::string PartialResultNote(const Hdf5File& file) {
  const RunSummary summary = ReadSummary(file);
  const std::string scene =
      StringAttributeOr(file, record::kScene, record::kSceneOrigin, "SCENE.toml");
  switch (summary.termination) {
    case Termination::kCompleted:
      return "";
    case Termination::kInterrupted:
      return fmt::format(
          "'{}' is a partial result (the run was interrupted or is still running: {}); its "
          "series and stages end at its last checkpoint. Continue it with `granasym dem run {} "
          "--out {} --restart`{}",
          file.path(), summary.message, scene, file.path(),
          std::filesystem::exists(file.path() + ".ckpt") ? "" : " (its checkpoint is missing)");
    case Termination::kFailed:
      return fmt::format(
          "'{}' is the result of a failed run ({}): the series ends where the run failed and "
          "the stage it failed in is marked failed",
          file.path(), summary.message);
    case Termination::kNotRun:
      break;
  }
  return fmt::format("'{}' is not a result: the run has not started", file.path());
}

std::string DescribeResult(const Hdf5File& file) {
  using namespace record;
  const RunSummary summary = ReadSummary(file);
  std::string text;
  const auto line = [&text](const std::string& key, const std::string& value) {
    text += key + ": " + value + "\n";
  };
  line("file", file.path());
  if (file.Exists(kProvenance)) {
    const Provenance p = ReadProvenance(file);
    line("program_version", p.program_version);
    line("scene", StringAttributeOr(file, kScene, kSceneOrigin, "?"));
    line("scene_sha256", p.scene_sha256);
    std::string start = p.start_kind;
    if (!p.parent_file.empty()) {
      start += " from '" + p.parent_file + "'" +
               (p.parent_stage.empty() ? " (final state)" : " stage '" + p.parent_stage + "'");
    }
    line("start", start);
    line("cpu", p.cpu_model);
    if (!p.case_key.empty()) line("case_key", p.case_key);
  } else {
    line("scene", StringAttributeOr(file, kScene, kSceneOrigin, "?"));
  }
  line("termination", std::string(ToString(summary.termination)));
  line("message", summary.message);
  line("final",
       summary.termination == Termination::kCompleted ? "yes" : "no: " + PartialResultNote(file));
  const std::string checkpoint = file.path() + ".ckpt";
  line("checkpoint", std::filesystem::exists(checkpoint) ? checkpoint : "none");
  line("particles", std::to_string(summary.particles));
  line("steps", std::to_string(summary.steps));
  line("rows", std::to_string(summary.rows));
  line("stages_completed", std::to_string(summary.stages_completed));
  line("simulated_time_s", fmt::format("{:.6g}", summary.simulated_time));
  line("time_step_s", fmt::format("{:.6g}", summary.time_step));
  if (summary.min_time_step != summary.max_time_step) {
    line("time_step_range_s",
         fmt::format("{:.6g} .. {:.6g}", summary.min_time_step, summary.max_time_step));
  }
  line("time_step_rule", summary.time_step_rule);
  line("stiffness_scaling", fmt::format("{:g}", summary.stiffness_scaling));
  line("wall_s", fmt::format("{:.1f}", summary.wall_seconds));
  // The time-stepping loop alone (this invocation), as benchmarks read it.
  line("loop_wall_s", fmt::format("{:.6g}", summary.loop_seconds));
  if (summary.particle_steps_per_second > 0) {
    line("us_per_particle_step", fmt::format("{:.6g}", 1e6 / summary.particle_steps_per_second));
  }
  line("neighbor_builds", std::to_string(summary.neighbor_builds));
  line("threads", std::to_string(summary.threads));
  line("validity", summary.validity.empty() ? "no flags" : summary.validity);
  if (file.Exists(kStages)) {
    // The records' attributes only: their end states are not read.
    for (const std::string& name : file.List(kStages)) {
      const std::string group = std::string(kStages) + "/" + name;
      std::string stage = fmt::format(
          "'{}' ({}), rows {}..{}{}, stop: {}", file.ReadStringAttribute(group, kStageName),
          file.ReadStringAttribute(group, kStageType), file.ReadIntAttribute(group, kStageFirstRow),
          file.ReadIntAttribute(group, kStageLastRow),
          file.HasAttribute(group, kStageFailed) && file.ReadIntAttribute(group, kStageFailed) != 0
              ? ", failed"
              : "",
          file.ReadStringAttribute(group, kStageStopReason));
      if (file.HasAttribute(group, kAsymptoteStatus)) {
        stage +=
            fmt::format("; asymptote: {} {}", file.ReadStringAttribute(group, kAsymptotePathKind),
                        file.ReadStringAttribute(group, kAsymptoteStatus));
      } else if (file.HasAttribute(group, kAsymptoteDetected)) {
        stage += file.ReadIntAttribute(group, kAsymptoteDetected) != 0
                     ? "; asymptote: detected"
                     : "; asymptote: not detected";
      }
      const std::string flags = StringAttributeOr(file, group, kValidityFlags, "");
      if (!flags.empty()) stage += "; validity: " + flags;
      line("stage " + name, stage);
    }
  }
  return text;
}

}  // namespace granasym::dem
