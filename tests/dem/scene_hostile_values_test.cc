// Every numeric key of a scene against the values a hostile or careless user
// writes: NaN, ±inf, 0, a negative number, 1e308 and 1e-300. Each (key,
// value) pair is either rejected with a message that names the key and the
// value, or listed here as valid for that key and then accepted.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/error.h"
#include "dem/scene.h"
#include "tests/common/hostile_values.h"

namespace granasym::dem {
namespace {

// A scene with one stage of each type; `{KEY}` marks are where a test puts
// its value (every other mark keeps its valid default).
struct Key {
  std::string name;                // dotted name as messages spell it
  std::string mark;                // placeholder in the template
  std::string valid;               // the valid value the template holds otherwise
  std::set<std::string> accepted;  // hostile values that are valid settings
};

const char* kTemplate = R"(
[sample.generate]
count = {count}
cell_size_mm = {cell}
seed = {seed}
max_attempts = {attempts}
[material]
youngs_modulus_mpa = {E}
stiffness_ratio = {kr}
friction_angle_rad = {phi}
rolling_friction = {roll}
density_kg_m3 = {rho}
local_damping = {damp}
stiffness_scaling = {stiff}
[numerics]
time_step_fraction = {dtf}
time_step_check_interval = {dtcheck}
max_time_step_s = {dtmax}
skin_fraction = {skin}
threads = {threads}
[output]
interval_strain = {dstrain}
interval_steps = {dsteps}
overlap_histogram = true
histogram_bins = {bins}
histogram_min = {hmin}
histogram_max = {hmax}
checkpoint_interval_s = {ckpt}
progress_interval_s = {progress}
[[stage]]
name = "ncl"
type = "strain_path"
psi_epsilon_deg = {psi}
stretching_rate = {rate}
[stage.asymptote]
sample_strain = {sample}
window_strain = {window}
psi_tolerance_deg = {psitol}
window_lnp = {wlnp}
slope_tolerance = {slope}
[stage.stop]
mean_stress_kpa = {p}
axial_strain = {ea}
volumetric_strain = {ev}
shear_strain = {es}
strain_norm = {norm}
time_s = {time}
steps = {steps}
[[stage]]
name = "shear"
type = "strain_path"
psi_epsilon_deg = 90.0
stretching_rate = 167.0
[stage.asymptote]
lnp_tolerance = {lnptol}
[stage.stop]
asymptote = true
[[stage]]
name = "triaxial"
type = "triaxial"
axial_strain_rate = {ear}
radial_stress_kpa = {sr}
[stage.control]
gain = {gain}
integral_gain = {igain}
max_rate_factor = {factor}
[stage.asymptote]
psi_epsilon_tolerance_deg = {psietol}
lnv_tolerance = {lnvtol}
[stage.stop]
axial_strain = 0.2
[[stage]]
name = "rest"
type = "rest"
mean_stress_kpa = {prest}
max_strain_rate = {maxrate}
[stage.control]
check_interval = {check}
[stage.stop]
stress_tolerance = {stol}
unbalanced_force = {unbal}
)";

const std::vector<Key>& Keys() {
  static const std::vector<Key> keys = {
      {"sample.generate.count", "count", "1000", {}},
      {"sample.generate.cell_size_mm", "cell", "5.8", {}},
      {"sample.generate.seed", "seed", "1", {"0"}},
      {"sample.generate.max_attempts", "attempts", "1000", {}},
      {"material.youngs_modulus_mpa", "E", "500.0", {}},
      {"material.stiffness_ratio", "kr", "0.3", {"0"}},
      {"material.friction_angle_rad", "phi", "0.5", {"0"}},
      {"material.rolling_friction", "roll", "0.0", {"0"}},
      {"material.density_kg_m3", "rho", "2650.0", {}},
      {"material.local_damping", "damp", "0.5", {"0"}},
      {"material.stiffness_scaling", "stiff", "0.5", {}},
      {"numerics.time_step_fraction", "dtf", "0.2", {}},
      {"numerics.time_step_check_interval", "dtcheck", "100", {}},
      {"numerics.max_time_step_s", "dtmax", "1e-7", {}},
      {"numerics.skin_fraction", "skin", "0.3", {}},
      {"numerics.threads", "threads", "1", {}},
      {"output.interval_strain", "dstrain", "0.002", {}},
      {"output.interval_steps", "dsteps", "0", {"0"}},
      {"output.histogram_bins", "bins", "20", {}},
      {"output.histogram_min", "hmin", "0.0001", {}},
      {"output.histogram_max", "hmax", "0.1", {}},
      {"output.checkpoint_interval_s", "ckpt", "600.0", {}},
      {"output.progress_interval_s", "progress", "10.0", {}},
      {"stage[0].psi_epsilon_deg", "psi", "0.0", {"0", "-1"}},
      {"stage[0].stretching_rate", "rate", "167.0", {}},
      {"stage[0].asymptote.sample_strain", "sample", "0.01", {}},
      {"stage[0].asymptote.window_strain", "window", "0.5", {}},
      {"stage[0].asymptote.psi_tolerance_deg", "psitol", "0.5", {}},
      {"stage[0].asymptote.window_lnp", "wlnp", "1.0", {}},
      {"stage[0].asymptote.slope_tolerance", "slope", "0.2", {}},
      {"stage[0].stop.mean_stress_kpa", "p", "100.0", {}},
      {"stage[0].stop.axial_strain", "ea", "0.5", {"0", "-1"}},
      {"stage[0].stop.volumetric_strain", "ev", "0.5", {"0", "-1"}},
      {"stage[0].stop.shear_strain", "es", "0.5", {"0", "-1"}},
      {"stage[0].stop.strain_norm", "norm", "1.0", {}},
      {"stage[0].stop.time_s", "time", "1.0", {}},
      {"stage[0].stop.steps", "steps", "100000", {}},
      {"stage[1].asymptote.lnp_tolerance", "lnptol", "0.02", {}},
      {"stage[2].axial_strain_rate", "ear", "136.355", {"-1"}},
      {"stage[2].radial_stress_kpa", "sr", "100.0", {}},
      {"stage[2].control.gain", "gain", "0.2", {}},
      {"stage[2].control.integral_gain", "igain", "0.01", {"0"}},
      {"stage[2].control.max_rate_factor", "factor", "2.0", {}},
      {"stage[2].asymptote.psi_epsilon_tolerance_deg", "psietol", "1.0", {}},
      {"stage[2].asymptote.lnv_tolerance", "lnvtol", "0.002", {}},
      {"stage[3].mean_stress_kpa", "prest", "100.0", {}},
      {"stage[3].max_strain_rate", "maxrate", "10.0", {}},
      {"stage[3].control.check_interval", "check", "100", {}},
      {"stage[3].stop.stress_tolerance", "stol", "0.01", {}},
      {"stage[3].stop.unbalanced_force", "unbal", "0.001", {}},
  };
  return keys;
}

std::string SceneWith(const Key& target, const std::string& value) {
  std::string text = kTemplate;
  for (const Key& key : Keys()) {
    const std::string mark = "{" + key.mark + "}";
    const size_t at = text.find(mark);
    EXPECT_NE(at, std::string::npos) << mark;
    text.replace(at, mark.size(), &key == &target ? value : key.valid);
  }
  return text;
}

TEST(SceneHostileValues, TheTemplateIsValid) {
  const std::string text = SceneWith(Keys().front(), Keys().front().valid);
  EXPECT_NO_THROW(Scene::Parse(text, "hostile.toml", "")) << text;
}

TEST(SceneHostileValues, EveryNumericKeyRejectsOrAcceptsEachValueAsListed) {
  int cases = 0, rejected = 0;
  for (const Key& key : Keys()) {
    for (const auto& [literal, spelling] : granasym::testing::HostileNumbers()) {
      ++cases;
      const std::string text = SceneWith(key, literal);
      const bool valid = key.accepted.count(literal) > 0;
      std::string message;
      try {
        Scene::Parse(text, "hostile.toml", "");
      } catch (const InputError& error) {
        message = error.what();
      } catch (const std::exception& error) {
        ADD_FAILURE() << key.name << " = " << literal << ": not an input error: " << error.what();
        continue;
      }
      rejected += valid ? 0 : 1;
      granasym::testing::ExpectOutcome(key.name + " = " + literal, valid, message, "hostile.toml",
                                       "'" + key.name + "'", spelling);
    }
  }
  // 50 keys x 7 values; the count is part of the issue's closing note.
  EXPECT_EQ(cases, 350);
  EXPECT_GT(rejected, 300);
}

TEST(SceneHostileValues, HistogramBoundsNameTheKeyThatIsWrong) {
  const Key* min_key = nullptr;
  for (const Key& key : Keys()) {
    if (key.mark == "hmin") min_key = &key;
  }
  ASSERT_NE(min_key, nullptr);
  try {
    Scene::Parse(SceneWith(*min_key, "0.5"), "hostile.toml", "");
    ADD_FAILURE() << "histogram_min above histogram_max was accepted";
  } catch (const InputError& error) {
    // histogram_max = 0.1 is valid by itself: the message names both.
    EXPECT_NE(std::string(error.what()).find("histogram_min = 0.5"), std::string::npos)
        << error.what();
  }
}

// What a scene implies, checked before the first step.
std::string FeasibilityError(const std::string& stage_keys, double time_step) {
  const std::string text = "[sample.generate]\ncount = 100\n[[stage]]\nname = \"s\"\n" + stage_keys;
  try {
    Scene::Parse(text, "costly.toml", "").CheckFeasible(time_step);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(SceneFeasibility, ARateThatNeverMovesTheCellIsRejectedBeforeTheFirstStep) {
  const std::string message = FeasibilityError(
      "psi_epsilon_deg = 0.0\nstretching_rate = 1e-9\n[stage.stop]\nmean_stress_kpa = 100.0\n",
      1e-7);
  EXPECT_NE(message.find("'stage[0].stretching_rate' = 1e-09"), std::string::npos) << message;
  EXPECT_NE(message.find("per unit strain"), std::string::npos) << message;
}

TEST(SceneFeasibility, StopsThatNeedTooManyStepsAreRejectedWithTheEstimate) {
  // 1e6 s at 1e-7 s per step: 1e13 steps.
  std::string message = FeasibilityError(
      "psi_epsilon_deg = 0.0\nstretching_rate = 1e-3\n[stage.stop]\ntime_s = 1e6\n", 1e-7);
  EXPECT_NE(message.find("'stage[0].stop.time_s' needs at least 1e+13 steps"), std::string::npos)
      << message;
  // A strain of 20 at 1e-3 1/s: at least 20 / (sqrt(3) 1e-10) = 1.2e11 steps:
  // below the limit, accepted; with a second stop that is nearer, too.
  EXPECT_EQ(FeasibilityError("psi_epsilon_deg = 0.0\nstretching_rate = 1e-3\n[stage.stop]\n"
                             "axial_strain = 20.0\n",
                             1e-7),
            "");
  // A mean-stress stop may come at any step: only the rate floor applies.
  EXPECT_EQ(FeasibilityError("psi_epsilon_deg = 0.0\nstretching_rate = 1e-3\n[stage.stop]\n"
                             "mean_stress_kpa = 100.0\ntime_s = 1e6\n",
                             1e-7),
            "");
  // The triaxial and rest stages bound their rates through their own keys.
  message = FeasibilityError(
      "type = \"triaxial\"\naxial_strain_rate = 1e-8\nradial_stress_kpa = 100.0\n"
      "[stage.stop]\naxial_strain = 0.1\n",
      1e-7);
  EXPECT_NE(message.find("'stage[0].axial_strain_rate'"), std::string::npos) << message;
}

TEST(SceneFeasibility, TheStudiesOwnScenesPass) {
  // The paper's rates at its time step, with the stops of its programme.
  EXPECT_EQ(FeasibilityError("psi_epsilon_deg = 0.0\nstretching_rate = 167.0\n[stage.stop]\n"
                             "mean_stress_kpa = 1000.0\n",
                             1.2e-7),
            "");
  EXPECT_EQ(FeasibilityError("type = \"triaxial\"\naxial_strain_rate = 136.355\n"
                             "radial_stress_kpa = 100.0\n[stage.stop]\naxial_strain = 0.4\n",
                             1.2e-7),
            "");
}

TEST(SceneFeasibility, ATimeStepFarBelowTheContactDurationIsRejected) {
  const std::string text =
      "[sample.generate]\ncount = 100\ncell_size_mm = 3.0\n[numerics]\ntime_step_s = 1e-15\n"
      "[[stage]]\npsi_epsilon_deg = 0.0\nstretching_rate = 167.0\n[stage.stop]\n"
      "mean_stress_kpa = 100.0\n";
  const Scene scene = Scene::Parse(text, "tiny_step.toml", "");
  try {
    scene.TimeStep(scene.BuildSample(nullptr));
    ADD_FAILURE() << "a time step of 1e-15 s was accepted";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'numerics.time_step_s' = 1e-15"), std::string::npos) << message;
    EXPECT_NE(message.find("of the smallest contact duration"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace granasym::dem

namespace granasym::dem {
namespace {

// Keys that a stage type, contact law or setting does not use are errors,
// not silently ignored.
TEST(SceneInapplicableKeys, AreRejectedNamingTheKey) {
  const std::string sample = "[sample.generate]\ncount = 100\n";
  const std::string ncl =
      "[[stage]]\npsi_epsilon_deg = 0.0\nstretching_rate = 167.0\n[stage.stop]\n"
      "mean_stress_kpa = 100.0\n";
  struct Case {
    std::string text, key;
  };
  const std::vector<Case> cases = {
      {sample + ncl + "[stage.control]\ngain = 0.5\n", "stage[0].control"},
      {sample + "[[stage]]\ntype = \"rest\"\nmean_stress_kpa = 100.0\n[stage.asymptote]\n"
                "window_strain = 0.5\n",
       "asymptote"},
      {sample + "[[stage]]\npsi_epsilon_deg = 0.0\nstretching_rate = 167.0\n"
                "axial_strain_rate = 1.0\n[stage.stop]\nmean_stress_kpa = 100.0\n",
       "stage[0].axial_strain_rate"},
      {sample + "[[stage]]\ntype = \"triaxial\"\naxial_strain_rate = 1.0\nradial_stress_kpa = "
                "100.0\nmax_strain_rate = 5.0\n[stage.stop]\naxial_strain = 0.1\n",
       "stage[0].max_strain_rate"},
      {sample + "[material]\npoissons_ratio = 0.2\n" + ncl, "material.poissons_ratio"},
      {sample + "[material]\ncontact_law = \"hertz_mindlin\"\nstiffness_ratio = 0.3\n" + ncl,
       "material.stiffness_ratio"},
      {sample + "[numerics]\ntime_step_s = 1e-7\ntime_step_fraction = 0.1\n" + ncl,
       "numerics.time_step_s"},
      {sample + "[numerics]\ntime_step_s = 1e-7\ntime_step_check_interval = 10\n" + ncl,
       "numerics.time_step_check_interval"},
      {sample + "[numerics]\ntime_step_s = 1e-7\nmax_time_step_s = 1e-7\n" + ncl,
       "numerics.max_time_step_s"},
      {"[sample]\nstage = \"ncl\"\n[sample.generate]\ncount = 100\n" + ncl, "sample.stage"},
      {sample + "[output]\noverlap_histogram = false\nhistogram_bins = 10\n" + ncl,
       "output.histogram_bins"},
      {sample + ncl + "[stage.stop.extra]\nx = 1\n", "stage[0].stop.extra"},
      {sample + "[[stage]]\npsi_epsilon_deg = 90.0\nstretching_rate = 167.0\n"
                "[stage.asymptote]\nwindow_lnp = 1.0\n[stage.stop]\nasymptote = true\n",
       "stage[0].asymptote.window_lnp"},
  };
  for (const Case& c : cases) {
    std::string message;
    try {
      Scene::Parse(c.text, "inapplicable.toml", "");
    } catch (const InputError& error) {
      message = error.what();
    }
    EXPECT_NE(message.find(c.key), std::string::npos)
        << "expected an error naming " << c.key << ", got '" << message << "' for:\n"
        << c.text;
  }
}

}  // namespace
}  // namespace granasym::dem
