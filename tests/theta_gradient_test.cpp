// The radial derivative of the angular velocity taken in s = 1/r^2 (engine/theta_gradient.hpp):
// exact for omega = A + B/r^2 (Couette flow) at any particle position, with bilinear weights and
// with GIMP domains that span two cells of different sizes; zero for a rigid spin to the last bit;
// and the slope in r in the cell on the axis.
#include "engine/theta_gradient.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace mpile {
namespace {

/// Cells of 0.05, 0.025 and 0.2 m in r from 0.2 m, so that GIMP domains reach cells of other sizes.
Grid annulus_grid() {
  const std::vector<AxisZone> r_zones = {{0.2, 0.4, 4}, {0.4, 0.5, 4}, {0.5, 1.1, 3}};
  const std::vector<AxisZone> y_zones = {{0.0, 0.4, 4}};
  return Grid(GradedAxis(r_zones), GradedAxis(y_zones));
}

template <int count, class Field>
double slope_of(const Grid& grid, const NodeWeights<count>& w, double r, Field omega_at) {
  // A GIMP domain inside its cell lists 4 or 6 nodes: only the first w.size entries are set.
  double omega[count] = {};
  for (int k = 0; k < w.size; ++k) {
    omega[k] = omega_at(grid.node_r(w.node[k]));
  }
  return radial_slope_in_s(grid.r_axis(), w, omega, r);
}

// Tolerance 1e-12 relative: the slope is a few products and quotients of nodal values that the
// closed form gives to rounding, against d(omega)/dr = -2B/r^3. The slope in r the engine took
// before is off by up to 3 h / (4 r) at a particle, 19 % in the first cell of this grid.
TEST(ThetaGradient, TheSlopeInSIsExactForCouetteFlowWhereverTheParticleSits) {
  const Grid grid = annulus_grid();
  constexpr double A = -0.01, B = 0.004;
  const auto couette = [&](double r) { return A + B / (r * r); };
  const auto rigid = [](double) { return 0.7; };
  const double y = 0.15, half_y = 0.0125;
  int straddling = 0;
  for (double r = 0.2001; r < 1.1; r += 0.00731) {
    const int cr = grid.r_axis().locate(r);
    const int cy = grid.y_axis().locate(y);
    const double exact = -2.0 * B / (r * r * r);
    const CellWeights linear = bilinear_weights(grid, cr, cy, r, y);
    EXPECT_NEAR(slope_of(grid, linear, r, couette) / exact, 1.0, 1e-12) << "linear, r = " << r;
    EXPECT_EQ(slope_of(grid, linear, r, rigid), 0.0) << "linear, r = " << r;
    for (const double half_r : {0.005, 0.0125, 0.03}) {
      const NodeWeights<9> gimp = gimp_weights(grid, cr, cy, r, y, half_r, half_y);
      straddling += gimp.columns == 3 ? 1 : 0;
      EXPECT_NEAR(slope_of(grid, gimp, r, couette) / exact, 1.0, 1e-12)
          << "GIMP, r = " << r << ", half-size " << half_r;
      EXPECT_EQ(slope_of(grid, gimp, r, rigid), 0.0) << "GIMP, r = " << r;
    }
  }
  EXPECT_GT(straddling, 20); // domains across a grid line were among them
}

TEST(ThetaGradient, TheCellOnTheAxisKeepsTheSlopeInR) {
  // s is infinite on the axis: there the slope is the plain one, exact for omega linear in r.
  const std::vector<AxisZone> r_zones = {{0.0, 0.4, 4}};
  const std::vector<AxisZone> y_zones = {{0.0, 0.4, 4}};
  const Grid grid{GradedAxis(r_zones), GradedAxis(y_zones)};
  const auto linear_in_r = [](double r) { return 0.3 + 2.0 * r; };
  for (const double r : {0.01, 0.05, 0.09}) {
    const CellWeights w = bilinear_weights(grid, 0, 1, r, 0.15);
    EXPECT_NEAR(slope_of(grid, w, r, linear_in_r), 2.0, 1e-12) << r;
  }
}

} // namespace
} // namespace mpile
