#include "engine/boundary_conditions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mpile {

std::vector<int> nodes_on_r_line(const Grid& grid, int ir, double y_from, double y_to) {
  std::vector<int> nodes;
  for (int iy = 0; iy < grid.nodes_y(); ++iy) {
    const double y = grid.y_axis().node(iy);
    if (y >= y_from && y <= y_to) {
      nodes.push_back(grid.node_index(ir, iy));
    }
  }
  return nodes;
}

std::vector<int> nodes_on_y_line(const Grid& grid, int iy, double r_from, double r_to) {
  std::vector<int> nodes;
  for (int ir = 0; ir < grid.nodes_r(); ++ir) {
    const double r = grid.r_axis().node(ir);
    if (r >= r_from && r <= r_to) {
      nodes.push_back(grid.node_index(ir, iy));
    }
  }
  return nodes;
}

std::vector<int> nodes_on_face(const Grid& grid, GridFace face) {
  const double inf = std::numeric_limits<double>::infinity();
  switch (face) {
  case GridFace::r_min:
    return nodes_on_r_line(grid, 0, -inf, inf);
  case GridFace::r_max:
    return nodes_on_r_line(grid, grid.nodes_r() - 1, -inf, inf);
  case GridFace::y_min:
    return nodes_on_y_line(grid, 0, -inf, inf);
  case GridFace::y_max:
    return nodes_on_y_line(grid, grid.nodes_y() - 1, -inf, inf);
  }
  return {};
}

NodeConstraint face_constraint(const Grid& grid, GeometryMode mode, GridFace face,
                               FaceCondition condition) {
  static const char* face_names[] = {"r_min", "r_max", "y_min", "y_max"};
  NodeConstraint c;
  c.name = face_names[static_cast<int>(face)];
  c.nodes = nodes_on_face(grid, face);
  const std::uint8_t normal = (face == GridFace::r_min || face == GridFace::r_max) ? DOF_R : DOF_Y;
  // On the axis v_theta = r omega is zero by construction; holding theta there would hold the
  // angular velocity and stop the cells beside the axis from turning rigidly.
  const bool axis = face == GridFace::r_min && grid.r_axis().start() == 0.0;
  const std::uint8_t all = has_theta(mode) && !axis ? DOF_R | DOF_Y | DOF_THETA : DOF_R | DOF_Y;
  switch (condition) {
  case FaceCondition::free:
    c.dofs = 0;
    break;
  case FaceCondition::roller:
    c.dofs = normal;
    break;
  case FaceCondition::fixed:
    c.dofs = all;
    break;
  }
  return c;
}

NodeConstraint axis_constraint(const Grid& grid) {
  NodeConstraint c;
  c.name = "axis";
  c.nodes = nodes_on_face(grid, GridFace::r_min);
  c.dofs = DOF_R; // u_theta = r omega is zero there by construction
  return c;
}

NodalLoad line_load(const Grid& grid, GeometryMode mode, const std::vector<int>& nodes,
                    int component, TimeFunction traction, std::string name) {
  NodalLoad load;
  load.name = std::move(name);
  load.nodes = nodes;
  load.component = component;
  load.traction = std::move(traction);
  load.weight.assign(nodes.size(), 0.0);
  const bool axisymmetric = mode == GeometryMode::axisymmetric;
  // Consistent load of each segment between consecutive nodes: for a linear N, the integral of
  // N_a r over the segment is L (2 r_a + r_b) / 6 (L / 2 without the r weight). A theta load
  // does work on v_theta = r omega: its torque weight is the integral of N_a r^2, with
  // d = r_b - r_a that is L (r_a^2 / 2 + r_a d / 3 + d^2 / 12).
  for (std::size_t k = 1; k < nodes.size(); ++k) {
    const double ra = grid.node_r(nodes[k - 1]);
    const double rb = grid.node_r(nodes[k]);
    const double length = std::hypot(rb - ra, grid.node_y(nodes[k]) - grid.node_y(nodes[k - 1]));
    if (axisymmetric && component == 2) {
      const double d = rb - ra;
      load.weight[k - 1] += length * (ra * ra / 2.0 + ra * d / 3.0 + d * d / 12.0);
      load.weight[k] += length * (rb * rb / 2.0 - rb * d / 3.0 + d * d / 12.0);
    } else if (axisymmetric) {
      load.weight[k - 1] += length * (2.0 * ra + rb) / 6.0;
      load.weight[k] += length * (ra + 2.0 * rb) / 6.0;
    } else {
      load.weight[k - 1] += 0.5 * length;
      load.weight[k] += 0.5 * length;
    }
  }
  return load;
}

void Boundaries::release_absorbing_supports() {
  for (const AbsorbingFace& face : absorbing) {
    if (!face.active) {
      continue;
    }
    for (NodeConstraint& c : constraints) {
      if (c.nodes == face.nodes && c.name != "axis") {
        c.dofs = 0;
        c.reaction = {0.0, 0.0, 0.0}; // it holds nothing from now on
        c.torque = 0.0;
      }
    }
  }
}

void Boundaries::mark_constrained_dofs(Grid& grid) const {
  for (int f = 0; f < grid.field_count(); ++f) {
    std::vector<std::uint8_t>& mask = grid.field_constrained(f);
    std::fill(mask.begin(), mask.end(), std::uint8_t{0});
  }
  grid.water_held.assign(grid.nodes.size(), 0);
  std::vector<std::uint8_t> drained(grid.nodes.size(), 0);
  bool any_drained = false;
  for (const NodeConstraint& c : constraints) {
    for (int f = 0; f < grid.field_count(); ++f) {
      if (c.field != NodeConstraint::all_fields && c.field != f) {
        continue;
      }
      std::vector<std::uint8_t>& mask = grid.field_constrained(f);
      for (const int node : c.nodes) {
        mask[static_cast<std::size_t>(node)] |= c.dofs;
        if (f == 0) {
          (c.drained ? drained : grid.water_held)[static_cast<std::size_t>(node)] |= c.dofs;
          any_drained = any_drained || c.drained;
        }
      }
    }
  }
  // An absorbing face holds the pore water of coupled soil to the skeleton along its normal: its
  // dashpot, of the undrained impedance, then takes the mixture's wave (at a small k the phases
  // move as one), and no water leaves through it unbooked.
  for (const AbsorbingFace& face : absorbing) {
    if (!face.active) {
      continue;
    }
    const auto normal = static_cast<std::uint8_t>(1u << face_normal(face.face));
    for (const int node : face.nodes) {
      grid.water_held[static_cast<std::size_t>(node)] |= normal;
    }
  }
  // A DOF another support or an absorbing face holds impermeably is held, not drained. The kept
  // velocities survive a change of phase (the same faces stay drained) and are dropped where a face
  // stops draining.
  if (any_drained) {
    for (std::size_t i = 0; i < drained.size(); ++i) {
      drained[i] = static_cast<std::uint8_t>(drained[i] & ~grid.water_held[i] & (DOF_R | DOF_Y));
    }
    if (grid.drain_water_velocity.size() != grid.nodes.size()) {
      grid.drain_water_velocity.assign(grid.nodes.size(),
                                       {std::nan(""), std::nan(""), std::nan("")});
    }
    for (std::size_t i = 0; i < drained.size(); ++i) {
      for (int d = 0; d < 2; ++d) {
        if ((drained[i] & (1u << d)) == 0) {
          grid.drain_water_velocity[i][static_cast<std::size_t>(d)] = std::nan("");
        }
      }
    }
    grid.water_drained = std::move(drained);
  } else {
    grid.water_drained.clear();
    grid.drain_water_velocity.clear();
  }
}

const NodeConstraint& Boundaries::constraint(const std::string& name) const {
  for (const NodeConstraint& c : constraints) {
    if (c.name == name) {
      return c;
    }
  }
  throw std::out_of_range("no constraint named " + name);
}

} // namespace mpile
