// The scene and stage key tables against the scene parser: every key of the
// tables is read by some scene, every key a scene may hold is in them (the
// parser's reads consult the tables: common/key_table.h), and a made-up key
// is refused naming it and the valid keys.
#include "dem/scene_keys.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/error.h"
#include "dem/scene.h"
#include "dem/strain_path_stage.h"
#include "dem/triaxial_stage.h"

namespace granasym::dem {
namespace {

// Every key, with a value other than its default where it has one.
constexpr const char* kGeneratedScene = R"(
[sample.generate]
count = 100
cell_size_mm = 3.0
seed = 2
max_attempts = 5000
gsd = "gsd.csv"

[material]
contact_law = "linear"
youngs_modulus_mpa = 400.0
stiffness_ratio = 0.25
friction_angle_rad = 0.4
rolling_friction = 0.1
density_kg_m3 = 2600.0
local_damping = 0.4
stiffness_scaling = 0.5

[numerics]
time_step_fraction = 0.05
time_step_check_interval = 50
max_time_step_s = 1e-6
skin_fraction = 0.2
threads = 2

[output]
interval_strain = 0.002
interval_steps = 100
overlap_histogram = true
histogram_bins = 20
histogram_min = 1e-5
histogram_max = 0.05
checkpoint_interval_s = 300
progress_interval_s = 5
stage_states = false

[[stage]]
name = "ncl"
type = "strain_path"
psi_epsilon_deg = 0.0
stretching_rate = 100.0
[stage.rate]
rule = "inertial"
inertial_number = 1e-3
diameter = "d_50"
min_mean_stress_kpa = 2.0
check_interval = 20
[stage.asymptote]
sample_strain = 1e-3
window_strain = 0.4
psi_tolerance_deg = 1.5
window_lnp = 0.8
slope_tolerance = 0.2
transient_strain = 0.05
[stage.stop]
mean_stress_kpa = 500.0
direction = "rising"
asymptote = true

[[stage]]
name = "isochoric"
psi_epsilon_deg = 90.0
stretching_rate = 100.0
[stage.asymptote]
lnp_tolerance = 0.1
[stage.stop]
shear_strain = 0.3
strain_norm = 0.5
liquefied = true
liquefied_strain = 0.05

[[stage]]
name = "extension"
psi_epsilon_deg = 120.0
stretching_rate = 100.0
[stage.asymptote]
window_lnp = 0.5
transient_strain = 0.1
lnp_tolerance = 0.3
floor_kpa = 1.0
[stage.stop]
axial_strain = -0.2
volumetric_strain = -0.1
time_s = 0.01
steps = 100000

[[stage]]
name = "triaxial"
type = "triaxial"
axial_strain_rate = 50.0
radial_stress_kpa = 100.0
[stage.control]
gain = 0.3
integral_gain = 0.02
max_rate_factor = 3.0
[stage.asymptote]
psi_epsilon_tolerance_deg = 2.0
lnv_tolerance = 0.003
[stage.stop]
axial_strain = 0.3

[[stage]]
name = "rest"
type = "rest"
mean_stress_kpa = 100.0
max_strain_rate = 5.0
[stage.control]
check_interval = 40
[stage.stop]
stress_tolerance = 0.02
unbalanced_force = 2e-3
)";

constexpr const char* kPackingScene = R"(
[sample]
packing = "packing.txt"
[material]
contact_law = "hertz_mindlin"
poissons_ratio = 0.2
[numerics]
time_step_s = 1e-7
[[stage]]
psi_epsilon_deg = 0.0
stretching_rate = 10.0
[stage.stop]
steps = 10
)";

constexpr const char* kStateScene = R"(
[sample]
state = "parent.h5"
stage = "ncl"
[[stage]]
psi_epsilon_deg = 90.0
stretching_rate = 10.0
[stage.stop]
shear_strain = 0.1
)";

TEST(SceneKeys, EveryKeyOfTheTablesIsReadAndTheGivenValuesArrive) {
  SceneKeys().ResetConsulted();
  StageKeys().ResetConsulted();
  const Scene scene = Scene::Parse(kGeneratedScene, "all.toml", "/base");
  ASSERT_TRUE(scene.generate);
  EXPECT_EQ(scene.generate->count, 100u);
  EXPECT_EQ(scene.generate->max_attempts, 5000);
  EXPECT_EQ(scene.gsd_path, "/base/gsd.csv");
  EXPECT_DOUBLE_EQ(scene.material.youngs_modulus, 400e6);
  EXPECT_DOUBLE_EQ(scene.material.stiffness_scaling, 0.5);
  EXPECT_DOUBLE_EQ(scene.adaptive_time_step.fraction, 0.05);
  EXPECT_EQ(scene.output.histogram_bins, 20);
  EXPECT_FALSE(scene.output.stage_states);
  ASSERT_EQ(scene.stages.size(), 5u);
  EXPECT_EQ(scene.stages[0].As<StrainPathStage>()->inertial.check_interval, 20);
  EXPECT_DOUBLE_EQ(scene.stages[0].asymptote.window_strain, 0.4);
  EXPECT_DOUBLE_EQ(scene.stages[2].asymptote.floor_kpa, 1.0);
  EXPECT_DOUBLE_EQ(scene.stages[3].As<TriaxialStage>()->control.gain, 0.3);
  EXPECT_DOUBLE_EQ(*scene.stages[1].stop.liquefied_strain, 0.05);
  const Scene packing = Scene::Parse(kPackingScene, "packing.toml", "/base");
  EXPECT_DOUBLE_EQ(packing.material.poissons_ratio, 0.2);
  EXPECT_DOUBLE_EQ(*packing.time_step_s, 1e-7);
  const Scene state = Scene::Parse(kStateScene, "state.toml", "/base");
  ASSERT_TRUE(state.parent);
  EXPECT_EQ(state.parent->stage, "ncl");
  for (const KeyTable* table : {&SceneKeys(), &StageKeys()}) {
    const std::vector<std::string> unread = table->Unconsulted();
    EXPECT_TRUE(unread.empty()) << table->kind() << " key never read: " << unread.front();
  }
}

void ExpectRefused(const std::string& text, const std::string& key, const std::string& valid) {
  try {
    Scene::Parse(text, "made_up.toml", "");
    FAIL() << "accepted " << key;
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("made_up.toml: key '" + key + "' is not a known key"), std::string::npos)
        << message;
    EXPECT_NE(message.find(valid), std::string::npos) << message;
  }
}

TEST(SceneKeys, AMadeUpKeyIsRefusedNamingItAndTheValidKeys) {
  const std::string stage =
      "[[stage]]\npsi_epsilon_deg = 0.0\nstretching_rate = 10.0\n[stage.stop]\nsteps = 10\n";
  ExpectRefused("[sample]\npacking = 'p.txt'\n[material]\nyoungs_modulus = 5.0\n" + stage,
                "material.youngs_modulus", "youngs_modulus_mpa");
  ExpectRefused("[sample]\npacking = 'p.txt'\n" + stage + "stresss_kpa = 3.0\n",
                "stage[0].stop.stresss_kpa", "mean_stress_kpa");
}

TEST(SceneKeys, TheTablesNameUnitsRangesAndDefaults) {
  const std::string text = SceneKeys().Render(KeyFormat::kText);
  EXPECT_NE(text.find("  youngs_modulus_mpa: number (MPa), in [0.001, 10000000]; default 500\n"),
            std::string::npos)
      << text;
  const std::string stage = StageKeys().Render(KeyFormat::kMarkdown);
  EXPECT_NE(stage.find("| `psi_epsilon_deg` | number | deg | in [-180, 180] | required |"),
            std::string::npos)
      << stage;
}

}  // namespace
}  // namespace granasym::dem
