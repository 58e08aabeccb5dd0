// The list of contact laws (contact_laws.h): a material selects its law,
// rolling resistance wraps it, and what dispatches through the list (κ, the
// adaptive time step's pass, the κ column's description) is each law's own.
#include "dem/contact_laws.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <type_traits>

#include "dem/output_columns.h"
#include "dem/run_record_names.h"

namespace granasym::dem {
namespace {

Material WithLaw(ContactLaw law, double rolling_friction = 0.0) {
  Material material;
  material.contact_law = law;
  material.rolling_friction = rolling_friction;
  return material;
}

template <class Expected>
bool Selects(const Material& material) {
  return VisitContactLaw(
      material, [](auto law) { return std::is_same_v<typename decltype(law)::type, Expected>; });
}

TEST(ContactLaws, AMaterialSelectsItsLawWrappedWhenItRollsWithResistance) {
  EXPECT_TRUE(Selects<LinearCundallStrack>(WithLaw(ContactLaw::kLinear)));
  EXPECT_TRUE(Selects<HertzMindlin>(WithLaw(ContactLaw::kHertzMindlin)));
  EXPECT_TRUE(Selects<RollingResistance<LinearCundallStrack>>(WithLaw(ContactLaw::kLinear, 0.1)));
  EXPECT_TRUE(Selects<RollingResistance<HertzMindlin>>(WithLaw(ContactLaw::kHertzMindlin, 0.1)));
  EXPECT_FALSE(Selects<HertzMindlin>(WithLaw(ContactLaw::kLinear)));
}

TEST(ContactLaws, OnlyHertzMindlinStiffensWithTheOverlap) {
  EXPECT_FALSE(LinearCundallStrack::kOverlapDependentStiffness);
  EXPECT_TRUE(HertzMindlin::kOverlapDependentStiffness);
  EXPECT_FALSE(RollingResistance<LinearCundallStrack>::kOverlapDependentStiffness);
  EXPECT_TRUE(RollingResistance<HertzMindlin>::kOverlapDependentStiffness);
}

// Rolling resistance leaves the overlaps, so κ, bit for bit.
TEST(ContactLaws, RollingResistanceKeepsTheLawsStiffnessNumber) {
  for (ContactLaw law : {ContactLaw::kLinear, ContactLaw::kHertzMindlin}) {
    const Material plain = WithLaw(law), rolling = WithLaw(law, 0.1);
    for (double p : {1e3, 100e3, 3.7e6})
      EXPECT_EQ(plain.StiffnessNumber(p), rolling.StiffnessNumber(p));
  }
}

// The description in every result file's series: the laws' own texts, in
// the order of ContactLaw.
TEST(ContactLaws, TheStiffnessNumberColumnNamesEachLawsDefinition) {
  std::string description;
  for (const OutputColumn& column : OutputColumns()) {
    if (std::string(column.name) == record::kColumnStiffnessNumber)
      description = column.description;
  }
  EXPECT_EQ(
      description,
      "kappa: E/(2p) for the linear law, (E*/p)^(2/3) for Hertz-Mindlin (1/relative overlap)");
}

}  // namespace
}  // namespace granasym::dem
