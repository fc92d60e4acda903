#include "engine/particle_split.hpp"

namespace mpile {

namespace {

/// A domain longer than its cell by more than this fraction is split: a particle seeded one per
/// cell fills its cell exactly and is left alone, whatever the rounding of its size.
constexpr double slack = 1e-9;

/// The ratio of the particle's length to its cell's along r (0) or y (1).
double excess(const Particles& p, const Grid& grid, std::size_t i, int direction) {
  return direction == 0 ? 2.0 * p.half_r[i] / grid.r_axis().cell_size(p.cell_r[i])
                        : 2.0 * p.half_y[i] / grid.y_axis().cell_size(p.cell_y[i]);
}

/// A particle halves at most this often per direction: a cell 2^20 times smaller than the one it
/// was seeded for is not a grading but an input error the reader refuses long before.
constexpr int max_halvings = 20;

} // namespace

bool oversized(const Particles& p, const Grid& grid, std::size_t i) {
  return excess(p, grid, i, 0) > 1.0 + slack || excess(p, grid, i, 1) > 1.0 + slack;
}

std::vector<std::int32_t> split_oversized_particles(Particles& p, const Grid& grid,
                                                    GeometryMode mode) {
  std::vector<std::int32_t> parent_of_new;
  const bool axisymmetric = mode == GeometryMode::axisymmetric;
  // Appended halves are visited too (the loop runs to the growing end), so a particle that needs
  // several halvings gets them all in this call.
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int halving = 0; halving < 2 * max_halvings; ++halving) {
      const double along_r = excess(p, grid, i, 0);
      const double along_y = excess(p, grid, i, 1);
      if (along_r <= 1.0 + slack && along_y <= 1.0 + slack) {
        break;
      }
      const int direction = along_r >= along_y ? 0 : 1;
      std::vector<double>& position = direction == 0 ? p.r : p.y;
      std::vector<double>& reference = direction == 0 ? p.r0 : p.y0;
      std::vector<double>& half = direction == 0 ? p.half_r : p.half_y;
      const GradedAxis& axis = direction == 0 ? grid.r_axis() : grid.y_axis();
      const double d = 0.5 * half[i];
      const double minus = position[i] - d;
      const double plus = position[i] + d;
      const int cell_minus = axis.locate(minus);
      const int cell_plus = axis.locate(plus);
      if (cell_minus < 0 || cell_plus < 0 || (axisymmetric && direction == 0 && !(minus > 0.0))) {
        break; // at the grid's edge or the axis: left as it is
      }
      // Each half's share of the integration weight: its area's half, times its radius in
      // axisymmetry (where the weight is A r) when split along r.
      double share_minus = 0.5, share_plus = 0.5;
      if (axisymmetric && direction == 0) {
        share_minus = 0.5 * minus / position[i];
        share_plus = 0.5 * plus / position[i];
      }
      const std::size_t j = p.duplicate(i);
      parent_of_new.push_back(static_cast<std::int32_t>(i));
      const double mass = p.mass[i];
      const double volume = p.volume[i];
      p.mass[i] = share_minus * mass;
      p.mass[j] = share_plus * mass;
      p.volume[i] = share_minus * volume;
      p.volume[j] = share_plus * volume;
      position[i] = minus;
      position[j] = plus;
      const double reference_centre = reference[i];
      reference[i] = reference_centre - d;
      reference[j] = reference_centre + d;
      half[i] = d;
      half[j] = d;
      if (direction == 0) {
        p.cell_r[i] = cell_minus;
        p.cell_r[j] = cell_plus;
        if (axisymmetric) {
          // sum m r v_theta over the halves is m v_theta (r^2 + d^2) / r at an unchanged v_theta.
          const double r = 0.5 * (minus + plus);
          const double keep = r * r / (r * r + d * d);
          p.v_theta[i] *= keep;
          p.v_theta[j] *= keep;
        }
      } else {
        p.cell_y[i] = cell_minus;
        p.cell_y[j] = cell_plus;
      }
    }
  }
  return parent_of_new;
}

} // namespace mpile
