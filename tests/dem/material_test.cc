#include "dem/material.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "common/canonical_text.h"
#include "common/config.h"
#include "common/error.h"
#include "common/state_measures.h"

namespace granasym::dem {
namespace {

Material Parse(const std::string& body) {
  const ConfigTable root = ConfigTable::ParseString("[material]\n" + body, "scene.toml");
  return ParseMaterial(root.GetTable("material"));
}

std::string ErrorOf(const std::string& body) {
  try {
    Parse(body);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

void ExpectMentions(const std::string& message, const std::vector<std::string>& parts) {
  ASSERT_FALSE(message.empty()) << "no error";
  for (const std::string& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' missing in: " << message;
  }
}

void ExpectSame(const Material& a, const Material& b) {
  EXPECT_EQ(a.contact_law, b.contact_law);
  EXPECT_EQ(a.youngs_modulus, b.youngs_modulus);
  EXPECT_EQ(a.stiffness_ratio, b.stiffness_ratio);
  EXPECT_EQ(a.poissons_ratio, b.poissons_ratio);
  EXPECT_EQ(a.friction_angle, b.friction_angle);
  EXPECT_EQ(a.rolling_friction, b.rolling_friction);
  EXPECT_EQ(a.density, b.density);
  EXPECT_EQ(a.local_damping, b.local_damping);
  EXPECT_EQ(a.stiffness_scaling, b.stiffness_scaling);
}

TEST(Material, DefaultMaterialIsValidAndIsThePapersLinearLaw) {
  const Material material;
  std::string why;
  EXPECT_TRUE(material.IsValid(&why)) << why;
  EXPECT_EQ(material.contact_law, ContactLaw::kLinear);
  EXPECT_EQ(material.youngs_modulus, 500e6);
  EXPECT_EQ(material.stiffness_ratio, 0.3);
  EXPECT_EQ(material.friction_angle, 0.5);
  EXPECT_EQ(material.density, 2650.0);
  EXPECT_EQ(material.local_damping, 0.5);
  EXPECT_EQ(material.rolling_friction, 0.0);  // the paper has no rolling resistance
  EXPECT_EQ(material.stiffness_scaling, 1.0);
  EXPECT_EQ(material.contact_modulus(), material.youngs_modulus);
  EXPECT_TRUE(material.has_friction());
  EXPECT_FALSE(material.has_rolling_resistance());
}

TEST(Material, IsValidNamesTheOffendingField) {
  std::string why;
  Material hertz;
  hertz.contact_law = ContactLaw::kHertzMindlin;
  hertz.poissons_ratio = 0.5;
  EXPECT_FALSE(hertz.IsValid(&why));
  EXPECT_NE(why.find("poissons_ratio"), std::string::npos) << why;
  hertz.poissons_ratio = 0.25;
  hertz.stiffness_ratio = -1;  // not Hertz–Mindlin's: ignored
  EXPECT_TRUE(hertz.IsValid(&why)) << why;
  Material rolling;
  rolling.rolling_friction = 0.1;
  EXPECT_TRUE(rolling.IsValid(&why)) << why;
  rolling.friction_angle = 0.0;
  EXPECT_FALSE(rolling.IsValid(&why));
  EXPECT_NE(why.find("rolling_friction"), std::string::npos) << why;
  rolling.rolling_friction = -0.1;
  EXPECT_FALSE(rolling.IsValid(&why));
}

// κ = E/(2p) (linear) and (E*/p)^(2/3), E* = E/(2(1 − ν²)) (Hertz–Mindlin),
// both with the contact modulus s·E.
TEST(Material, TheStiffnessNumberIsThatOfItsLawWithTheScaledModulus) {
  const Material linear = Parse("youngs_modulus_mpa = 500.0\nstiffness_scaling = 0.1\n");
  EXPECT_DOUBLE_EQ(linear.StiffnessNumber(100e3), 0.1 * 500e6 / (2 * 100e3));  // 250
  const Material hertz =
      Parse("contact_law = \"hertz_mindlin\"\nyoungs_modulus_mpa = 500.0\npoissons_ratio = 0.2\n");
  EXPECT_DOUBLE_EQ(hertz.StiffnessNumber(100e3),
                   std::pow(500e6 / (2 * (1 - 0.04)) / 100e3, 2.0 / 3.0));
  Material scaled = hertz;
  scaled.stiffness_scaling = 0.125;  // κ falls by s^(2/3) = 1/4
  EXPECT_DOUBLE_EQ(scaled.StiffnessNumber(100e3), 0.25 * hertz.StiffnessNumber(100e3));
  EXPECT_EQ(linear.StiffnessNumber(0.0), std::numeric_limits<double>::infinity());
}

TEST(ContactLaw, NamesRoundTrip) {
  for (ContactLaw law : {ContactLaw::kLinear, ContactLaw::kHertzMindlin}) {
    EXPECT_EQ(FromString<ContactLaw>(ToString(law)), law);
  }
  EXPECT_FALSE(FromString<ContactLaw>("hertz").has_value());
}

TEST(ParseMaterial, AnEmptyTableGivesTheDefaults) { ExpectSame(Parse(""), Material{}); }

TEST(ParseMaterial, ReadsTheExistingKeysInTheirUnits) {
  const Material material = Parse(
      "youngs_modulus_mpa = 70.0\nstiffness_ratio = 0.25\nfriction_angle_rad = 0.4\n"
      "density_kg_m3 = 2500.0\nlocal_damping = 0.2\n");
  EXPECT_EQ(material.contact_law, ContactLaw::kLinear);
  EXPECT_DOUBLE_EQ(material.youngs_modulus, 70e6);
  EXPECT_EQ(material.stiffness_ratio, 0.25);
  EXPECT_EQ(material.friction_angle, 0.4);
  EXPECT_EQ(material.density, 2500.0);
  EXPECT_EQ(material.local_damping, 0.2);
}

TEST(ParseMaterial, ReadsHertzMindlinWithRollingResistance) {
  const Material material =
      Parse("contact_law = 'hertz_mindlin'\npoissons_ratio = 0.2\nrolling_friction = 0.05\n");
  EXPECT_EQ(material.contact_law, ContactLaw::kHertzMindlin);
  EXPECT_EQ(material.poissons_ratio, 0.2);
  EXPECT_EQ(material.rolling_friction, 0.05);
  EXPECT_TRUE(material.has_rolling_resistance());
  EXPECT_EQ(Parse("contact_law = 'hertz_mindlin'\n").poissons_ratio, Material{}.poissons_ratio);
  EXPECT_EQ(Parse("rolling_friction = 0.1\n").rolling_friction, 0.1);  // linear + rolling
}

TEST(ParseMaterial, RejectsTheElasticConstantOfTheOtherLaw) {
  ExpectMentions(ErrorOf("contact_law = 'hertz_mindlin'\nstiffness_ratio = 0.3\n"),
                 {"scene.toml", "material.stiffness_ratio", "0.3", "'linear' only",
                  "poissons_ratio", "(-1, 0.5)"});
  ExpectMentions(ErrorOf("poissons_ratio = 0.2\n"), {"scene.toml", "material.poissons_ratio", "0.2",
                                                     "'hertz_mindlin' only", "stiffness_ratio"});
}

TEST(ParseMaterial, RejectsValuesOutOfRangeUnknownLawsAndUnknownKeys) {
  ExpectMentions(ErrorOf("contact_law = 'hertz_mindlin'\npoissons_ratio = 0.5\n"),
                 {"material.poissons_ratio", "0.5", "(-1, 0.5)"});
  ExpectMentions(ErrorOf("rolling_friction = -0.1\n"),
                 {"material.rolling_friction", "-0.1", "in [0, 10]"});
  ExpectMentions(ErrorOf("contact_law = 'hertz'\n"),
                 {"material.contact_law", "hertz", "linear or hertz_mindlin"});
  ExpectMentions(ErrorOf("friction_angle = 0.5\n"),
                 {"material.friction_angle", "friction_angle_rad"});
  ExpectMentions(ErrorOf("youngs_modulus_mpa = -1\n"),
                 {"material.youngs_modulus_mpa", "-1", "in [0.001, 10000000]"});
}

TEST(ParseMaterial, StiffnessScalingIsAFractionOfTheContactModulus) {
  const Material scaled = Parse("youngs_modulus_mpa = 400.0\nstiffness_scaling = 0.25\n");
  EXPECT_EQ(scaled.stiffness_scaling, 0.25);
  EXPECT_DOUBLE_EQ(scaled.youngs_modulus, 400e6);  // the grains' modulus is kept as given
  EXPECT_DOUBLE_EQ(scaled.contact_modulus(), 100e6);
  EXPECT_EQ(Parse("stiffness_scaling = 1.0\n").stiffness_scaling, 1.0);
  for (const auto& [literal, spelling] : std::vector<std::pair<std::string, std::string>>{
           {"0.0", "= 0 "}, {"-0.5", "= -0.5 "}, {"1.5", "= 1.5 "}}) {
    ExpectMentions(ErrorOf("stiffness_scaling = " + literal + "\n"),
                   {"scene.toml", "material.stiffness_scaling", spelling, "in (0, 1]"});
  }
  std::string why;
  Material invalid;
  invalid.stiffness_scaling = 0;
  EXPECT_FALSE(invalid.IsValid(&why));
  EXPECT_NE(why.find("stiffness_scaling"), std::string::npos) << why;
}

TEST(ParseMaterial, RejectsRollingResistanceWithoutFriction) {
  ExpectMentions(ErrorOf("rolling_friction = 0.1\nfriction_angle_rad = 0.0\n"),
                 {"material.rolling_friction", "0.1", "friction_angle_rad > 0"});
  ExpectMentions(ErrorOf("rolling_friction = 0.1\nstiffness_ratio = 0.0\n"),
                 {"material.rolling_friction", "stiffness_ratio > 0"});
  EXPECT_NO_THROW(Parse("rolling_friction = 0.0\nfriction_angle_rad = 0.0\n"));
}

TEST(Material, ItsCanonicalTextIsWhatParseMaterialReadsBack) {
  Material linear;
  linear.rolling_friction = 0.07;
  linear.friction_angle = 0.123456789012345;
  Material hertz;
  hertz.contact_law = ContactLaw::kHertzMindlin;
  hertz.youngs_modulus = 70e9;
  hertz.poissons_ratio = 0.22;
  hertz.local_damping = 0.0;
  hertz.stiffness_scaling = 0.01;
  for (const Material& material : {Material{}, linear, hertz}) {
    CanonicalText canonical;
    material.Canonical(canonical, "");
    const std::string text = "[material]\n" + canonical.Text();
    SCOPED_TRACE(text);
    const ConfigTable root = ConfigTable::ParseString(text, "canonical");
    const Material back = ParseMaterial(root.GetTable("material"));
    ExpectSame(back, material);
    EXPECT_NO_THROW(root.CheckNoUnknownKeys());
  }
  auto text_of = [](const Material& material) {
    CanonicalText canonical;
    material.Canonical(canonical, "");
    return canonical.Text();
  };
  EXPECT_EQ(text_of(hertz).find("stiffness_ratio"), std::string::npos);
  EXPECT_EQ(text_of(Material{}).find("poissons_ratio"), std::string::npos);
}

// ---------------------------------------------------------------------------
// Contact durations.

TEST(ContactDurations, LinearLawKeepsThePapersFormulasBitForBit) {
  const Material material;
  const std::vector<double> radii = {0.3e-3, 0.1e-3, 0.5e-3, 0.12e-3};
  const ContactDurations d = ComputeContactDurations(radii, material);
  // The formulas as the engine wrote them into result files before the laws
  // had their own headers (SPEC §4).
  auto mass = [&](double r) { return material.density * 4.0 / 3.0 * kPi * r * r * r; };
  auto duration = [&](double r, bool reduced) {
    const double k_n = material.youngs_modulus * r;
    const double m = mass(r);
    return kPi / std::sqrt(k_n / (reduced ? 0.5 * m : m));
  };
  EXPECT_EQ(d.smallest_reduced_mass, duration(0.1e-3, true));
  EXPECT_EQ(d.largest_reduced_mass, duration(0.5e-3, true));
  EXPECT_EQ(d.smallest_single_mass, duration(0.1e-3, false));
  EXPECT_EQ(d.largest_single_mass, duration(0.5e-3, false));
  const double k_n = 2.0 * material.youngs_modulus * 0.1e-3 * 0.12e-3 / (0.1e-3 + 0.12e-3);
  const double inverse_mass = 1.0 / mass(0.1e-3) + 1.0 / mass(0.12e-3);
  EXPECT_EQ(d.critical_time_step,
            2.0 / std::sqrt(k_n * inverse_mass * std::max(1.0, 3.5 * material.stiffness_ratio)));
  // The paper's values for its GSD (0.2–1.0 mm): 1.05e-6 s and 5.23e-6 s with
  // the reduced mass, 1.5e-6 s and 7.4e-6 s with one sphere's mass.
  const ContactDurations paper = ComputeContactDurations({0.1e-3, 0.5e-3}, material);
  EXPECT_NEAR(paper.smallest_reduced_mass, 1.05e-6, 0.01e-6);
  EXPECT_NEAR(paper.largest_reduced_mass, 5.23e-6, 0.01e-6);
  EXPECT_NEAR(paper.smallest_single_mass, 1.5e-6, 0.05e-6);
  EXPECT_NEAR(paper.largest_single_mass, 7.4e-6, 0.05e-6);
  EXPECT_NE(d.description.find("linear"), std::string::npos) << d.description;
}

TEST(ContactDurations, HertzMindlinUsesTheReferenceSpeedAndOverlap) {
  Material material;
  material.contact_law = ContactLaw::kHertzMindlin;
  material.poissons_ratio = 0.2;
  const double r = 0.1e-3;
  const ContactDurations d = ComputeContactDurations({r, 0.4e-3}, material);
  const double e_star = material.youngs_modulus / (2 * (1 - 0.2 * 0.2));
  const double m = SphereMass(r, material.density);
  auto hertz = [&](double mass, double speed) {
    return 2.8682657 * std::pow(mass * mass / (0.5 * r * e_star * e_star * speed), 0.2);
  };
  EXPECT_NEAR(d.smallest_reduced_mass, hertz(0.5 * m, 1.0), 1e-12 * d.smallest_reduced_mass);
  EXPECT_NEAR(d.smallest_single_mass, hertz(m, 1.0), 1e-12 * d.smallest_single_mass);
  EXPECT_GT(d.largest_reduced_mass, d.smallest_reduced_mass);
  // Leapfrog limit of the two smallest spheres (here the only two) with k_n at
  // u_N = 0.1 (r_i + r_j) and the sliding factor 3.5 k_t/k_n = 3.5 · 2(1 − ν)/(2 − ν).
  const double r_j = 0.4e-3;
  const double k_n = 2 * e_star * std::sqrt(r * r_j / (r + r_j) * 0.1 * (r + r_j));
  const double inverse_mass = 1 / m + 1 / SphereMass(r_j, material.density);
  const double factor = 3.5 * 2 * (1 - 0.2) / (2 - 0.2);
  EXPECT_NEAR(d.critical_time_step, 2 / std::sqrt(k_n * inverse_mass * factor),
              1e-12 * d.critical_time_step);
  EXPECT_NE(d.description.find("1 m/s"), std::string::npos) << d.description;
  EXPECT_NE(d.description.find("0.1"), std::string::npos) << d.description;
}

TEST(ContactDurations, ScalingTheStiffnessByAQuarterDoublesTheLinearDurations) {
  // t_c = π sqrt(m_12/k_n) with k_n ∝ s E: a quarter of the stiffness
  // doubles every duration and the stability limit (exactly: 4 is a power of 2).
  const std::vector<double> radii = {0.1e-3, 0.3e-3, 0.5e-3};
  Material scaled;
  scaled.stiffness_scaling = 0.25;
  const ContactDurations full = ComputeContactDurations(radii, Material{});
  const ContactDurations soft = ComputeContactDurations(radii, scaled);
  EXPECT_EQ(soft.smallest_reduced_mass, 2 * full.smallest_reduced_mass);
  EXPECT_EQ(soft.largest_single_mass, 2 * full.largest_single_mass);
  EXPECT_DOUBLE_EQ(soft.critical_time_step, 2 * full.critical_time_step);
  EXPECT_EQ(soft.stability_fraction, full.stability_fraction);
  // Hertz–Mindlin: the impact duration scales as E*^(-2/5).
  Material hertz;
  hertz.contact_law = ContactLaw::kHertzMindlin;
  Material hertz_scaled = hertz;
  hertz_scaled.stiffness_scaling = 0.25;
  EXPECT_NEAR(ComputeContactDurations(radii, hertz_scaled).smallest_reduced_mass /
                  ComputeContactDurations(radii, hertz).smallest_reduced_mass,
              std::pow(0.25, -0.4), 1e-12);
}

TEST(ContactDurations, TheStabilityFractionIsTheLimitOverTheDurationAtOneStiffness) {
  // Linear law, equal spheres: critical / t_c = 2/(π sqrt(factor)); without
  // friction factor = 1, with the paper's k_s/k_n = 0.3 it is 3.5 · 0.3.
  Material frictionless;
  frictionless.friction_angle = 0;
  const ContactDurations plain = ComputeContactDurations({0.1e-3, 0.1e-3}, frictionless);
  EXPECT_NEAR(plain.stability_fraction, 2 / kPi, 1e-15);
  EXPECT_NEAR(plain.critical_time_step / plain.smallest_reduced_mass, plain.stability_fraction,
              1e-12);
  const ContactDurations paper = ComputeContactDurations({0.1e-3, 0.1e-3}, Material{});
  EXPECT_NEAR(paper.stability_fraction, 2 / (kPi * std::sqrt(1.05)), 1e-15);
  // Hertz–Mindlin with friction (ν = 0.25: k_t/k_n = 6/7): 0.368.
  Material hertz;
  hertz.contact_law = ContactLaw::kHertzMindlin;
  EXPECT_NEAR(ComputeContactDurations({0.1e-3}, hertz).stability_fraction,
              2 / (kPi * std::sqrt(3.5 * 6.0 / 7.0)), 1e-15);
}

TEST(ContactDurations, StiffRollingResistanceTightensTheStabilityLimit) {
  Material material;
  const std::vector<double> radii = {0.1e-3, 0.5e-3};
  const double without = ComputeContactDurations(radii, material).critical_time_step;
  material.rolling_friction = 0.1;  // k_r (1/I_i + 1/I_j) well below the normal mode
  EXPECT_EQ(ComputeContactDurations(radii, material).critical_time_step, without);
  material.rolling_friction = 2.0;
  const ContactDurations stiff = ComputeContactDurations(radii, material);
  EXPECT_LT(stiff.critical_time_step, without);
  EXPECT_NE(stiff.description.find("rolling"), std::string::npos);
  EXPECT_EQ(stiff.smallest_reduced_mass,
            ComputeContactDurations(radii, Material{}).smallest_reduced_mass);
}

}  // namespace
}  // namespace granasym::dem
