// The verification cases of docs/verification.md, each against its closed form. Every check carries
// the tolerance of the reference table (../shared/docs/verification.md); the patch tests must be
// exact to rounding and are held to that.
#include "cases/verification/verification_cases.hpp"

#include <gtest/gtest.h>

namespace mpile::verification {
namespace {

void expect_within_tolerance(const Report& report) {
  ASSERT_FALSE(report.checks.empty());
  for (const Check& check : report.checks) {
    EXPECT_LE(check.error(), check.tolerance)
        << report.id << ": " << check.quantity << " = " << check.measured << " " << check.unit
        << ", reference " << check.reference;
  }
}

const Check& check_named(const Report& report, const std::string& prefix) {
  for (const Check& check : report.checks) {
    if (check.quantity.rfind(prefix, 0) == 0) {
      return check;
    }
  }
  throw std::out_of_range("no check " + prefix + " in " + report.id);
}

TEST(Verification, VHSHardeningSoilOedometerFollowsItsElementTest) {
  // Homogeneous oedometric loading of the seed's sand in a full run: every particle must follow
  // the single-point path (tolerances 1 % of the stress increment, in the case).
  expect_within_tolerance(run_hs_oedometer({}));
}

TEST(Verification, V1VibratingBar) {
  expect_within_tolerance(run_vibrating_bar({}));
}

TEST(Verification, V2SinglePoint) {
  expect_within_tolerance(run_single_point({}));
  // One point in one cell is the case: a refinement leaves it as it is (with two cells the period
  // would be 29 % off).
  Options refined;
  refined.refinement = 2;
  refined.particles_per_direction = 2;
  const Report again = run_single_point(refined);
  expect_within_tolerance(again);
  EXPECT_EQ(again.particles, 1u);
}

TEST(Verification, V3LameCylinder) {
  expect_within_tolerance(run_lame_cylinder({}));
}

TEST(Verification, V4RadialPatchIsExactWithAndWithoutBbar) {
  for (const bool bbar : {true, false}) {
    Options options;
    options.bbar = bbar;
    const Report report = run_radial_patch(options);
    expect_within_tolerance(report);
    // A linear field is reproduced exactly by bilinear shape functions, on the axis too: only
    // rounding remains (relative 1e-16 per step over ~50 steps).
    for (const Check& check : report.checks) {
      EXPECT_LT(check.error(), 1e-12)
          << check.quantity << (bbar ? " with" : " without") << " B-bar";
    }
  }
}

TEST(Verification, V4PlaneStrainPatchIsExactWithAndWithoutBbar) {
  for (const bool bbar : {true, false}) {
    Options options;
    options.bbar = bbar;
    const Report report = run_plane_strain_patch(options);
    expect_within_tolerance(report);
    EXPECT_LT(report.checks.at(0).error(), 1e-12) << (bbar ? "with" : "without") << " B-bar";
  }
}

TEST(Verification, V5UniaxialCylinder) {
  expect_within_tolerance(run_uniaxial_cylinder({}));
}

TEST(Verification, V6ShaftTorsion) {
  expect_within_tolerance(run_shaft_torsion({}));
}

// V6c: a torsional field that varies across the cells (omega = A + B/r^2). Tolerances (in the
// case): every particle's tau_rtheta within 1 % of -2 G B/r^2 and the inner face's torque within
// 0.1 %. The theta gradient taken in s = 1/r^2 is exact for this field and the torque row
// integrates r^2 tau_rtheta, a constant here, exactly at any particle positions, so what is left
// is the relaxation's 1e-9 (measured: torque 2e-8, shear 3e-9, the same with both shape
// functions, whose domains here lie inside their cells). Taken in r, the gradient put a saw-tooth
// of about (r_p / r_c)^3 - 1 on the particles of each cell: -8.3 % and +9.5 % at r = 0.21, a torque
// 0.59 % high (docs/verification.md, V6c).
TEST(Verification, V6cElasticCouetteWithLinearShapeFunctions) {
  Options options;
  options.shape_functions = ShapeFunctions::linear;
  expect_within_tolerance(run_elastic_couette(options));
}

TEST(Verification, V6cElasticCouetteWithGimp) {
  Options options;
  options.shape_functions = ShapeFunctions::gimp;
  expect_within_tolerance(run_elastic_couette(options));
}

TEST(Verification, V8SelfWeightColumn) {
  expect_within_tolerance(run_self_weight_column({}));
}

TEST(Verification, V8K0StateStaysPut) {
  expect_within_tolerance(run_k0_column({}));
}

// Nearly incompressible elasticity (nu = 0.49). The Lame cylinder has a non-uniform volumetric
// field that bilinear cells cannot follow without B-bar (volumetric locking); with B-bar it must
// stay within the V3 tolerance of 2 %. Without B-bar the hoop stress is far off (measured: 78 %
// worst particle, 13 % at the inner face); the test asserts that the difference is visible.
TEST(Verification, BbarRemovesVolumetricLockingInTheNearlyIncompressibleLameCylinder) {
  Options options;
  options.poisson_ratio = 0.49;
  options.bbar = true;
  const Report with_bbar = run_lame_cylinder(options);
  expect_within_tolerance(with_bbar);
  options.bbar = false;
  const Report without_bbar = run_lame_cylinder(options);
  EXPECT_GT(check_named(without_bbar, "max sigma_thth error").error(), 0.2);
  EXPECT_GT(check_named(without_bbar, "sigma_thth(a)").error(), 0.05);
}

// V5 with nu = 0.49: between smooth platens the exact state is homogeneous, which bilinear cells
// represent exactly, so there is nothing to lock: both variants must meet the 1 % tolerance.
TEST(Verification, V5NearlyIncompressibleIsWithinOnePercentWithAndWithoutBbar) {
  for (const bool bbar : {true, false}) {
    Options options;
    options.poisson_ratio = 0.49;
    options.bbar = bbar;
    expect_within_tolerance(run_uniaxial_cylinder(options));
  }
}

} // namespace
} // namespace mpile::verification
