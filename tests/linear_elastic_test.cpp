#include "engine/materials/linear_elastic.hpp"
#include "engine/materials/material_registry.hpp"

#include <gtest/gtest.h>

namespace mpile {
namespace {

Stress update_elastic_once(const LinearElastic& material, Stress stress,
                           const StrainIncrement& de) {
  const double modulus = update_single_point(material, stress, nullptr, de);
  EXPECT_DOUBLE_EQ(modulus, material.lame_lambda() + 2.0 * material.shear_modulus());
  return stress;
}

TEST(LinearElastic, IncrementFollowsHookesLawWithEngineeringShear) {
  const LinearElastic material(100e6, 0.25, 2000.0);
  // E = 100 MPa, nu = 0.25: lambda = mu = 40 MPa.
  ASSERT_DOUBLE_EQ(material.lame_lambda(), 40e6);
  ASSERT_DOUBLE_EQ(material.shear_modulus(), 40e6);
  const Stress s = update_elastic_once(material, Stress{1.0, 2.0, 3.0, 4.0, 5.0, 6.0},
                                       StrainIncrement{1e-4, -2e-4, 3e-4, 1e-4, 2e-4, -3e-4});
  const double volumetric = 40e6 * 2e-4;
  EXPECT_DOUBLE_EQ(s[RR], 1.0 + volumetric + 80e6 * 1e-4);
  EXPECT_DOUBLE_EQ(s[YY], 2.0 + volumetric - 80e6 * 2e-4);
  EXPECT_DOUBLE_EQ(s[TT], 3.0 + volumetric + 80e6 * 3e-4);
  EXPECT_DOUBLE_EQ(s[RY], 4.0 + 40e6 * 1e-4);
  EXPECT_DOUBLE_EQ(s[YT], 5.0 + 40e6 * 2e-4);
  EXPECT_DOUBLE_EQ(s[RT], 6.0 - 40e6 * 3e-4);
}

TEST(LinearElastic, StoredEnergyIsHalfStressTimesStrain) {
  const LinearElastic material(70e6, 0.3, 1800.0);
  const StrainIncrement strain{2e-4, -1e-4, 5e-5, 3e-4, -2e-4, 1e-4};
  const Stress s = update_elastic_once(material, Stress{}, strain);
  double work = 0.0;
  for (int c = 0; c < 6; ++c) {
    work += 0.5 * s[static_cast<std::size_t>(c)] * strain[static_cast<std::size_t>(c)];
  }
  EXPECT_NEAR(material.elastic_energy_density(s, nullptr), work, 1e-12 * work);
}

TEST(LinearElastic, RejectsNonPhysicalParameters) {
  EXPECT_THROW(LinearElastic(-1.0, 0.3, 1000.0), std::invalid_argument);
  EXPECT_THROW(LinearElastic(1e6, 0.5, 1000.0), std::invalid_argument);
  EXPECT_THROW(LinearElastic(1e6, 0.3, 0.0), std::invalid_argument);
}

TEST(MaterialRegistry, BuildsByNameAndNamesWhatIsWrong) {
  auto material = create_material(
      "linear_elastic", {{"young_modulus", 1e7}, {"poisson_ratio", 0.2}, {"density", 1500.0}});
  EXPECT_EQ(material->type(), "linear_elastic");
  EXPECT_DOUBLE_EQ(material->density(), 1500.0);
  auto message_of = [](auto&& build) {
    try {
      build();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(
      message_of([] { create_material("elastc", {}); }).find("unknown material type 'elastc'"),
      std::string::npos);
  EXPECT_NE(message_of([] {
              create_material("linear_elastic", {{"young_modulus", 1e7}, {"density", 1500.0}});
            }).find("missing parameter 'poisson_ratio'"),
            std::string::npos);
  EXPECT_NE(message_of([] {
              create_material("linear_elastic", {{"young_modulus", 1e7},
                                                 {"poisson_ratio", 0.2},
                                                 {"density", 1500.0},
                                                 {"yield", 1.0}});
            }).find("unknown parameter 'yield'"),
            std::string::npos);
  EXPECT_NE(message_of([] {
              create_material(
                  "linear_elastic",
                  {{"young_modulus", -5.0}, {"poisson_ratio", 0.2}, {"density", 1500.0}});
            }).find("linear_elastic: young_modulus must be > 0 Pa, got -5"),
            std::string::npos);
}

} // namespace
} // namespace mpile
