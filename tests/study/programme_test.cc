#include "study/programme.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "common/error.h"
#include "dem/scene.h"
#include "dem/strain_path_stage.h"
#include "dem/triaxial_stage.h"
#include "study/plan.h"

namespace granasym::study {
namespace {

const char* kProgramme = R"(
[study]
name = "t"
ncl = "ncl"
[scale.tiny]
count = 100
replicates = 2
[sample]
reference_count = 100
reference_cell_size_mm = 4.0
[scene.numerics]
time_step_s = 1e-7
[[run]]
name = "ncl"
from = "sample"
[[run.stage]]
each = { p = [10, 50.5] }
name = "p{p}"
psi_epsilon_deg = 0.0
stretching_rate = 100.0
stop.mean_stress_kpa = "{p}"
[[run]]
name = "nc{p}_psi{psi}"
from = "ncl@p{p}"
vary = { p = [10, 50.5], psi = [45, 90] }
[[run.stage]]
psi_epsilon_deg = "{psi}"
stretching_rate = 100.0
stop = { strain_norm = 0.01, asymptote = true }
[[run]]
name = "tx"
from = "ncl"
[[run.stage]]
type = "triaxial"
axial_strain_rate = 50.0
radial_stress_kpa = 50.5
stop.axial_strain = 0.01
)";

Programme Parse(const std::string& text, Scale scale = Scale::kTiny) {
  return Programme::Parse(text, "p.toml", ".", scale);
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(Programme, ListsExpandIntoCasesWithTypedValues) {
  const Programme p = Parse(kProgramme);
  ASSERT_EQ(p.cases.size(), 6u);
  EXPECT_EQ(p.cases[0].name, "ncl");
  EXPECT_EQ(p.cases[0].stage_names, (std::vector<std::string>{"p10", "p50.5"}));
  std::set<std::string> names;
  for (const CaseSpec& c : p.cases) names.insert(c.name);
  EXPECT_TRUE(names.count("nc50.5_psi90"));
  const CaseSpec* c = p.Find("nc50.5_psi45");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->parent, "ncl");
  EXPECT_EQ(c->parent_stage, "p50.5");
  EXPECT_EQ(c->variables.at("psi"), "45");
  // "{psi}" alone became the number 45, not the string "45".
  EXPECT_NE(c->scene_body.find("psi_epsilon_deg = 45"), std::string::npos) << c->scene_body;
  EXPECT_NE(p.cases[0].scene_body.find("mean_stress_kpa = 50.5"), std::string::npos);
  EXPECT_EQ(p.Find("tx")->parent_stage, "");
}

TEST(Programme, CellScalesAtConstantPorosity) {
  SampleSpec s;
  s.reference_count = 150000;
  s.reference_cell_size_mm = 31.0;
  EXPECT_NEAR(s.CellSizeMm(150000), 31.0, 1e-12);
  EXPECT_NEAR(s.CellSizeMm(150000 / 8), 15.5, 1e-12);
}

TEST(Programme, BadInputNamesTheKey) {
  auto message = [](const std::string& text) {
    try {
      Parse(text);
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(Replace(kProgramme, "from = \"ncl@p{p}\"", "from = \"nope@p{p}\""))
                .find("names no earlier case"),
            std::string::npos);
  // "RUN@" with no stage would fork from the final state silently.
  EXPECT_NE(message(Replace(kProgramme, "from = \"ncl@p{p}\"", "from = \"ncl@\""))
                .find("names no stage after '@'"),
            std::string::npos);
  // The study's NCL must have an isotropic compression stage.
  EXPECT_NE(message(Replace(kProgramme, "ncl = \"ncl\"", "ncl = \"tx\"")).find("study.ncl"),
            std::string::npos);
  EXPECT_NE(message(Replace(kProgramme, "psi_epsilon_deg = 0.0", "psi_epsilon_deg = 10.0"))
                .find("no isotropic compression stage"),
            std::string::npos);
  EXPECT_NE(message(Replace(kProgramme, "from = \"ncl@p{p}\"", "from = \"ncl@q{p}\""))
                .find("has no stage 'q10'"),
            std::string::npos);
  EXPECT_NE(message(Replace(kProgramme, "name = \"nc{p}_psi{psi}\"", "name = \"nc{p}_psi{phi}\""))
                .find("{phi}, which is not a variable"),
            std::string::npos);
  EXPECT_NE(message(Replace(kProgramme, "name = \"tx\"", "name = \"ncl\"")).find("twice"),
            std::string::npos);
  EXPECT_NE(message(Replace(kProgramme, "[study]", "[study]\ncolour = 1")).find("study.colour"),
            std::string::npos);
  EXPECT_NE(message(Replace(kProgramme, "[scale.tiny]", "[scale.huge]")).find("expected tiny"),
            std::string::npos);
  EXPECT_NE(message(Replace(kProgramme, "name = \"tx\"", "name = \"a/b\"")).find("not a valid"),
            std::string::npos);
  // What a run serves is checked where it is read (study/case_record.h).
  const std::string figures =
      message(Replace(kProgramme, "name = \"tx\"", "name = \"tx\"\nfigures = \"12, 31\""));
  EXPECT_NE(figures.find("key 'run[3].figures' = '12, 31': '31' is not valid"), std::string::npos)
      << figures;
  EXPECT_EQ(Parse(Replace(kProgramme, "name = \"tx\"", "name = \"tx\"\nfigures = \"12,Sec. 4.3\""))
                .Find("tx")
                ->figures.Text(),
            "12, Sec. 4.3");
}

// A scale that keeps some values of the lists and sets placeholders.
const char* kScaled = R"(
[study]
name = "t"
ncl = "ncl"
[scale.tiny]
count = 100
[scale.tiny.only]
p = [50.5]
psi = [90.0]
[scale.tiny.variables]
cap = 0.01
[scale.small]
count = 200
replicates = 2
[scale.small.variables]
cap = 0.5
[sample]
reference_count = 100
reference_cell_size_mm = 4.0
[scene.numerics]
time_step_s = 1e-7
[[run]]
name = "ncl"
from = "sample"
[[run.stage]]
each = { p = [10, 50.5] }
name = "p{p}"
psi_epsilon_deg = 0.0
stretching_rate = 100.0
stop.mean_stress_kpa = "{p}"
[[run]]
name = "nc{p}_psi{psi}"
from = "ncl@p{p}"
vary = { p = [10, 50.5], psi = [45, 90] }
[[run.stage]]
psi_epsilon_deg = "{psi}"
stretching_rate = 100.0
stop = { strain_norm = "{cap}", asymptote = true }
[[run]]
name = "tx_psi{psi}"
from = "ncl"
vary = { psi = [45] }
[[run.stage]]
type = "triaxial"
axial_strain_rate = 50.0
radial_stress_kpa = 50.5
stop.axial_strain = "{cap}"
)";

TEST(Programme, ScaleKeepsTheValuesOfItsListsAndSetsItsPlaceholders) {
  const Programme tiny = Parse(kScaled, Scale::kTiny);
  std::vector<std::string> names;
  for (const CaseSpec& c : tiny.cases) names.push_back(c.name);
  // Only p = 50.5 (as the number 50.5: `each` and `vary` alike) and ψ = 90
  // (90.0 keeps the integer 90); the triaxial run's only ψ is dropped.
  EXPECT_EQ(names, (std::vector<std::string>{"ncl", "nc50.5_psi90"}));
  EXPECT_EQ(tiny.cases[0].stage_names, (std::vector<std::string>{"p50.5"}));
  EXPECT_NE(tiny.cases[1].scene_body.find("strain_norm = 0.01"), std::string::npos)
      << tiny.cases[1].scene_body;
  EXPECT_EQ(tiny.Current().only.at("p"), (std::vector<std::string>{"50.5"}));
  EXPECT_EQ(tiny.Current().variables.at("cap"), "0.01");

  const Programme small = Parse(kScaled, Scale::kSmall);
  EXPECT_EQ(small.cases.size(), 6u);  // ncl, 4 paths, 1 triaxial
  EXPECT_EQ(small.cases[0].stage_names, (std::vector<std::string>{"p10", "p50.5"}));
  EXPECT_NE(small.Find("tx_psi45")->scene_body.find("axial_strain = 0.5"), std::string::npos);
  const Plan plan = Plan::Make(small, 1, "out");
  EXPECT_EQ(plan.cases.size(), 12u);  // two replicates at this scale
  EXPECT_EQ(plan.scale, Scale::kSmall);
}

TEST(Programme, ScaleRestrictionsThatTakeNoEffectAreErrors) {
  auto message = [](const std::string& text, Scale scale = Scale::kTiny) {
    try {
      Parse(text, scale);
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  // A value no list holds, a variable no list varies.
  EXPECT_NE(message(Replace(kScaled, "p = [50.5]", "p = [50]")).find("keeps 50, which no list"),
            std::string::npos);
  EXPECT_NE(message(Replace(kScaled, "psi = [90.0]", "phi = [90.0]"))
                .find("scale.tiny.only.phi' names no variable"),
            std::string::npos);
  // A string is not the number it spells.
  EXPECT_NE(message(Replace(kScaled, "p = [50.5]", "p = [\"50.5\"]")).find("which no list"),
            std::string::npos);
  // Scales define the same placeholders, and no list reuses their names.
  EXPECT_NE(message(Replace(kScaled, "cap = 0.5", "limit = 0.5"))
                .find("every scale gives the same placeholders"),
            std::string::npos);
  EXPECT_NE(message(Replace(kScaled, "vary = { psi = [45] }", "vary = { psi = [45], cap = [1] }"),
                    Scale::kSmall)
                .find("is also a variable of [scale.small.variables]"),
            std::string::npos);
  // A child kept without its parent stage, a case left without stages.
  EXPECT_NE(message(Replace(kScaled, "each = { p = [10, 50.5] }", "each = { p = [10] }"))
                .find("gives case 'ncl' no stage at scale tiny"),
            std::string::npos);
  EXPECT_NE(message(Replace(kScaled, "from = \"ncl@p{p}\"", "from = \"ncl@p10\""))
                .find("has no stage 'p10'"),
            std::string::npos);
  // The scale asked for must exist.
  EXPECT_NE(message(kScaled, Scale::kPaper).find("has no [scale.paper]"), std::string::npos);
  // Placeholders of the scale fill every table; an undefined one is named.
  EXPECT_NE(message(Replace(kScaled, "\"{cap}\", asymptote", "\"{limit}\", asymptote"))
                .find("{limit}, which is not a variable here (defined: cap"),
            std::string::npos);
}

// The cache survives a commit that changes no result (the program version
// is no part of a key) but not one that does (a new results key).
TEST(Plan, KeysDependOnTheResultsKeyNotOnTheProgramVersion) {
  const Programme p = Parse(kProgramme);
  const Plan a = Plan::Make(p, 1, "out", "results v1; GNU 12.2.0; Release; x86_64");
  const Plan same = Plan::Make(p, 1, "out", "results v1; GNU 12.2.0; Release; x86_64");
  const Plan next = Plan::Make(p, 1, "out", "results v2; GNU 12.2.0; Release; x86_64");
  ASSERT_FALSE(a.cases.empty());
  for (size_t k = 0; k < a.cases.size(); ++k) {
    EXPECT_EQ(a.cases[k].key, same.cases[k].key);
    EXPECT_NE(a.cases[k].key, next.cases[k].key);
    EXPECT_EQ(a.cases[k].inputs.results, "results v1; GNU 12.2.0; Release; x86_64");
    EXPECT_EQ(a.cases[k].inputs.scene_sha256.size(), 64u);
  }
  for (size_t k = 0; k < a.samples.size(); ++k) EXPECT_NE(a.samples[k].key, next.samples[k].key);
  EXPECT_EQ(Plan::Make(p, 1, "out").cases[0].inputs.results, ResultsKey());
  EXPECT_NE(ResultsKey().find("results v" + std::to_string(kResultsVersion) + ";"),
            std::string::npos);
  // Why a case is computed again, in words.
  EXPECT_NE(a.cases[1].inputs.Difference(next.cases[1].inputs).find("the results key changed"),
            std::string::npos);
  EXPECT_NE(a.cases[1].inputs.Difference(next.cases[1].inputs).find("its parent"),
            std::string::npos);
  EXPECT_EQ(a.cases[1].inputs.Difference(same.cases[1].inputs), "");
  EXPECT_NE(KeyInputs{}.Difference(a.cases[1].inputs).find("older version"), std::string::npos);
}

// A vary of 10^6 combinations is refused before any is made, naming the
// count and the lists; so is a case name that cannot be a folder name.
TEST(Programme, AHugeVaryIsRefusedAtOnceWithItsCount) {
  std::string list;
  for (int k = 0; k < 1000; ++k) list += (k ? ", " : "") + std::to_string(k);
  const std::string huge =
      Replace(kProgramme, "vary = { p = [10, 50.5], psi = [45, 90] }",
              "vary = { p = [10, 50.5], psi = [45, 90], a = [" + list + "], b = [" + list + "] }");
  const auto start = std::chrono::steady_clock::now();
  try {
    Parse(huge);
    ADD_FAILURE() << "a 4e6-case programme was accepted";
  } catch (const InputError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("4000000 combinations"), std::string::npos) << what;
    EXPECT_NE(what.find("a (1000) × b (1000)"), std::string::npos) << what;
    EXPECT_NE(what.find("at most 100000"), std::string::npos) << what;
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  const std::string long_name =
      Replace(kProgramme, "name = \"tx\"", "name = \"" + std::string(300, 'x') + "\"");
  try {
    Parse(long_name);
    ADD_FAILURE() << "a 300-character case name was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("300 characters"), std::string::npos) << error.what();
  }
}

TEST(Plan, KeysChainThroughParentsAndThreads) {
  const Programme p = Parse(kProgramme);
  const Plan one = Plan::Make(p, 1, "out");
  ASSERT_EQ(one.cases.size(), 12u);  // two replicates
  EXPECT_EQ(one.cases[0].id, "r1/ncl");
  EXPECT_EQ(one.cases[6].id, "r2/ncl");
  EXPECT_NE(one.cases[0].key, one.cases[6].key);  // another seed
  EXPECT_NE(one.samples[0].key, one.samples[1].key);
  const Plan two = Plan::Make(p, 2, "out");
  for (size_t k = 0; k < one.cases.size(); ++k) EXPECT_NE(one.cases[k].key, two.cases[k].key);
  EXPECT_NE(one.cases[1].scene_text.find("state = \"../ncl/result.h5\""), std::string::npos);

  // A changed parameter of one case changes its key and its descendants' only.
  const Plan changed = Plan::Make(
      Parse(Replace(kProgramme, "axial_strain_rate = 50.0", "axial_strain_rate = 51.0")), 1, "out");
  for (size_t k = 0; k < one.cases.size(); ++k) {
    const bool tx = one.cases[k].spec.name == "tx";
    EXPECT_EQ(one.cases[k].key != changed.cases[k].key, tx) << one.cases[k].id;
  }
  const Plan parent_changed =
      Plan::Make(Parse(Replace(kProgramme, "stretching_rate = 100.0\nstop.mean",
                               "stretching_rate = 90.0\nstop.mean")),
                 1, "out");
  for (size_t k = 0; k < one.cases.size(); ++k) {
    EXPECT_NE(one.cases[k].key, parent_changed.cases[k].key) << one.cases[k].id;
  }
}

TEST(Plan, ShardsCoverEveryLeafOnceWithTheirAncestors) {
  const Plan plan = Plan::Make(Parse(kProgramme), 1, "out");
  std::multiset<int> leaves;
  for (int count : {1, 2, 3, 5}) {
    leaves.clear();
    for (int index = 1; index <= count; ++index) {
      const std::vector<int> shard = plan.Shard(index, count);
      std::set<int> members(shard.begin(), shard.end());
      for (int k : shard) {
        const PlannedCase& c = plan.cases[static_cast<size_t>(k)];
        if (c.parent >= 0) {
          EXPECT_TRUE(members.count(c.parent)) << c.id;
        }
        if (c.children.empty()) leaves.insert(k);
      }
      EXPECT_TRUE(std::is_sorted(shard.begin(), shard.end()));
    }
    EXPECT_EQ(leaves.size(), 10u) << count << " shards";
    EXPECT_EQ(std::set<int>(leaves.begin(), leaves.end()).size(), 10u);
  }
}

// studies/programmes/rate.toml (issue 10 §2): the study at the small scale,
// and the tiny scale that CI runs.
std::string RateProgrammePath() { return std::string(GRANASYM_PROGRAMMES_DIR) + "/rate.toml"; }

TEST(RateProgramme, SmallScaleRunsEveryDirectionStartAndRate) {
  const Programme small = Programme::Load(RateProgrammePath(), Scale::kSmall);
  EXPECT_EQ(small.Current().replicates, 3);
  EXPECT_EQ(small.Current().count, 5000);
  // Per Young's modulus one NCL with a state at every start.
  for (const char* ncl : {"ncl_E500", "ncl_E100"}) {
    ASSERT_NE(small.Find(ncl), nullptr) << ncl;
    EXPECT_EQ(small.Find(ncl)->stage_names,
              (std::vector<std::string>{"p5", "p20", "p100", "p500"}));
    EXPECT_NE(small.Find(ncl)->scene_body.find("inertial_number = 0.001"), std::string::npos);
  }
  // Every (ψ_ε, p_0) at five I* and at 167 1/s; 90° also at E = 100 MPa for
  // the three smallest I* and 167 1/s; 3e-4 on the 90° path from 100 kPa.
  auto expect = [&small](const std::string& name, const std::string& p) {
    const CaseSpec* c = small.Find(name);
    EXPECT_NE(c, nullptr) << name;
    if (!c) return 0;
    EXPECT_EQ(c->figures.Text(), "rate") << name;
    EXPECT_EQ(c->parent_stage, "p" + p) << name;
    return 1;
  };
  int rate_cases = 0;
  for (const std::string p : {"5", "20", "100", "500"}) {
    for (const std::string rate : {"I0.1", "I0.03", "I0.01", "I0.003", "I0.001", "D167"}) {
      rate_cases += expect("nc" + p + "_psi0_" + rate, p);
      rate_cases += expect("nc" + p + "_psi100_" + rate, p);
      rate_cases += expect("nc" + p + "_psi90_" + rate + "_E500", p);
    }
    for (const std::string rate : {"I0.01", "I0.003", "I0.001", "D167"}) {
      rate_cases += expect("nc" + p + "_psi90_" + rate + "_E100", p);
    }
    EXPECT_EQ(small.Find("nc" + p + "_psi90_I0.1_E100"), nullptr);
  }
  rate_cases += expect("nc100_psi90_I0.0003_E500", "100");
  EXPECT_EQ(small.Find("nc20_psi90_I0.0003_E500"), nullptr);
  // The extension sweep: 95°, 105° ... 150° from NC 100 kPa at I* = 3e-3
  // (100° is the rate cases'), stopping on liquefaction; not at I* = 0.1.
  for (int psi = 95; psi <= 150; psi += 5) {
    if (psi == 100) continue;
    rate_cases += expect(fmt::format("nc100_psi{}_I0.003", psi), "100");
    EXPECT_EQ(small.Find(fmt::format("nc100_psi{}_I0.1", psi)), nullptr) << psi;
  }
  EXPECT_NE(small.Find("nc100_psi150_I0.003")->scene_body.find("liquefied = true"),
            std::string::npos);
  EXPECT_NE(small.Find("nc100_psi100_I0.003")->scene_body.find("liquefied = true"),
            std::string::npos);
  // Dilating paths at I* <= 3e-2 stop after 0.02 of strain of gas; at I* = 0.1,
  // at 167 1/s and at 90° (where gas phases were seen to recover) the
  // detector's window holds.
  for (const char* name :
       {"nc100_psi150_I0.003", "nc100_psi95_I0.003", "nc5_psi100_I0.03", "nc500_psi100_I0.001"}) {
    EXPECT_NE(small.Find(name)->scene_body.find("liquefied_strain = 0.02"), std::string::npos)
        << name;
  }
  for (const char* name : {"nc100_psi100_I0.1", "nc100_psi100_D167", "nc100_psi90_I0.001_E500",
                           "nc20_psi90_D167_E100"}) {
    EXPECT_EQ(small.Find(name)->scene_body.find("liquefied_strain"), std::string::npos) << name;
  }
  // Drained triaxial compression at σ_r = p_0 and three axial rates (I ≈
  // 1e-2, 1e-3, 3e-4 at the critical state): ε̇_a ∝ √p_0.
  const std::map<std::string, std::vector<std::string>> drained = {
      {"5", {"9.4789", "0.9479", "0.2844"}},
      {"20", {"18.9577", "1.8958", "0.5687"}},
      {"100", {"42.3908", "4.2391", "1.2717"}},
      {"500", {"94.7887", "9.4789", "2.8437"}}};
  for (const auto& [p, rates] : drained) {
    for (const std::string& rate : rates) {
      const std::string name = "nc" + p + "_drained_ea" + rate;
      rate_cases += expect(name, p);
    }
  }
  // Every 90° case stops once it has liquefied (a slow isochoric path from
  // these NC states turns into a gas and does not rebuild its network).
  EXPECT_NE(small.Find("nc100_psi90_I0.0003_E500")->scene_body.find("liquefied = true"),
            std::string::npos);
  EXPECT_EQ(rate_cases, 4 * 6 * 3 + 4 * 4 + 1 + 11 + 12);
  EXPECT_EQ(small.cases.size(), static_cast<size_t>(rate_cases + 2));
  // The 90° cases of the softer material start from its own NCL.
  EXPECT_EQ(small.Find("nc20_psi90_I0.001_E100")->parent, "ncl_E100");
  EXPECT_NE(small.Find("nc20_psi90_I0.001_E100")->scene_body.find("youngs_modulus_mpa = 100"),
            std::string::npos);
  EXPECT_NE(small.Find("nc20_psi90_D167_E500")->scene_body.find("strain_norm = 0.8"),
            std::string::npos);
  // The runs whose every case is slow and loose take the thinner skin (a
  // speed setting: the results do not depend on it); the others the default.
  for (const char* name : {"nc20_psi90_I0.001_E100", "nc100_psi90_I0.0003_E500", "nc5_psi100_I0.03",
                           "nc100_psi150_I0.003"}) {
    EXPECT_NE(small.Find(name)->scene_body.find("skin_fraction = 0.1"), std::string::npos) << name;
  }
  for (const char* name : {"nc100_psi0_I0.001", "nc100_psi90_I0.001_E500", "nc100_psi100_I0.1",
                           "nc100_psi100_D167", "nc20_drained_ea1.8958"}) {
    EXPECT_EQ(small.Find(name)->scene_body.find("skin_fraction"), std::string::npos) << name;
  }
  // Every scene of every scale is a valid scene (Plan::Make parses them).
  const Plan plan = Plan::Make(small, 1, "out");
  EXPECT_EQ(plan.cases.size(), 3 * small.cases.size());
  const int drained_case = plan.Find("r2/nc100_drained_ea4.2391");
  ASSERT_GE(drained_case, 0);
  const dem::Scene drained_scene = dem::Scene::Parse(
      plan.cases[static_cast<size_t>(drained_case)].scene_text, "scene.toml", ".");
  ASSERT_EQ(drained_scene.stages.size(), 1u);
  const auto* triaxial = drained_scene.stages[0].As<dem::TriaxialStage>();
  ASSERT_NE(triaxial, nullptr);
  EXPECT_DOUBLE_EQ(triaxial->radial_stress_kpa, 100);
  EXPECT_DOUBLE_EQ(triaxial->axial_strain_rate, 4.2391);
  EXPECT_DOUBLE_EQ(*drained_scene.stages[0].stop.axial_strain, 0.6);
  EXPECT_TRUE(drained_scene.stages[0].stop.asymptote);
  const int d167 = plan.Find("r1/nc20_psi90_D167_E500");
  ASSERT_GE(d167, 0);
  EXPECT_EQ(dem::Scene::Parse(plan.cases[static_cast<size_t>(d167)].scene_text, "scene.toml", ".")
                .adaptive_time_step.fraction,
            0.3);
  // The cost estimate (ETA, shards) of a path at fixed I* grows as 1/I*, not
  // that of its cap of 5000 1/s.
  auto steps = [&plan](const std::string& id) {
    const int k = plan.Find(id);
    EXPECT_GE(k, 0) << id;
    return k < 0 ? 0.0 : plan.cases[static_cast<size_t>(k)].estimated_steps;
  };
  EXPECT_NEAR(steps("r1/nc100_psi90_I0.0003_E500") / steps("r1/nc100_psi90_I0.003_E500"), 10.0,
              1e-9);
  EXPECT_GT(steps("r1/nc20_psi90_I0.003_E500"), steps("r1/nc20_psi90_D167_E500"));
  const Programme paper = Programme::Load(RateProgrammePath(), Scale::kPaper);
  EXPECT_EQ(paper.Current().count, 150000);
  EXPECT_EQ(paper.cases.size(), small.cases.size());
}

TEST(RateProgramme, TinyScaleKeepsOneStartTwoRatesAndTheConstantRate) {
  const Programme tiny = Programme::Load(RateProgrammePath(), Scale::kTiny);
  std::vector<std::string> names;
  for (const CaseSpec& c : tiny.cases) names.push_back(c.name);
  EXPECT_EQ(names, (std::vector<std::string>{
                       "ncl_E500", "nc100_psi0_I0.1", "nc100_psi0_I0.03", "nc100_psi0_D167",
                       "nc100_psi90_I0.1_E500", "nc100_psi90_I0.03_E500", "nc100_drained_ea42.3908",
                       "nc100_psi90_D167_E500", "nc100_psi120_I0.1", "nc100_psi150_I0.1"}));
  EXPECT_EQ(tiny.Find("ncl_E500")->stage_names, (std::vector<std::string>{"p100"}));
  const Plan plan = Plan::Make(tiny, 1, "out");
  EXPECT_EQ(plan.cases.size(), 20u);  // two replicates
  EXPECT_EQ(plan.samples[0].options.count, 800u);
  // The tiny caps and rates reach the scenes.
  const int k = plan.Find("r1/nc100_psi90_I0.03_E500");
  ASSERT_GE(k, 0);
  const dem::Scene scene =
      dem::Scene::Parse(plan.cases[static_cast<size_t>(k)].scene_text, "scene.toml", ".");
  ASSERT_EQ(scene.stages.size(), 1u);
  EXPECT_DOUBLE_EQ(*scene.stages[0].stop.strain_norm, 0.3);
  const auto* path = scene.stages[0].As<dem::StrainPathStage>();
  ASSERT_NE(path, nullptr);
  EXPECT_EQ(path->rule, dem::RateRule::kInertial);
  EXPECT_DOUBLE_EQ(path->inertial.inertial_number, 0.03);
  EXPECT_DOUBLE_EQ(path->psi_epsilon_deg, 90);
}

// Every programme shipped in studies/programmes loads at every scale it
// defines, with its NCL case among its cases and its GSD table present.
TEST(ShippedProgrammes, EveryOneLoadsAtEveryScaleItDefines) {
  int programmes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(GRANASYM_PROGRAMMES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    ++programmes;
    const std::string path = entry.path().string();
    const Programme tiny = Programme::Load(path, Scale::kTiny);
    EXPECT_FALSE(tiny.cases.empty()) << path;
    for (const auto& [scale, spec] : tiny.scales) {
      SCOPED_TRACE(path + " at " + ToString(scale));
      const Programme p = Programme::Load(path, scale);
      EXPECT_FALSE(p.cases.empty());
      if (!p.ncl_case.empty()) {
        EXPECT_NE(p.Find(p.ncl_case), nullptr);
      }
      if (!p.sample.gsd_path.empty()) {
        EXPECT_TRUE(std::filesystem::exists(p.sample.gsd_path));
      }
    }
  }
  EXPECT_GE(programmes, 6);
}

// studies/programmes/critical_state_friction*.toml (issue 39 §2): each
// material prepares its own NC state and shears it with the same material.
TEST(CriticalStateFrictionProgramme, EachMaterialPreparesAndShearsItsOwnSample) {
  const std::string dir = GRANASYM_PROGRAMMES_DIR;
  const Programme p = Programme::Load(dir + "/critical_state_friction.toml", Scale::kSmall);
  EXPECT_EQ(p.Current().count, 5000);
  EXPECT_EQ(p.Current().replicates, 3);
  struct Material {
    const char* suffix;
    double damping, ratio, fraction;
  };
  const Material materials[] = {{"chi0.5_kr0.3_f0.3", 0.5, 0.3, 0.3},
                                {"chi0.2_kr0.3_f0.3", 0.2, 0.3, 0.3},
                                {"chi0.05_kr0.3_f0.3", 0.05, 0.3, 0.3},
                                {"chi0.5_kr0.3_f0.2", 0.5, 0.3, 0.2},
                                {"chi0.5_kr1_f0.2", 0.5, 1.0, 0.2}};
  const Plan plan = Plan::Make(p, 1, "out");
  for (const Material& m : materials) {
    const std::string ncl = std::string("ncl_") + m.suffix;
    const std::string drained = std::string("nc100_drained_") + m.suffix;
    ASSERT_NE(p.Find(ncl), nullptr) << ncl;
    ASSERT_NE(p.Find(drained), nullptr) << drained;
    EXPECT_EQ(p.Find(drained)->parent, ncl);
    for (const std::string& name : {ncl, drained}) {
      const int k = plan.Find("r3/" + name);
      ASSERT_GE(k, 0) << name;
      const dem::Scene scene =
          dem::Scene::Parse(plan.cases[static_cast<size_t>(k)].scene_text, "scene.toml", ".");
      EXPECT_DOUBLE_EQ(scene.material.local_damping, m.damping) << name;
      EXPECT_DOUBLE_EQ(scene.material.stiffness_ratio, m.ratio) << name;
      EXPECT_DOUBLE_EQ(scene.adaptive_time_step.fraction, m.fraction) << name;
      if (name == drained) {
        const auto* triaxial = scene.stages.at(0).As<dem::TriaxialStage>();
        ASSERT_NE(triaxial, nullptr);
        EXPECT_DOUBLE_EQ(triaxial->axial_strain_rate, 4.11);
        EXPECT_DOUBLE_EQ(triaxial->radial_stress_kpa, 100);
      }
    }
  }
  EXPECT_EQ(p.cases.size(), 10u);

  const Programme narrow =
      Programme::Load(dir + "/critical_state_friction_narrow.toml", Scale::kSmall);
  EXPECT_NE(narrow.sample.gsd_path.find("gsd_narrow_0.6_0.8.csv"), std::string::npos);
  EXPECT_DOUBLE_EQ(narrow.sample.reference_cell_size_mm, 42.0);
  const Plan narrow_plan = Plan::Make(narrow, 1, "out");
  const dem::Scene narrow_drained = dem::Scene::Parse(
      narrow_plan.cases[static_cast<size_t>(narrow_plan.Find("r1/nc100_drained_narrow"))]
          .scene_text,
      "scene.toml", ".");
  EXPECT_DOUBLE_EQ(narrow_drained.stages.at(0).As<dem::TriaxialStage>()->axial_strain_rate, 5.14);
}

}  // namespace
}  // namespace granasym::study
