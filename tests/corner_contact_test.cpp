// Contact at a corner of two surfaces (engine/corner_contact.hpp): the projection of the soil's
// relative velocity on the admissible cone, against the cases worked by hand and against the
// projection theorem on random corners.
#include "engine/corner_contact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace mpile {
namespace {

// A pile tip's outer corner: the tip faces down, the outer shaft outwards.
constexpr std::array<double, 2> tip{0.0, -1.0};
constexpr std::array<double, 2> outer{1.0, 0.0};

TEST(CornerContact, SoilUnderTheTipMovesWithItWhereTheMeanNormalLeftHalfItsLag) {
  // The pile moves down 0.3 m/s faster than the soil under its corner: relative velocity of the
  // soil (0, 0.3). Held by the tip alone, it keeps no lag at all.
  const CornerProjection p = project_on_corner({0.0, 0.3}, tip, outer);
  EXPECT_EQ(p.active, CornerActive::first);
  EXPECT_EQ(p.velocity[0], 0.0);
  EXPECT_EQ(p.velocity[1], 0.0);
  // The mean normal (1, -1) / sqrt 2 removes only the approach along it, which leaves (0.15,
  // 0.15): half the lag, and as much sliding outwards.
  const double m = 1.0 / std::sqrt(2.0);
  const double approach = 0.3 * -m;
  EXPECT_NEAR(0.0 - approach * m, 0.15, 1e-15);
  EXPECT_NEAR(0.3 + approach * m, 0.15, 1e-15);
}

TEST(CornerContact, HandWorkedCases) {
  // Approaching both (inwards and up): held by both, no relative motion in r-y.
  CornerProjection p = project_on_corner({-0.2, 0.3}, tip, outer);
  EXPECT_EQ(p.active, CornerActive::both);
  EXPECT_EQ(p.velocity[0], 0.0);
  EXPECT_EQ(p.velocity[1], 0.0);
  // Approaching the tip while moving outwards: slides out along the tip.
  p = project_on_corner({0.2, 0.3}, tip, outer);
  EXPECT_EQ(p.active, CornerActive::first);
  EXPECT_DOUBLE_EQ(p.velocity[0], 0.2);
  EXPECT_EQ(p.velocity[1], 0.0);
  // Approaching the shaft while moving down past it: slides along the shaft.
  p = project_on_corner({-0.2, -0.1}, tip, outer);
  EXPECT_EQ(p.active, CornerActive::second);
  EXPECT_EQ(p.velocity[0], 0.0);
  EXPECT_DOUBLE_EQ(p.velocity[1], -0.1);
  // At rest against the corner, or sliding along one surface without leaving it: in contact
  // (friction and adhesion act), nothing to remove.
  p = project_on_corner({0.0, 0.0}, tip, outer);
  EXPECT_EQ(p.active, CornerActive::both);
  p = project_on_corner({0.3, 0.0}, tip, outer);
  EXPECT_EQ(p.active, CornerActive::first);
  EXPECT_DOUBLE_EQ(p.velocity[0], 0.3);
  p = project_on_corner({0.0, -0.3}, tip, outer);
  EXPECT_EQ(p.active, CornerActive::second);
  // Leaving both: unchanged.
  p = project_on_corner({0.1, -0.1}, tip, outer);
  EXPECT_EQ(p.active, CornerActive::none);
  EXPECT_DOUBLE_EQ(p.velocity[0], 0.1);
  EXPECT_DOUBLE_EQ(p.velocity[1], -0.1);
}

TEST(CornerContact, ProjectionTheoremOnRandomCorners) {
  // v is the projection of u on the closed convex cone K = {w : n1 . w >= 0, n2 . w >= 0} exactly
  // when v is in K, (u - v) . v = 0 and (u - v) . w <= 0 for every w in K, that is for the two
  // rays that span K (Moreau). Corners of every opening between 1 and 179 degrees.
  std::mt19937_64 random(12345);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
  std::uniform_real_distribution<double> opening(std::numbers::pi / 180.0,
                                                 179.0 * std::numbers::pi / 180.0);
  std::normal_distribution<double> component(0.0, 1.0);
  int both = 0;
  for (int k = 0; k < 20000; ++k) {
    const double a = angle(random);
    const double b = a + opening(random); // n2 turned from n1 by less than pi: a convex corner
    const std::array<double, 2> n1{std::cos(a), std::sin(a)};
    const std::array<double, 2> n2{std::cos(b), std::sin(b)};
    const std::array<double, 2> u{component(random), component(random)};
    const CornerProjection p = project_on_corner(u, n1, n2);
    const auto dot = [](const std::array<double, 2>& x, const std::array<double, 2>& y) {
      return x[0] * y[0] + x[1] * y[1];
    };
    // The rays of K: perpendicular to n1 on n2's side, and to n2 on n1's side.
    std::array<double, 2> ray1{-n1[1], n1[0]};
    if (dot(ray1, n2) < 0.0) {
      ray1 = {n1[1], -n1[0]};
    }
    std::array<double, 2> ray2{-n2[1], n2[0]};
    if (dot(ray2, n1) < 0.0) {
      ray2 = {n2[1], -n2[0]};
    }
    const std::array<double, 2> residual{u[0] - p.velocity[0], u[1] - p.velocity[1]};
    constexpr double tolerance = 1e-12; // rounding of unit-sized velocities
    EXPECT_GE(dot(p.velocity, n1), -tolerance) << k;
    EXPECT_GE(dot(p.velocity, n2), -tolerance) << k;
    EXPECT_NEAR(dot(residual, p.velocity), 0.0, tolerance) << k;
    EXPECT_LE(dot(residual, ray1), tolerance) << k;
    EXPECT_LE(dot(residual, ray2), tolerance) << k;
    both += p.active == CornerActive::both ? 1 : 0;
  }
  EXPECT_GT(both, 1000); // the apex was reached often enough to be tested
}

TEST(CornerContact, ACornerForceSplitsAlongTheTwoNormals) {
  const std::array<double, 2> n1{std::cos(0.3), std::sin(0.3)};
  const std::array<double, 2> n2{std::cos(1.9), std::sin(1.9)};
  const auto [a, b] = split_on_normals({2.0, -0.5}, n1, n2);
  EXPECT_NEAR(a * n1[0] + b * n2[0], 2.0, 1e-14);
  EXPECT_NEAR(a * n1[1] + b * n2[1], -0.5, 1e-14);
  // The pile tip's corner: a push up and inwards is a tip force and a shaft force.
  const auto [t, s] = split_on_normals({-3.0, 4.0}, tip, outer);
  EXPECT_DOUBLE_EQ(t, -4.0);
  EXPECT_DOUBLE_EQ(s, -3.0);
}

} // namespace
} // namespace mpile
