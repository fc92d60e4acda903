// GIMP shape functions (engine/shape_functions.hpp) against an independent quadrature of the
// grid's hat functions over the particle's domain, on a graded axis; their properties (partition
// of unity, reproduction of x, gradients that are the derivatives of the weights); and the reason
// they exist: the nodal force of a piecewise-constant stress does not depend on where the grid
// lines lie.
#include "engine/shape_functions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

namespace mpile {
namespace {

/// A graded axis with cells of 0.1, 0.05 and 0.2 m, so that domains reach cells of other sizes.
GradedAxis graded() {
  const std::vector<AxisZone> zones = {{0.0, 0.4, 4}, {0.4, 0.6, 4}, {0.6, 1.2, 3}};
  return GradedAxis(zones);
}

/// The hat function of node j of the axis at x.
double hat(const GradedAxis& axis, int j, double x) {
  if (j > 0 && x >= axis.node(j - 1) && x <= axis.node(j)) {
    return (x - axis.node(j - 1)) / axis.cell_size(j - 1);
  }
  if (j < axis.cell_count() && x >= axis.node(j) && x <= axis.node(j + 1)) {
    return (axis.node(j + 1) - x) / axis.cell_size(j);
  }
  return 0.0;
}

/// The mean of node j's hat over [x - l, x + l] by the midpoint rule with many panels (the hat
/// is piecewise linear, so the error is only at its two or three kinks: O(1 / panels^2)).
double mean_hat(const GradedAxis& axis, int j, double x, double l) {
  constexpr int panels = 20000;
  double sum = 0.0;
  for (int k = 0; k < panels; ++k) {
    sum += hat(axis, j, x - l + (k + 0.5) * 2.0 * l / panels);
  }
  return sum / panels;
}

TEST(GimpShapeFunctions, WeightsAreTheHatsMeanOverTheDomain) {
  const GradedAxis axis = graded();
  // Points in each zone, domains within a cell and across a line into a finer or coarser cell.
  const double points[][2] = {{0.13, 0.02},  {0.105, 0.025}, {0.39, 0.02}, {0.41, 0.012},
                              {0.595, 0.02}, {0.61, 0.02},   {0.9, 0.05}};
  for (const auto& [x, l] : points) {
    const int c = axis.locate(x);
    const AxisWeights w = gimp_axis_weights(axis, c, x, l);
    double sum = 0.0;
    double first_moment = 0.0;
    for (int m = 0; m < 3; ++m) {
      const int j = w.first + m;
      // The quadrature's error is below 1e-8 of a weight; the closed form is exact to rounding.
      EXPECT_NEAR(w.S[m], mean_hat(axis, j, x, l), 1e-8) << "x = " << x << ", node " << j;
      // Gradient: the derivative of the weight with the point (central difference, h = 1e-7;
      // the weights are quadratic in x, so the difference is exact but for rounding, ~1e-8).
      const double h = 1e-7;
      const double slope =
          (gimp_axis_weights(axis, c, x + h, l).S[m] - gimp_axis_weights(axis, c, x - h, l).S[m]) /
          (2.0 * h);
      EXPECT_NEAR(w.dS[m], slope, 1e-6 / l) << "x = " << x << ", node " << j;
      sum += w.S[m];
      first_moment += w.S[m] * axis.node(j);
    }
    EXPECT_NEAR(sum, 1.0, 1e-14) << "x = " << x;         // partition of unity
    EXPECT_NEAR(first_moment, x, 1e-14) << "x = " << x;  // linear completeness
    EXPECT_NEAR(w.dS[0] + w.dS[1] + w.dS[2], 0.0, 1e-9); // rigid translation strains nothing
  }
}

// The particle passes loop over the nodes gimp_weights lists, which leaves out those of exactly
// zero weight: every node of the 3 x 3 support that it leaves out must have the hats' mean zero
// (quadrature, as above), every node it lists must carry the mean, and a domain inside its cell
// must list its cell's 4 nodes alone. Points all over a graded grid, domains of several sizes,
// the first and last cells included.
TEST(GimpShapeFunctions, TheListedNodesAreExactlyThoseThatWeigh) {
  const Grid grid{graded(), graded()};
  const GradedAxis& axis = grid.r_axis();
  int sizes[10] = {};
  for (double r = 0.004; r < 1.2; r += 0.0617) {
    for (double y = 0.006; y < 1.2; y += 0.0819) {
      for (const double half : {0.004, 0.0125, 0.03}) {
        const int cr = axis.locate(r);
        const int cy = axis.locate(y);
        const NodeWeights<9> w = gimp_weights(grid, cr, cy, r, y, half, half);
        ASSERT_TRUE(w.size == 4 || w.size == 6 || w.size == 9);
        ++sizes[w.size];
        // The listed nodes: columns from first_r, and the weights the quadrature gives.
        const double l_r = std::min({half, axis.domain_reach(cr), r, axis.end() - r});
        const double l_y = std::min({half, axis.domain_reach(cy), y, axis.end() - y});
        double listed_sum = 0.0;
        for (int k = 0; k < w.size; ++k) {
          const int nr = w.node[k] % grid.nodes_r();
          const int ny = w.node[k] / grid.nodes_r();
          EXPECT_EQ(nr, w.first_r + k % w.columns);
          EXPECT_NEAR(w.N[k], mean_hat(axis, nr, r, l_r) * mean_hat(axis, ny, y, l_y), 1e-8);
          listed_sum += w.N[k];
        }
        // Partition of unity over the listed nodes alone: nothing that weighs is left out.
        EXPECT_NEAR(listed_sum, 1.0, 1e-14) << r << ", " << y;
        // Inside its cell in both directions: exactly the cell's 4 nodes, the bilinear weights.
        const bool inside = r - half >= axis.node(cr) && r + half <= axis.node(cr + 1) &&
                            y - half >= axis.node(cy) && y + half <= axis.node(cy + 1);
        if (inside) {
          const CellWeights bilinear = bilinear_weights(grid, cr, cy, r, y);
          ASSERT_EQ(w.size, 4);
          for (int k = 0; k < 4; ++k) {
            EXPECT_EQ(w.node[k], bilinear.node[k]);
            EXPECT_NEAR(w.N[k], bilinear.N[k], 1e-15);
          }
        }
      }
    }
  }
  // Each kind of support occurred.
  EXPECT_GT(sizes[4], 0);
  EXPECT_GT(sizes[6], 0);
  EXPECT_GT(sizes[9], 0);
}

TEST(GimpShapeFunctions, DomainsAreKeptInsideTheGridAndWithinTwoCells) {
  const GradedAxis axis = graded();
  // A point 0.01 m from the grid's start with a 0.03 m half-size: the domain is cut to 0.01 m,
  // so the weights still sum to 1 and nothing reaches beyond the first node.
  const AxisWeights near_start = gimp_axis_weights(axis, 0, 0.01, 0.03);
  EXPECT_EQ(near_start.first, 0);
  EXPECT_NEAR(near_start.S[0] + near_start.S[1] + near_start.S[2], 1.0, 1e-14);
  EXPECT_NEAR(near_start.S[0], mean_hat(axis, 0, 0.01, 0.01), 1e-8);
  // The last cell: the three nodes stay inside the axis.
  const AxisWeights at_end = gimp_axis_weights(axis, axis.cell_count() - 1, 1.15, 0.05);
  EXPECT_EQ(at_end.first + 2, axis.node_count() - 1);
  EXPECT_NEAR(at_end.S[0], 0.0, 1e-15);
  // A domain larger than half of a neighbouring cell (0.06 m next to 0.05 m cells) is cut to
  // half of it (0.025 m), so it spans two cells at most.
  const AxisWeights big = gimp_axis_weights(axis, axis.locate(0.38), 0.38, 0.06);
  EXPECT_NEAR(big.S[0] + big.S[1] + big.S[2], 1.0, 1e-14);
  EXPECT_NEAR(big.S[1], mean_hat(axis, big.first + 1, 0.38, 0.025), 1e-8);
  // A domain of zero size gives the bilinear weights.
  const AxisWeights point = gimp_axis_weights(axis, 1, 0.13, 0.0);
  EXPECT_EQ(point.first, 1);
  EXPECT_NEAR(point.S[0], 0.7, 1e-14);
  EXPECT_NEAR(point.dS[1], 10.0, 1e-12);
}

// Why GIMP: particles that tile a bar carry a stress sigma(x) = x (piecewise constant over their
// domains). With GIMP the force at an interior node is the exact integral -int sigma N' dx of that
// piecewise-constant field, whatever the offset of the grid under the particles; bilinear weights
// at the particle centres give a force that jumps as a particle crosses a line.
TEST(GimpShapeFunctions, NodalForceOfATiledStressDoesNotDependOnTheGridPosition) {
  // 2.86 particles per 0.05 m cell: the bar was seeded for cells of 0.035 m (a moving mesh's
  // squeezed zone, docs/design.md) and the grid now has cells of 0.05 m.
  const int particles = 57;
  const double size = 0.0175;
  auto nodal_force = [&](double shift, bool gimp) {
    const GradedAxis axis = GradedAxis::uniform(-0.5 + shift, 1.5 + shift, 40);
    const int node = 20; // at x = 0.5 + shift
    double force = 0.0;
    for (int k = 0; k < particles; ++k) {
      const double x = (k + 0.5) * size;
      const double sigma = x;
      const int c = axis.locate(x);
      const AxisWeights w = gimp_axis_weights(axis, c, x, gimp ? 0.5 * size : 0.0);
      for (int m = 0; m < 3; ++m) {
        if (w.first + m == node) {
          force -= size * sigma * w.dS[m];
        }
      }
    }
    return force;
  };
  // Exact: -int sigma N' over the particles' piecewise-constant field; N' = 20 on the 0.05 m to
  // the left of the node and -20 on the right, and each particle's sigma is its centre's x.
  auto exact = [&](double shift) {
    const double node = 0.5 + shift;
    double force = 0.0;
    for (int k = 0; k < particles; ++k) {
      const double lo = k * size;
      const double hi = lo + size;
      const double sigma = lo + 0.5 * size;
      const double left = std::max(0.0, std::min(hi, node) - std::max(lo, node - 0.05));
      const double right = std::max(0.0, std::min(hi, node + 0.05) - std::max(lo, node));
      force -= sigma * (20.0 * left - 20.0 * right);
    }
    return force;
  };
  double gimp_min = 1e300;
  double gimp_max = -1e300;
  double linear_spread_min = 1e300;
  double linear_spread_max = -1e300;
  for (int step = 0; step <= 50; ++step) {
    const double shift = 0.001 * step; // the grid slides over 1 mm steps across a whole cell
    EXPECT_NEAR(nodal_force(shift, true), exact(shift), 1e-12) << "shift " << shift;
    gimp_min = std::min(gimp_min, nodal_force(shift, true));
    gimp_max = std::max(gimp_max, nodal_force(shift, true));
    linear_spread_min = std::min(linear_spread_min, nodal_force(shift, false));
    linear_spread_max = std::max(linear_spread_max, nodal_force(shift, false));
  }
  // The force of the field sigma = x itself is 0.05 (its slope times the support's 0.05 m, times
  // N' = 20 over 0.05 m). The piecewise-constant field differs from it only in the domains cut
  // where N' jumps (by 20 at the support's ends, 40 at the node): at most 20 (l^2 / 2) per end
  // and 40 (l^2 / 2) at the node with l = 0.00875, 0.0031 in all. Measured: 0.04988 to 0.05075.
  EXPECT_GT(gimp_min, 0.05 - 0.0031);
  EXPECT_LT(gimp_max, 0.05 + 0.0031);
  // Bilinear weights at the centres: -0.150 to 0.230 over the same shifts, an error four times
  // the force itself, jumping as particles cross the lines (the cell-crossing error).
  EXPECT_GT(linear_spread_max - linear_spread_min, 0.3);
  std::cout << "nodal force, exact field 0.05: GIMP " << gimp_min << " to " << gimp_max
            << ", bilinear " << linear_spread_min << " to " << linear_spread_max << '\n';
}

} // namespace
} // namespace mpile
