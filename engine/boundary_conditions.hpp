#pragma once

#include "engine/absorbing_boundary.hpp"
#include "engine/geometry_mode.hpp"
#include "engine/grid.hpp"
#include "engine/time_function.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace mpile {

/// Constrained nodal velocities on a set of grid nodes, with the reaction it takes to hold them.
/// A DOF in the mask without a velocity function is held at rest. With theta_is_rotation the theta
/// function is an angular velocity (rad/s) and the node gets v_theta = omega(t) r_node: a rigid
/// rotation of the node set about the axis.
struct NodeConstraint {
  std::string name;
  std::vector<int> nodes;
  std::uint8_t dofs = 0; // DofBit mask
  std::array<std::optional<TimeFunction>, 3> velocity;
  bool theta_is_rotation = false;
  /// A drained face: the pore water of coupled soil flows through it though the skeleton is held.
  bool drained = false;
  /// The velocity field the constraint acts on: every field (all_fields: a support holds whatever
  /// body reaches it), 0 for the soil only, k for the k-th contact structure only. Rigid bodies'
  /// fields follow their DOFs and are never constrained.
  static constexpr int all_fields = -1;
  int field = all_fields;

  /// Reaction of the last step: the force the support exerts on the material, summed over the node
  /// set (N, or N/rad in axisymmetric mode), and its torque about the axis (N m/rad).
  std::array<double, 3> reaction{0.0, 0.0, 0.0};
  double torque = 0.0;
};

/// A distributed load on a set of grid nodes: nodal force = weight_i * traction(t) along one
/// component. The weights are the consistent nodal shares of the loaded face (times r in
/// axisymmetric mode), so a uniform traction gives the exact resultant. A theta load in
/// axisymmetric mode acts on the nodes' angular velocity: its weights are those of the torque,
/// the integral of N_i r^2 over the face, so a uniform traction gives the exact torque.
struct NodalLoad {
  std::string name;
  std::vector<int> nodes;
  std::vector<double> weight;
  int component = 0; // 0 = r, 1 = y, 2 = theta
  TimeFunction traction;
};

enum class FaceCondition { free, roller, fixed };

/// Node indices along a grid line: the column of nodes at r-index ir (direction y) or the row at
/// y-index iy (direction r), limited to coordinates within [from, to].
std::vector<int> nodes_on_r_line(const Grid& grid, int ir, double y_from, double y_to);
std::vector<int> nodes_on_y_line(const Grid& grid, int iy, double r_from, double r_to);
std::vector<int> nodes_on_face(const Grid& grid, GridFace face);

/// fixed: every DOF of the mode at rest; roller: the normal DOF at rest; free: no constraint. A
/// face on the axis (r_min at r = 0, axisymmetric) holds no theta DOF, as axis_constraint.
NodeConstraint face_constraint(const Grid& grid, GeometryMode mode, GridFace face,
                               FaceCondition condition);

/// u_r = u_theta = 0 on the axis (the r = 0 nodes) in axisymmetric mode. Only u_r is held: the
/// theta unknown of a node is its angular velocity omega, and u_theta = r omega is zero on the
/// axis whatever omega is (holding omega = 0 there would stop the cells beside the axis from
/// turning rigidly).
NodeConstraint axis_constraint(const Grid& grid);

/// A normal traction (tension positive, Pa) on a straight run of nodes along a grid line, with
/// consistent weights: for axisymmetric mode the integral of N_i r over the face.
NodalLoad line_load(const Grid& grid, GeometryMode mode, const std::vector<int>& nodes,
                    int component, TimeFunction traction, std::string name);

/// The far field's pore water beyond a drained face, at rest below the saturated soil's surface:
/// its pressure p_b = rho_w g_y (surface - y) below the surface (tension positive, g_y < 0), zero
/// above, acts on the face as the traction p_b n on the water and on the mixture. Without it a
/// drained face is an open drain (p_b = 0), through which a hydrostatic column empties.
struct DrainedFaceWater {
  GridFace face = GridFace::y_min;
  std::vector<int> nodes; // along the face, in order
  double surface = 0.0;   // m: where the far field's pore pressure is zero
  double density = 0.0;   // kg/m^3: its water's
  /// The last step's force (r, y) on each node of `nodes` (solver/drained_face_water.cpp).
  std::vector<std::array<double, 2>> force;
};

struct Boundaries {
  std::vector<NodeConstraint> constraints;
  std::vector<NodalLoad> loads;
  /// Drained faces held at the far field's hydrostatic pressure ([boundaries] drained_pressure).
  std::vector<DrainedFaceWater> drained_water;
  /// Faces whose support gives way to dashpots when they are switched on.
  std::vector<AbsorbingFace> absorbing;

  /// The supports on the faces of active absorbing faces give way (the axis keeps its own).
  void release_absorbing_supports();
  /// Sets grid.constrained from the constraints (the DOFs that local damping leaves alone) and
  /// grid.water_held from the impermeable ones.
  void mark_constrained_dofs(Grid& grid) const;
  const NodeConstraint& constraint(const std::string& name) const;
};

} // namespace mpile
