#include "engine/materials/principal_stress.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <vector>

namespace mpile {
namespace {

/// Each decomposition against Eigen's iterative solver (backward stable): values within 1e-9 Pa
/// and ordered, directions orthonormal within 1e-12, the recomposed tensor within 1e-9 Pa (values
/// up to 2e5 Pa round at a few 1e-11 Pa).
void expect_as_the_iterative_solver(const std::vector<Stress>& cases) {
  for (const Stress& s : cases) {
    const PrincipalStress p = principal_compression(s);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> reference(-to_matrix(s));
    for (std::size_t k = 0; k < 3; ++k) {
      ASSERT_NEAR(p.values[k], reference.eigenvalues()(2 - static_cast<int>(k)), 1e-9);
    }
    EXPECT_GE(p.values[0], p.values[1]);
    EXPECT_GE(p.values[1], p.values[2]);
    const Eigen::Matrix3d gram = p.directions.transpose() * p.directions;
    ASSERT_LT((gram - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
    const Stress back = compose_from_principal(p.values, p.directions);
    for (std::size_t c = 0; c < 6; ++c) {
      ASSERT_NEAR(back[c], s[c], 1e-9) << "component " << c;
    }
  }
}

/// 1000 random stresses and each with its theta shears zeroed (the r-y block alone).
void add_random_stresses(std::vector<Stress>& cases, std::mt19937& random,
                         std::uniform_real_distribution<double>& value) {
  for (int k = 0; k < 1000; ++k) {
    Stress s;
    for (double& c : s) {
      c = value(random);
    }
    cases.push_back(s);
    s[RT] = s[YT] = 0.0;
    cases.push_back(s);
  }
}

TEST(PrincipalStress, DecomposesAndRecomposesTheFullTensor) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> value(-1e5, 1e5);
  for (int k = 0; k < 1000; ++k) {
    Stress s;
    for (double& c : s) {
      c = value(random);
    }
    const PrincipalStress p = principal_compression(s);
    EXPECT_GE(p.values[0], p.values[1]);
    EXPECT_GE(p.values[1], p.values[2]);
    // Invariants: the trace (compression positive) and the recomposed tensor.
    EXPECT_NEAR(p.values[0] + p.values[1] + p.values[2], -(s[RR] + s[YY] + s[TT]), 1e-9);
    const Stress back = compose_from_principal(p.values, p.directions);
    for (std::size_t c = 0; c < 6; ++c) {
      ASSERT_NEAR(back[c], s[c], 1e-9) << "component " << c;
    }
  }
}

TEST(PrincipalStress, AnRYBlockDecomposesInClosedFormAsTheIterativeSolverDoes) {
  // Without theta shears the decomposition is the closed form of the r-y block; the reference is
  // Eigen's iterative solver (backward stable). Values up to 1e5 Pa round at about 1e-11 Pa, so
  // 1e-9 Pa on values and recomposed components, 1e-12 on the orthonormality of the directions.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> value(-1e5, 1e5);
  std::vector<Stress> cases;
  for (int k = 0; k < 1000; ++k) {
    cases.push_back({value(random), value(random), value(random), value(random), 0.0, 0.0});
  }
  // Isotropic block, no shear with either normal larger, a K0 state, an out-of-plane value
  // equal to one of the block's.
  cases.push_back({-70e3, -70e3, -10e3, 0.0, 0.0, 0.0});
  cases.push_back({-30e3, -90e3, -50e3, 0.0, 0.0, 0.0});
  cases.push_back({-90e3, -30e3, -50e3, 0.0, 0.0, 0.0});
  cases.push_back({-50e3, -100e3, -50e3, 0.0, 0.0, 0.0});
  cases.push_back({-60e3, -60e3, -40e3, 20e3, 0.0, 0.0});
  expect_as_the_iterative_solver(cases);
}

TEST(PrincipalStress, TheFullTensorDecomposesWithoutIterationsAsTheIterativeSolverDoes) {
  // With theta shears: the value farther from the others from the cubic, its direction from
  // cross products, the other two as a closed-form pair in the plane normal to it. Reference:
  // Eigen's iterative solver (backward stable). Random tensors, and the hard cases: a double
  // root (a K0 state with theta shears from 1e-3 Pa up), a nearly triple one, equally spaced
  // roots (r = 0 of the cubic) and values of very different size. Values up to 2e5 Pa round at a
  // few 1e-11 Pa: 1e-9 Pa on values and recomposed components, 1e-12 on orthonormality.
  std::mt19937 random(17);
  std::uniform_real_distribution<double> value(-1e5, 1e5);
  std::vector<Stress> cases;
  for (int k = 0; k < 2000; ++k) {
    Stress s;
    for (double& c : s) {
      c = value(random);
    }
    cases.push_back(s);
  }
  for (const double tiny : {1e-3, 1e-1, 1e1, 1e3}) {
    cases.push_back({-50e3, -100e3, -50e3, 0.0, tiny, 0.0});
    cases.push_back({-50e3, -100e3, -50e3, tiny, 0.0, tiny});
    cases.push_back({-50e3, -50e3, -100e3, 0.0, tiny, tiny});
    cases.push_back({-70e3, -70e3, -70e3, 0.0, 0.0, tiny});
    cases.push_back({-70e3, -70e3 + tiny, -70e3 - tiny, tiny, tiny, tiny});
    cases.push_back({0.0, 0.0, 0.0, 0.0, 25e3, tiny});
  }
  cases.push_back({-1e5, -1.0, -1e-3, 0.0, 1e-2, 0.0});
  expect_as_the_iterative_solver(cases);
}

TEST(PrincipalStress, RepeatedValuesOfAK0StateAndTorsionShear) {
  // K0 state: sigma_rr = sigma_thth = 0.5 sigma_yy (tension positive), a double eigenvalue.
  const Stress k0{-50e3, -100e3, -50e3, 0.0, 0.0, 0.0};
  const PrincipalStress p = principal_compression(k0);
  EXPECT_DOUBLE_EQ(p.values[0], 100e3);
  EXPECT_NEAR(p.values[1], 50e3, 1e-9);
  EXPECT_NEAR(p.values[2], 50e3, 1e-9);
  // Pure y-theta shear tau: principal values tau, 0, -tau.
  const Stress torsion{0.0, 0.0, 0.0, 0.0, 25e3, 0.0};
  const PrincipalStress t = principal_compression(torsion);
  EXPECT_NEAR(t.values[0], 25e3, 1e-9);
  EXPECT_NEAR(t.values[1], 0.0, 1e-9);
  EXPECT_NEAR(t.values[2], -25e3, 1e-9);
}

TEST(PrincipalStress, ValuesAloneAgreeWithTheDecompositionWithinTheirUncertainty) {
  // Random tensors with and without theta shears, and near-repeated values (a K0 state with a
  // tiny torsion shear), where the cubic's closed form is least accurate. The reference is the
  // iterative decomposition (backward stable: errors of order 1e-16 of the largest value).
  std::mt19937 random(5);
  std::uniform_real_distribution<double> value(-1e5, 1e5);
  std::vector<Stress> cases;
  add_random_stresses(cases, random, value);
  for (const double tiny : {1e-3, 1e-1, 1e1}) {
    cases.push_back({-50e3, -100e3, -50e3, 0.0, tiny, 0.0});
    cases.push_back({-50e3, -100e3, -50e3, tiny, 0.0, tiny});
    cases.push_back({-70e3, -70e3, -70e3, 0.0, 0.0, tiny});
  }
  for (const Stress& s : cases) {
    const PrincipalValues fast = principal_compression_values(s);
    const PrincipalStress reference = principal_compression(s);
    const bool block = s[RT] == 0.0 && s[YT] == 0.0;
    EXPECT_EQ(fast.uncertainty == 0.0, block);
    // Rounding of values up to 2e5 Pa: a few 1e-11 Pa; 1e-9 leaves room for either method.
    const double allowed = fast.uncertainty + 1e-9;
    EXPECT_GE(fast.values[0], fast.values[1]);
    EXPECT_GE(fast.values[1], fast.values[2]);
    for (std::size_t k = 0; k < 3; ++k) {
      ASSERT_NEAR(fast.values[k], reference.values[k], allowed) << "value " << k;
    }
  }
}

TEST(PrincipalStress, TheEstimateBoundsItsDistanceFromTheValues) {
  // The elastic check's estimate: with theta shears below 1e-8 of the stress, the r-y block's
  // values with the shears as their bound (Weyl), which must hold against the tensor's values
  // (the iterative decomposition), at K0-like double roots above all; otherwise the values.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> value(-1e5, 1e5), scale(-12.0, -8.0);
  std::vector<Stress> cases;
  for (int k = 0; k < 2000; ++k) {
    Stress s;
    for (double& c : s) {
      c = value(random);
    }
    if (k % 2 == 0) {
      s[TT] = s[RR]; // a double root when the r-y shear is small, as at K0
      s[RY] = k % 4 == 0 ? 0.0 : s[RY];
    }
    const double size = std::abs(s[RR]) + std::abs(s[YY]) + std::abs(s[TT]);
    s[RT] = size * std::pow(10.0, scale(random)) * (k % 3 == 0 ? 0.0 : 1.0);
    s[YT] = size * std::pow(10.0, scale(random));
    cases.push_back(s);
  }
  int bounded = 0;
  for (const Stress& s : cases) {
    const PrincipalEstimate estimate = principal_compression_estimate(s);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> reference(-to_matrix(s));
    const double largest = reference.eigenvalues().cwiseAbs().maxCoeff();
    bounded += estimate.bounded ? 1 : 0;
    for (int k = 0; k < 3; ++k) {
      // Descending against Eigen's ascending order; rounding: a few ulps of the largest value.
      ASSERT_NEAR(estimate.values.values[static_cast<std::size_t>(k)],
                  reference.eigenvalues()(2 - k), estimate.values.uncertainty + 1e-14 * largest);
    }
    if (!estimate.bounded) {
      EXPECT_EQ(estimate.values.values, principal_compression_values(s).values);
    }
  }
  EXPECT_GT(bounded, 500); // the bound was exercised
}

TEST(PrincipalStress, TheMinorValueAloneIsTheValuesSmallestToTheBit) {
  // principal_compression_minor serves the stiffness at the start of a Hardening Soil update in
  // place of principal_compression_values: it must give the very same number, with and without
  // theta shears, at repeated values and at the isotropic state.
  std::mt19937 random(68);
  std::uniform_real_distribution<double> value(-1e5, 1e5);
  std::vector<Stress> cases{{-50e3, -100e3, -50e3, 0.0, 0.0, 0.0},
                            {-50e3, -100e3, -50e3, 0.0, 1e-3, 0.0},
                            {-70e3, -70e3, -70e3, 0.0, 0.0, 0.0},
                            {-70e3, -70e3, -70e3, 0.0, 0.0, 1e-200},
                            {-20e3, -60e3, -80e3, 0.0, 0.0, 0.0}};
  add_random_stresses(cases, random, value);
  for (const Stress& s : cases) {
    ASSERT_EQ(principal_compression_minor(s), principal_compression_values(s).values[2]);
  }
}

TEST(PrincipalStress, EngineeringShearStrainConvertsBothWays) {
  const StrainIncrement de{1e-4, -2e-4, 3e-5, 4e-4, -6e-5, 8e-5};
  const Eigen::Matrix3d m = to_matrix(de, true);
  EXPECT_DOUBLE_EQ(m(0, 1), 2e-4); // tensor shear is half the engineering shear
  const auto back = from_matrix(m, true);
  for (std::size_t c = 0; c < 6; ++c) {
    EXPECT_DOUBLE_EQ(back[c], de[c]);
  }
}

} // namespace
} // namespace mpile
