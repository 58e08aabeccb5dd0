#include "dem/stage_types.h"

#include <iterator>
#include <memory>
#include <vector>

#include "common/config.h"
#include "common/error.h"
#include "dem/rest_stage.h"
#include "dem/strain_path_stage.h"
#include "dem/triaxial_stage.h"

namespace granasym::dem {
namespace {

// The stage types: the spelling of `type` and the parser of its keys. A new
// loading mode adds its line here.
struct StageTypeEntry {
  const char* name;
  std::shared_ptr<const StageSpec> (*parse)(const ConfigTable& table);
};
constexpr StageTypeEntry kStageTypes[] = {
    {"strain_path", &StrainPathStage::Parse},
    {"triaxial", &TriaxialStage::Parse},
    {"rest", &RestStage::Parse},
};

}  // namespace

std::string StageTypeNames() {
  std::string names;
  const size_t count = std::size(kStageTypes);
  for (size_t k = 0; k < count; ++k) {
    names += k == 0 ? "" : (k + 1 == count ? " or " : ", ");
    names += kStageTypes[k].name;
  }
  return names;
}

Stage ParseStage(const ConfigTable& table, size_t index) {
  Stage stage;
  stage.name = table.GetString("name", "stage" + std::to_string(index + 1));
  std::vector<std::string> types;
  for (const StageTypeEntry& entry : kStageTypes) types.push_back(entry.name);
  const std::string type = table.GetChoice("type", types, "strain_path");
  for (const StageTypeEntry& entry : kStageTypes) {
    if (type == entry.name) stage.spec = entry.parse(table);
  }
  GRANASYM_CHECK(stage.spec) << "no parser for stage type " << type;
  const std::optional<PathKind> kind = stage.spec->path_kind();
  if (kind) stage.asymptote = AsymptoteCriterion::For(*kind);
  if (table.Has("asymptote")) {
    if (!kind) {
      table.Fail("asymptote", "is given, but " + type + " stages have no asymptote detector");
    }
    stage.asymptote = AsymptoteCriterion::Parse(table.GetTable("asymptote"), *kind);
    stage.detect_asymptote = true;
  }
  if (!table.Has("stop")) {
    table.Fail("stop",
               "is missing: every stage needs a [stage.stop] table with at least one of "
               "mean_stress_kpa, axial_strain, volumetric_strain, shear_strain, "
               "strain_norm, time_s, steps, asymptote (rest stages stop at equilibrium)");
  }
  const ConfigTable stop = table.GetTable("stop");
  stage.stop = StopConditions::Parse(stop);
  if (stage.stop.asymptote) {
    if (!kind) stop.Fail("asymptote", "= true, but " + type + " stages have no asymptote detector");
    stage.detect_asymptote = true;
  }
  if (stage.stop.liquefied) {
    if (!kind) stop.Fail("liquefied", "= true, but " + type + " stages have no asymptote detector");
    if (!stage.stop.any()) {
      stop.Fail("liquefied",
                "= true is not enough to end a stage (the sample may never liquefy): add "
                "strain_norm, time_s, steps or asymptote");
    }
    stage.detect_asymptote = true;  // its record then says "gas"
  }
  if (!stage.stop.any() && !stage.spec->StopsByItself()) {
    stop.Fail("",
              "has no stop condition: give at least one of mean_stress_kpa, axial_strain, "
              "volumetric_strain, shear_strain, strain_norm, time_s, steps, asymptote");
  }
  return stage;
}

}  // namespace granasym::dem
