#pragma once

// The radial derivative of the angular velocity for gamma_rtheta = r d(omega)/dr (physics.md
// section 2, docs/design.md "Angular momentum on the grid"). Each cell's slope of omega is taken
// in s = 1/r^2 rather than in r: the nodal difference over the difference of s, times ds/dr =
// -2/r^3 at the particle. omega = A + B/r^2 is the torsional equilibrium of a field that varies
// in r alone (Couette flow between two cylinders, the soil around a twisted pile): linear in s,
// its slope in s is exact in every cell, where the slope in r times r_p put a saw-tooth of about
// (r_p / r_c)^3 - 1 on the particles of a cell (+-9 % at 8 cells from the axis). A constant omega
// (a rigid spin) has no slope in either variable.
#include "engine/graded_axis.hpp"
#include "engine/shape_functions.hpp"

namespace mpile {

/// The factor that turns a cell's slope of omega in r into its slope in s times ds/dr at r:
/// (h / (s_b - s_a)) (-2 / r^3) = 2 r_a^2 r_b^2 / (r^3 (r_a + r_b)), about 1 at the cell's
/// centre. The cell on the axis keeps the slope in r: s is infinite at its inner node (and omega
/// regular there has no 1/r^2 part).
inline double inverse_square_slope_factor(const GradedAxis& r_axis, int cell, double r) {
  const double r_a = r_axis.node(cell);
  if (!(r_a > 0.0)) {
    return 1.0;
  }
  const double r_b = r_axis.node(cell + 1);
  return 2.0 * (r_a * r_a) * (r_b * r_b) / (r * r * r * (r_a + r_b));
}

/// d(omega)/dr at a particle at radius r from the omegas of its nodes (in the weights' order),
/// with each cell's slope taken in s. The support's node columns are split into the cells
/// between them, each cell's part of sum_k dN_k/dr omega_k (sum over a row of its outer column's
/// dN/dr times the difference to the inner column) scaled by its own factor: exact for omega =
/// A + B/r^2 with GIMP too, where a particle's domain spans two cells (its gradient is then the
/// mean of the two cells' slopes, weighted by the share of the domain in each).
template <int count>
inline double radial_slope_in_s(const GradedAxis& r_axis, const NodeWeights<count>& w,
                                const double (&omega)[count], double r) {
  const int columns = w.columns;
  const int rows = w.size / columns;
  // The cell between columns 0 and 1: column 0's dN/dr is minus column 1's (minus columns 1 and
  // 2's with GIMP, the rest of which is the next cell's part).
  double left = 0.0;
  for (int b = 0; b < rows; ++b) {
    left += w.dN_dr[columns * b] * (omega[columns * b] - omega[columns * b + 1]);
  }
  double slope = inverse_square_slope_factor(r_axis, w.first_r, r) * left;
  if (columns == 3) {
    double right = 0.0;
    for (int b = 0; b < rows; ++b) {
      right += w.dN_dr[3 * b + 2] * (omega[3 * b + 2] - omega[3 * b + 1]);
    }
    slope += inverse_square_slope_factor(r_axis, w.first_r + 1, r) * right;
  }
  return slope;
}

} // namespace mpile
