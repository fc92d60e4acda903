#pragma once

#include "engine/grid.hpp"

namespace mpile {

/// Bilinear shape functions of the cell (cr, cy) at a point, with their gradients. Nodes in the
/// order (cr, cy), (cr+1, cy), (cr, cy+1), (cr+1, cy+1).
struct CellWeights {
  int node[4];
  double N[4];
  double dN_dr[4];
  double dN_dy[4];
};

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
  const int n0 = grid.node_index(cr, cy);
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

} // namespace mpile
