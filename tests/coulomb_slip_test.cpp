// Coulomb friction at a contact node whose theta DOF has its own inertia (engine/coulomb_slip.hpp):
// the node sticks when the impulse that stops its slip is within the limit; a sliding node's
// friction impulse has the magnitude of the limit and opposes the slip left after it.
#include "engine/coulomb_slip.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mpile {
namespace {

TEST(CoulombSlip, SticksWithinTheLimit) {
  // Stopping both slips takes an impulse of hypot(2 * 0.3, 2.2 * 0.4) = 1.065 < 1.1.
  const SlipKept keep = coulomb_slip(0.3, 0.4, 2.0, 2.2, 1.1);
  EXPECT_EQ(keep.plane, 0.0);
  EXPECT_EQ(keep.theta, 0.0);
}

TEST(CoulombSlip, EqualInertiasKeepOneMinusTheLimitOverTheSlip) {
  // The isotropic rule: the slip keeps its direction and loses limit / m of its speed (round-off
  // only: one Newton step from the exact start).
  const double keep = 1.0 - 0.5 / (2.0 * 0.5);
  const SlipKept slip = coulomb_slip(0.3, 0.4, 2.0, 2.0, 0.5);
  EXPECT_NEAR(slip.plane, keep, 1e-15);
  EXPECT_NEAR(slip.theta, keep, 1e-15);
  // Frictionless: everything is kept.
  const SlipKept free = coulomb_slip(0.3, 0.4, 2.0, 3.0, 0.0);
  EXPECT_EQ(free.plane, 1.0);
  EXPECT_EQ(free.theta, 1.0);
}

TEST(CoulombSlip, UnequalInertiasGiveTheLimitOpposingTheSlipLeft) {
  // Theta inertia 10 % above the mass (soil beside the outer wall of a pile): the friction impulse
  // F_d = m_d (t_d - s_d) must have magnitude `limit` and be parallel to the slip s left after it
  // (maximal dissipation), to rounding (the Newton iterates stop at it).
  const double m = 2.0, m_theta = 2.2, limit = 0.5;
  for (const auto& [t_plane, t_theta] :
       {std::pair{0.3, 0.4}, std::pair{0.05, 0.6}, std::pair{0.6, 0.05}, std::pair{0.0, 0.5}}) {
    const SlipKept keep = coulomb_slip(t_plane, t_theta, m, m_theta, limit);
    const double s_plane = keep.plane * t_plane, s_theta = keep.theta * t_theta;
    const double f_plane = m * (t_plane - s_plane), f_theta = m_theta * (t_theta - s_theta);
    EXPECT_NEAR(std::hypot(f_plane, f_theta), limit, 1e-14 * limit);
    EXPECT_NEAR(f_plane * s_theta - f_theta * s_plane, 0.0, 1e-14 * limit) << "not parallel";
    EXPECT_GT(s_plane * t_plane + s_theta * t_theta, 0.0) << "the slip turned back";
  }
}

} // namespace
} // namespace mpile
