#pragma once

#include "engine/graded_axis.hpp"
#include "engine/node_box.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace mpile {

/// One grid node in one cache line, so that a particle's scatter to its four nodes touches four
/// lines. The grid update converts the accumulated momentum and force in place (the passes after
/// it read and write them through velocity() and velocity_increment()):
///   during particle-to-grid:  momentum = sum N m v,   force = f_ext - f_int
///   after the grid update:    momentum = velocity v^{n+1},  force = velocity increment v^{n+1} -
///   v^n
/// Component order is (r, y, theta); plane strain leaves the theta slot untouched. In axisymmetric
/// mode the theta slot is angular (docs/design.md, "Angular momentum on the grid"): the node's
/// unknown is its angular velocity omega, with v_theta = r omega everywhere in a cell, so
///   during particle-to-grid:  momentum[2] = sum N m r v_theta (angular momentum),
///                             force[2] = torque, inertia = sum N m r^2
///   after the grid update:    momentum[2] = omega^{n+1}, force[2] = omega^{n+1} - omega^n.
struct alignas(64) GridNode {
  double mass = 0.0;
  double momentum[3] = {0.0, 0.0, 0.0};
  double force[3] = {0.0, 0.0, 0.0};
  double inertia = 0.0; // rotational inertia about the axis (kg m^2 per radian); 0 in plane strain

  // The slots by what they hold after the grid update, for the passes that come after it.
  double* velocity() { return momentum; }
  const double* velocity() const { return momentum; }
  double* velocity_increment() { return force; }
  const double* velocity_increment() const { return force; }
};
static_assert(sizeof(GridNode) == 64);

/// The pore water of coupled soil at one node (physics.md section 9b), beside field 0's node,
/// which then holds the skeleton. With m_w a particle's water mass and n its porosity:
///   during particle-to-grid:  mass = sum N m_w / n (the water's own inertia, rho_w V),
///                             share = sum N m_w (its part in the mixture's momentum),
///                             drag = sum N m_w g / k (Darcy's n rho_w g / k V),
///                             momentum = sum N (m_w / n) w, force = the water's f_ext - f_int,
///                             skeleton_momentum = sum N m_w v (to take out of field 0's sum);
///                             theta: the same times r (momentum) and r^2 (the three inertias)
///   after the water update:   momentum = w^{n+1}, force = w^{n+1} - w^n (theta: angular).
struct LiquidNode {
  double mass = 0.0;
  double share = 0.0;
  double drag = 0.0;
  double momentum[3] = {0.0, 0.0, 0.0};
  double force[3] = {0.0, 0.0, 0.0};
  double skeleton_momentum[3] = {0.0, 0.0, 0.0};
  double inertia = 0.0;
  double share_inertia = 0.0;
  double drag_inertia = 0.0;
  /// Field 0's mass and rotational inertia before couple_phases made them effective: the weights
  /// the MUSL remap of the skeleton's velocity divides by.
  double mixture_mass = 0.0;
  double mixture_inertia = 0.0;
  /// The force (r, y) an impermeable support exerted on the water this step to hold it to the
  /// skeleton: part of the support's reaction, which the skeleton's part alone left short.
  double held_force[2] = {0.0, 0.0};
  /// At a drained DOF: the velocity the drain kept less the particles' mapped one (r, y; m/s).
  double drain_jump[2] = {0.0, 0.0};
  /// At a structure's wall: the kinetic energy tying the phases took per DOF (r, y), and the DOFs
  /// (DofBit) along which the wall runs on a grid line, where the water flows along the wall
  /// after the contact (update_water_velocities) instead of keeping to the skeleton.
  double tie_merged[2] = {0.0, 0.0};
  std::uint8_t wall_free = 0;

  double* velocity() { return momentum; }
  const double* velocity() const { return momentum; }
  double* velocity_increment() { return force; }
  const double* velocity_increment() const { return force; }
};

/// The four faces of the grid's rectangle.
enum class GridFace { r_min, r_max, y_min, y_max };

/// Bit mask of constrained nodal degrees of freedom.
enum DofBit : std::uint8_t { DOF_R = 1, DOF_Y = 2, DOF_THETA = 4 };

/// The nodal velocity field of one contact structure (physics.md section 5): its own mass,
/// momentum and force per node, and its own constrained-DOF mask. Exists only in scenes with
/// contact.
///
/// Its passes visit only `reach`, the nodes the structure's particles can touch in this step (set
/// when the particles are binned; empty for a structure without particles). Outside `held`, the
/// box it was last scattered to, every node and mass gradient is zero, so that clearing `held` and
/// scattering into `reach` leaves the field exact everywhere: a small or idle structure costs in
/// proportion to its size, not to the grid's.
struct NodeField {
  NodeBox reach;
  NodeBox held;
  std::vector<GridNode> nodes;
  std::vector<std::uint8_t> constrained;
  /// sum m_p grad N_i(x_p) per node (it points out of the body at its surface), only for a
  /// structure whose contact normals come from it; empty otherwise.
  std::vector<std::array<double, 2>> mass_gradient;
};

/// A rectilinear background grid with graded spacing in r and y. Nodes are numbered r-fastest:
/// node(ir, iy) = ir + nodes_r * iy; cells likewise with cells_r.
class Grid {
public:
  Grid() = default;
  Grid(GradedAxis r_axis, GradedAxis y_axis);

  const GradedAxis& r_axis() const { return r_axis_; }
  const GradedAxis& y_axis() const { return y_axis_; }
  int cells_r() const { return r_axis_.cell_count(); }
  int cells_y() const { return y_axis_.cell_count(); }
  int nodes_r() const { return r_axis_.node_count(); }
  int nodes_y() const { return y_axis_.node_count(); }
  std::size_t node_count() const { return nodes.size(); }
  int node_index(int ir, int iy) const { return ir + nodes_r() * iy; }
  double node_r(int node) const { return r_axis_.node(node % nodes_r()); }
  double node_y(int node) const { return y_axis_.node(node / nodes_r()); }

  /// 1 / cell size per cell column and row, read by every particle pass.
  double inverse_cell_size_r(int cr) const { return inverse_size_r_[static_cast<std::size_t>(cr)]; }
  double inverse_cell_size_y(int cy) const { return inverse_size_y_[static_cast<std::size_t>(cy)]; }
  double cell_min_size(int cr, int cy) const {
    const double dr = r_axis_.cell_size(cr), dy = y_axis_.cell_size(cy);
    return dr < dy ? dr : dy;
  }

  /// Moves the y-lines (the moving mesh); cell sizes and the lookup follow.
  void set_y_nodes(std::vector<double> y_nodes);

  /// Field 0: every body that has no field of its own (without contact, every body).
  std::vector<GridNode> nodes;
  /// Constrained DOFs per node (DofBit mask), set from the boundary conditions. Local damping
  /// skips constrained DOFs so that reactions at moving supports are not polluted by it.
  std::vector<std::uint8_t> constrained;
  /// Field 0's constrained DOFs that hold the pore water of coupled soil to the skeleton too
  /// (impermeable faces); a drained face's are not among them.
  std::vector<std::uint8_t> water_held;
  /// Field 0's constrained DOFs at a drained face (the skeleton held, the water free), and the
  /// water velocity each such DOF ended the last step with (NaN where none): the one state the
  /// grid keeps between steps. At a drain the water's Darcy velocity jumps against the next
  /// node's, and the particles, mapped from one side only, smear it into their neighbour's every
  /// step; the drag then restores only dt Q / (M_w + dt Q) of it, so a radial drain passed 0.6 of
  /// its Darcy flux, less as the step shrank (docs/consolidation.md, "Radial consolidation").
  /// Kept only in a scene with a drained face, else empty; checkpoints carry it.
  std::vector<std::uint8_t> water_drained;
  std::vector<std::array<double, 3>> drain_water_velocity;
  /// The pore water's share of field 0's internal force per node (r, y; N or N/rad): -sum V p
  /// grad N over its saturated particles, for the effective normal force of contact; kept only in
  /// a scene with contact and undrained soil, else empty.
  std::vector<std::array<double, 2>> pore_force;
  /// The pore water of coupled soil per node; kept only in a scene with coupled soil, else empty.
  std::vector<LiquidNode> liquid;
  /// Fields 1, 2, ...: one per contact structure; empty in a scene without contact.
  std::vector<NodeField> structure_fields;

  int field_count() const { return 1 + static_cast<int>(structure_fields.size()); }
  std::vector<GridNode>& field_nodes(int field) {
    return field == 0 ? nodes : structure_fields[static_cast<std::size_t>(field - 1)].nodes;
  }
  const std::vector<GridNode>& field_nodes(int field) const {
    return field == 0 ? nodes : structure_fields[static_cast<std::size_t>(field - 1)].nodes;
  }
  std::vector<std::uint8_t>& field_constrained(int field) {
    return field == 0 ? constrained
                      : structure_fields[static_cast<std::size_t>(field - 1)].constrained;
  }
  /// Whether any structure field has more than mass_floor at the node: there contact, not the
  /// node's own momentum balance, decides the soil's motion.
  bool structure_occupies(std::size_t node, double mass_floor) const {
    for (const NodeField& field : structure_fields) {
      if (field.nodes[node].mass > mass_floor) {
        return true;
      }
    }
    return false;
  }
  /// Adds a structure field (all nodes empty) and returns its index.
  int add_structure_field();

private:
  void update_cell_sizes();

  GradedAxis r_axis_;
  GradedAxis y_axis_;
  std::vector<double> inverse_size_r_;
  std::vector<double> inverse_size_y_;
};

} // namespace mpile
