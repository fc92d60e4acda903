#pragma once

#include "engine/grid.hpp"
#include "engine/particles.hpp"

#include <algorithm>

namespace mpile {

/// How a particle reaches the grid (docs/design.md, "Shape functions").
///  - linear: the bilinear shape functions of the particle's cell at its centre (standard MPM).
///  - gimp: generalised interpolation (Bardenhagen & Kober 2004, uGIMP): the shape functions
///    averaged over the particle's domain, a rectangle of the size it was seeded with. Where the
///    domains tile the body, nodal forces are the exact integral of the piecewise-constant stress,
///    wherever the grid lines lie: a particle crossing a line changes them smoothly, not by a jump.
enum class ShapeFunctions { linear, gimp };

/// Nodes a particle reaches: its cell's 4, or 3 x 3 with GIMP (its domain may reach into one
/// neighbouring cell per direction).
constexpr int support_nodes(ShapeFunctions shape) {
  return shape == ShapeFunctions::linear ? 4 : 9;
}

/// Shape function values and gradients at a particle, node by node: `columns` node columns in r
/// by size / columns rows in y, node k = a + columns b. With GIMP a domain inside its cell along
/// an axis reaches two nodes of it, not three, so the passes loop over 4, 6 or 9 nodes and never
/// over weights that are exactly zero.
template <int count> struct NodeWeights {
  int size = count;
  int columns = count == 4 ? 2 : 3;
  int first_r; // the r index of the first node column (the theta gradient's cells)
  /// The first node of the whole support, 2 x 2 or 3 x 3 nodes, zero weights included: the nodes
  /// whose contact gaps a particle takes part in (for_each_support_node).
  int support_origin;
  int node[count];
  double N[count];
  double dN_dr[count];
  double dN_dy[count];
};
using CellWeights = NodeWeights<4>;

/// Bilinear shape functions of the cell (cr, cy) at a point, with their gradients. Nodes in the
/// order (cr, cy), (cr+1, cy), (cr, cy+1), (cr+1, cy+1).
inline CellWeights bilinear_weights(const Grid& grid, int cr, int cy, double r, double y) {
  const double inv_hr = grid.inverse_cell_size_r(cr);
  const double inv_hy = grid.inverse_cell_size_y(cy);
  const double xi = (r - grid.r_axis().node(cr)) * inv_hr;
  const double eta = (y - grid.y_axis().node(cy)) * inv_hy;
  const double nr[2] = {1.0 - xi, xi};
  const double ny[2] = {1.0 - eta, eta};
  const double dnr[2] = {-inv_hr, inv_hr};
  const double dny[2] = {-inv_hy, inv_hy};
  CellWeights w;
  w.first_r = cr;
  const int n0 = grid.node_index(cr, cy);
  w.support_origin = n0;
  const int nr_count = grid.nodes_r();
  for (int b = 0; b < 2; ++b) {
    for (int a = 0; a < 2; ++a) {
      const int k = a + 2 * b;
      w.node[k] = n0 + a + nr_count * b;
      w.N[k] = nr[a] * ny[b];
      w.dN_dr[k] = dnr[a] * ny[b];
      w.dN_dy[k] = nr[a] * dny[b];
    }
  }
  return w;
}

/// GIMP weights along one axis: nodes first, first + 1, first + 2. Those from first + lowest on,
/// `count` of them, may be nonzero; a domain inside its cell has one weight of exactly zero.
struct AxisWeights {
  int first;
  double S[3];
  double dS[3];
  int lowest = 0;
  int count = 3;
};

/// The weights of a domain of half-size l that a grid line splits into `left` (in the cell before
/// the line, of inverse size inverse_left) and `right` (in the cell after it): the means of the
/// three hats over the domain, and their slopes (N(x + l) - N(x - l)) / 2l.
inline void straddle(double left, double right, double inverse_left, double inverse_right, double l,
                     AxisWeights& w) {
  const double inverse_length = 0.5 / l;
  w.S[0] = 0.5 * left * left * inverse_left * inverse_length;
  w.S[2] = 0.5 * right * right * inverse_right * inverse_length;
  w.S[1] = 1.0 - w.S[0] - w.S[2];
  w.dS[0] = -left * inverse_left * inverse_length;
  w.dS[2] = right * inverse_right * inverse_length;
  w.dS[1] = -(w.dS[0] + w.dS[2]);
}

/// The hat functions of one axis averaged over [x - half, x + half], for a point x in cell c of an
/// axis of at least 2 cells. The half-size is first limited to half of the cells the domain can
/// reach and to the grid's extent, so the domain spans at most two cells and never leaves the
/// grid (then the weights sum to 1). A domain inside its cell gets the linear weights (the mean of
/// a linear function over an interval is its value at the centre); one that crosses a line gets
/// the closed-form means of the hats of the two cells it overlaps.
inline AxisWeights gimp_axis_weights(const GradedAxis& axis, int c, double x, double half) {
  const double lower = axis.node(c);
  const double upper = axis.node(c + 1);
  const double l = std::min({half, axis.domain_reach(c), x - axis.start(), axis.end() - x});
  const double h = upper - lower;
  const double inverse_h = 1.0 / h;
  AxisWeights w;
  if (x - l < lower) {
    // Nodes c - 1, c, c + 1: [x - l, lower] in cell c - 1, [lower, x + l] in cell c.
    w.first = c - 1;
    const double left = lower - (x - l);
    straddle(left, 2.0 * l - left, 1.0 / (lower - axis.node(c - 1)), inverse_h, l, w);
  } else if (x + l > upper) {
    // Nodes c, c + 1, c + 2: [x - l, upper] in cell c, [upper, x + l] in cell c + 1.
    w.first = c;
    const double right = x + l - upper;
    straddle(2.0 * l - right, right, inverse_h, 1.0 / (axis.node(c + 2) - upper), l, w);
  } else {
    // Inside the cell: nodes c, c + 1 as for linear, and a third node (inside the axis) with
    // weight 0.
    const double xi = (x - lower) * inverse_h;
    const bool last = c + 2 > axis.cell_count();
    w.first = last ? c - 1 : c;
    const int k = last ? 1 : 0;
    w.S[2 - 2 * k] = 0.0;
    w.dS[2 - 2 * k] = 0.0;
    w.S[k] = 1.0 - xi;
    w.S[k + 1] = xi;
    w.dS[k] = -inverse_h;
    w.dS[k + 1] = inverse_h;
    w.lowest = k;
    w.count = 2;
  }
  return w;
}

/// The GIMP weights of a particle with domain half-sizes (half_r, half_y): 2 or 3 node columns by
/// 2 or 3 rows, those of its support whose weights are not exactly zero. Node k = a + columns b is
/// (first_r + a, first_y + b).
inline NodeWeights<9> gimp_weights(const Grid& grid, int cr, int cy, double r, double y,
                                   double half_r, double half_y) {
  const AxisWeights wr = gimp_axis_weights(grid.r_axis(), cr, r, half_r);
  const AxisWeights wy = gimp_axis_weights(grid.y_axis(), cy, y, half_y);
  NodeWeights<9> w;
  w.first_r = wr.first + wr.lowest;
  w.columns = wr.count;
  w.size = wr.count * wy.count;
  w.support_origin = grid.node_index(wr.first, wy.first);
  const int n0 = grid.node_index(w.first_r, wy.first + wy.lowest);
  const int nr_count = grid.nodes_r();
  for (int b = 0; b < wy.count; ++b) {
    const double s_y = wy.S[wy.lowest + b];
    const double ds_y = wy.dS[wy.lowest + b];
    for (int a = 0; a < wr.count; ++a) {
      const int k = a + wr.count * b;
      w.node[k] = n0 + a + nr_count * b;
      w.N[k] = wr.S[wr.lowest + a] * s_y;
      w.dN_dr[k] = wr.dS[wr.lowest + a] * s_y;
      w.dN_dy[k] = wr.S[wr.lowest + a] * ds_y;
    }
  }
  return w;
}

/// Calls f(node) for each node of the whole support of weights w (2 x 2, or 3 x 3 with GIMP),
/// those of exactly zero weight included.
template <int count, class F>
inline void for_each_support_node(const Grid& grid, const NodeWeights<count>& w, F&& f) {
  constexpr int side = count == 4 ? 2 : 3;
  for (int b = 0; b < side; ++b) {
    for (int a = 0; a < side; ++a) {
      f(w.support_origin + a + grid.nodes_r() * b);
    }
  }
}

/// The weights of particle i for the chosen shape functions.
template <ShapeFunctions shape>
inline NodeWeights<support_nodes(shape)> particle_weights(const Grid& grid, const Particles& p,
                                                          std::size_t i) {
  if constexpr (shape == ShapeFunctions::linear) {
    return bilinear_weights(grid, p.cell_r[i], p.cell_y[i], p.r[i], p.y[i]);
  } else {
    return gimp_weights(grid, p.cell_r[i], p.cell_y[i], p.r[i], p.y[i], p.half_r[i], p.half_y[i]);
  }
}

} // namespace mpile
