// Coulomb friction at a contact node whose theta DOF has its own inertia, and the contact law
// built on it (engine/structures/coulomb_slip.hpp):
// the node sticks when the impulse that stops its slip is within the limit; a sliding node's
// friction impulse has the magnitude of the limit and opposes the slip left after it.
#include "engine/structures/coulomb_slip.hpp"

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

// The whole law at a node (contact_correction): a shaft node whose normal is (1, 0) into the
// soil; relative velocity of the soil (approaching at 0.2 m/s, slipping 0.3 m/s down and 0.4 m/s
// round).

TEST(ContactLaw, FrictionlessRemovesTheApproachOnly) {
  const ContactCorrection c = contact_correction({-0.2, -0.3, 0.4}, {1.0, 0.0}, 2.0, 2.2, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(c.change[0], 0.2);
  EXPECT_EQ(c.change[1], 0.0);
  EXPECT_EQ(c.change[2], 0.0);
}

TEST(ContactLaw, StickingRemovesTheWholeRelativeVelocity) {
  // mu = 10: the limit 10 * 2 * 0.2 = 4 exceeds the impulse that stops both slips (1.065).
  const ContactCorrection c =
      contact_correction({-0.2, -0.3, 0.4}, {1.0, 0.0}, 2.0, 2.2, 10.0, 0.0);
  EXPECT_EQ(c.keep.plane, 0.0);
  EXPECT_EQ(c.keep.theta, 0.0);
  EXPECT_DOUBLE_EQ(c.change[0], 0.2);
  EXPECT_DOUBLE_EQ(c.change[1], 0.3);
  EXPECT_DOUBLE_EQ(c.change[2], -0.4);
}

TEST(ContactLaw, SlidingFrictionAndAdhesionGiveTheLimitAsTheTangentialImpulse) {
  // mu = 0.4 on the normal impulse 2 * 0.2 = 0.4, plus an adhesive impulse of 0.05: the tangential
  // impulse m dv_t (r-y with m = 2, theta with 2.2) has magnitude 0.16 + 0.05 = 0.21, to rounding.
  const double m = 2.0, m_theta = 2.2;
  const ContactCorrection c =
      contact_correction({-0.2, -0.3, 0.4}, {1.0, 0.0}, m, m_theta, 0.4, 0.05);
  EXPECT_DOUBLE_EQ(c.change[0], 0.2);
  EXPECT_NEAR(std::hypot(m * c.change[1], m_theta * c.change[2]), 0.21, 1e-14);
  EXPECT_GT(c.keep.plane, 0.0);
  // Adhesion alone acts on soil at rest in the normal direction.
  const ContactCorrection a =
      contact_correction({0.0, -0.3, 0.0}, {1.0, 0.0}, m, m_theta, 0.4, 0.05);
  EXPECT_EQ(a.change[0], 0.0);
  EXPECT_NEAR(m * a.change[1], 0.05, 1e-15);
}

} // namespace
} // namespace mpile
