// A contact node's force split over the surfaces of its outline area (engine/structures/
// surface_split.hpp): one traction over each surface's share, so the parts add up to the node's
// force and each keeps the node's friction ratio.
#include "engine/structures/surface_split.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace mpile {
namespace {

using Force = std::array<double, 3>;
using Normal = std::array<double, 2>;

std::vector<Force> split_surface_force(const Force& f, const std::vector<double>& share,
                                       const std::vector<Normal>& normal, bool* solved = nullptr) {
  std::vector<Force> part(share.size());
  const bool ok = split_over_surfaces(f, share, normal, part);
  if (solved != nullptr) {
    *solved = ok;
  }
  return part;
}

TEST(SurfaceSplit, ASquareTipCornerOfEqualSharesGivesEachSurfaceItsOwnPressure) {
  // The inner tip corner of a pile: the tip faces down, the inner wall towards the axis. Soil
  // pressing with p over the node's area A pushes with p A / 2 on each half; the node's force is
  // their sum, p A / sqrt(2) along the mean normal. Turning each half of that force into its
  // surface's frame would give each p A / (2 sqrt(2)), 29 % short; the split gives p A / 2.
  const double pA = 1000.0;
  const Force f{-pA / 2.0, -pA / 2.0, 0.0};
  const auto part = split_surface_force(f, {0.5, 0.5}, {Normal{0.0, -1.0}, Normal{-1.0, 0.0}});
  EXPECT_NEAR(part[0][0], 0.0, 1e-12); // the tip: vertical only
  EXPECT_NEAR(part[0][1], -pA / 2.0, 1e-12);
  EXPECT_NEAR(part[1][0], -pA / 2.0, 1e-12); // the wall: radial only
  EXPECT_NEAR(part[1][1], 0.0, 1e-12);
}

TEST(SurfaceSplit, PartsAddUpToTheForceAndKeepTheNodesFrictionRatio) {
  // Uneven shares of two surfaces at 90, 120 and 60 degrees (a square corner, a cone's apex
  // region, a slanted tip), the node sliding at mu = 0.4 along the mean normal's tangent, with a
  // theta force: the parts add up to the force and each surface's tangential part is mu times its
  // normal part, to rounding (1e-12 relative: a few operations on numbers of order 1).
  const double mu = 0.4;
  for (const double angle : {M_PI / 2.0, 2.0 * M_PI / 3.0, M_PI / 3.0}) {
    for (const double s : {0.5, 0.2, 0.9}) {
      const std::vector<double> share{s, 1.0 - s};
      const std::vector<Normal> normal{Normal{0.0, -1.0},
                                       Normal{-std::sin(angle), -std::cos(angle)}};
      Normal mean{share[0] * normal[0][0] + share[1] * normal[1][0],
                  share[0] * normal[0][1] + share[1] * normal[1][1]};
      const double length = std::hypot(mean[0], mean[1]);
      const Normal n{mean[0] / length, mean[1] / length};
      const Normal t{-n[1], n[0]};
      const double fn = 3.0, ft = mu * fn;
      const Force f{fn * n[0] + ft * t[0], fn * n[1] + ft * t[1], 0.7};
      const auto part = split_surface_force(f, share, normal);
      for (std::size_t d = 0; d < 3; ++d) {
        EXPECT_NEAR(part[0][d] + part[1][d], f[d], 1e-12) << angle << " " << s << " " << d;
      }
      for (std::size_t q = 0; q < 2; ++q) {
        const Normal& m = normal[q];
        const double normal_part = part[q][0] * m[0] + part[q][1] * m[1];
        const double tangential_part = -part[q][0] * m[1] + part[q][1] * m[0];
        EXPECT_GT(normal_part, 0.0);
        EXPECT_NEAR(tangential_part / normal_part, mu, 1e-12) << angle << " " << s << " " << q;
        EXPECT_NEAR(part[q][2], share[q] * f[2], 1e-15);
      }
    }
  }
}

TEST(SurfaceSplit, OneSurfaceTakesTheWholeForce) {
  const Force f{3.0, -4.0, 0.5};
  const auto part = split_surface_force(f, {1.0}, {Normal{1.0, 0.0}});
  for (std::size_t d = 0; d < 3; ++d) {
    EXPECT_NEAR(part[0][d], f[d], 1e-15);
  }
}

TEST(SurfaceSplit, OpposedFacesSplitTheForceByShares) {
  // Both faces of a wall thinner than a cell on one node: the mean normal vanishes, no traction
  // is defined, and the parts are the shares of the force (still adding up to it).
  bool solved = true;
  const Force f{2.0, -1.0, 0.3};
  const auto part =
      split_surface_force(f, {0.5, 0.5}, {Normal{1.0, 0.0}, Normal{-1.0, 0.0}}, &solved);
  EXPECT_FALSE(solved);
  for (std::size_t d = 0; d < 3; ++d) {
    EXPECT_DOUBLE_EQ(part[0][d], 0.5 * f[d]);
    EXPECT_DOUBLE_EQ(part[1][d], 0.5 * f[d]);
  }
}

} // namespace
} // namespace mpile
