#include "dem/strain_path_stage.h"

#include "common/canonical_text.h"
#include "common/config.h"
#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "dem/run_record_names.h"

namespace granasym::dem {
namespace {

class StrainPathController final : public StageController {
 public:
  explicit StrainPathController(const StrainPathStage& spec) : spec_(spec) {}
  std::array<double, 3> Start() override {
    const AxisymmetricRate rate =
        AxisymmetricRate::FromAngle(spec_.psi_epsilon(), spec_.stretching_rate);
    return {-rate.axial, -rate.radial, -rate.radial};
  }
  bool NeedsStress(int64_t) const override { return false; }
  bool NeedsStiffness() const override { return false; }
  std::optional<std::array<double, 3>> Control(const Engine::Sums&, double) override {
    return std::nullopt;
  }

 private:
  const StrainPathStage& spec_;
};

}  // namespace

std::shared_ptr<const StageSpec> StrainPathStage::Parse(const ConfigTable& table) {
  auto stage = std::make_shared<StrainPathStage>();
  stage->psi_epsilon_deg = table.GetDouble("psi_epsilon_deg", Range::Closed(-180, 180));
  stage->stretching_rate = table.GetDouble("stretching_rate", kStrainRate);
  return stage;
}

double StrainPathStage::psi_epsilon() const { return psi_epsilon_deg * kDegree; }

std::unique_ptr<StageController> StrainPathStage::MakeController() const {
  return std::make_unique<StrainPathController>(*this);
}

void StrainPathStage::Canonical(CanonicalText& text, const std::string& prefix) const {
  text.Add(prefix + "psi_epsilon_deg", psi_epsilon_deg);
  text.Add(prefix + "stretching_rate", stretching_rate);
}

void StrainPathStage::Describe(Hdf5File& file, const std::string& group) const {
  file.SetAttribute(group, record::kStagePsiEpsilonDeg, psi_epsilon_deg);
  file.SetAttribute(group, record::kStageStretchingRate, stretching_rate);
}

bool StrainPathStage::ContinuesPath(const StageSpec& previous) const {
  const auto* path = dynamic_cast<const StrainPathStage*>(&previous);
  return path && path->psi_epsilon_deg == psi_epsilon_deg &&
         path->stretching_rate == stretching_rate;
}

}  // namespace granasym::dem
