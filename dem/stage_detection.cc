#include "dem/stage_detection.h"

#include <cmath>
#include <limits>
#include <utility>

#include "common/state_measures.h"

namespace granasym::dem {
namespace {

// The first output row of the detector's samples in stage `index`: the
// stage's own (`first_row`), or that of the first stage of a chain that
// continues one path.
int64_t SamplesFirstRow(const std::vector<Stage>& stages, int64_t index,
                        const std::vector<StageRecord>& records, int64_t first_row) {
  const size_t current = static_cast<size_t>(index);
  size_t k = current;
  while (k > 0 && k <= records.size() && stages[k].ContinuesDetection(stages[k - 1])) --k;
  return k < current && k < records.size() ? records[k].first_row : first_row;
}

}  // namespace

void StageDetection::Start(const std::vector<Stage>& stages, int64_t index,
                           const std::vector<StageRecord>& records, int64_t first_row,
                           double previous_strain) {
  std::vector<AsymptoteDetector::Sample> carried;
  if (index > 0 && stages[index].ContinuesDetection(stages[index - 1])) {
    carried = detector_.samples();
    for (AsymptoteDetector::Sample& sample : carried) sample.strain -= previous_strain;
  }
  Restore(stages, index, records, first_row, std::move(carried));
}

void StageDetection::Restore(const std::vector<Stage>& stages, int64_t index,
                             const std::vector<StageRecord>& records, int64_t first_row,
                             std::vector<AsymptoteDetector::Sample> samples,
                             std::optional<AsymptoteDetector::Result> held) {
  detector_ = AsymptoteDetector(stages[index].asymptote);
  detector_.set_samples(std::move(samples));
  detector_.set_last_held(std::move(held));
  first_row_ = SamplesFirstRow(stages, index, records, first_row);
}

void StageDetection::AddSample(const Engine& engine, const std::array<double, 3>& reference_cell,
                               double strain) {
  const AxisymmetricStress stress = AxisymmetricFromTensor(engine.sums().stress);
  const double p_kpa = stress.mean() / kKiloPascal;
  const auto& cell = engine.cell();
  const auto& reference = reference_cell;
  detector_.Add({strain, stress.psi(),
                 p_kpa > 0 ? std::log(p_kpa) : std::numeric_limits<double>::quiet_NaN(),
                 std::log1p(engine.void_ratio()), -std::log(cell[0] / reference[0]),
                 -0.5 * (std::log(cell[1] / reference[1]) + std::log(cell[2] / reference[2])),
                 engine.time()});
  detector_.Track();
}

}  // namespace granasym::dem
