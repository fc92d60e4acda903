#pragma once

// Viscous absorbing boundaries (Lysmer and Kuhlemeyer 1969): dashpots on a grid face whose
// tractions t_n = -rho c_p v_n and t_t = -rho c_s v_t (theta included) absorb a plane wave at
// normal incidence exactly, plus the traction that held the face when it was switched on, so that
// a soil at rest under its own weight stays at rest (a dashpot carries no static load).

#include "engine/geometry_mode.hpp"
#include "engine/grid.hpp"

#include <array>
#include <string>
#include <vector>

namespace mpile {

struct Scene;

/// An absorbing grid face. Its impedances and holding traction are sampled when it is switched on
/// (switch_on_absorbing_face) as functions of the coordinate along the face, so that with a moving
/// mesh the nodes, which then slide along the face, keep seeing the soil they face.
struct AbsorbingFace {
  GridFace face = GridFace::r_max;
  bool active = false;
  /// The face's nodes in increasing coordinate along it.
  std::vector<int> nodes;
  /// When switched on: the nodes' coordinates along the face (m)...
  std::vector<double> edges;
  /// ...the soil's impedances rho c_p and rho c_s (Pa s/m) on each segment between two edges (0
  /// where no soil touches it)...
  std::vector<double> p_impedance;
  std::vector<double> s_impedance;
  /// ...and the traction that held each node then (Pa; theta: the v_theta component), which the
  /// face goes on exerting.
  std::vector<std::array<double, 3>> holding_traction;
};

/// The coordinate along a face (y on an r face, r on a y face) and the normal direction (0 = r,
/// 1 = y).
inline int face_normal(GridFace face) {
  return face == GridFace::r_min || face == GridFace::r_max ? 0 : 1;
}

/// The nodal weights of a traction uniform along each segment of the face at the nodes' current
/// coordinates, for a unit traction on segment j alone: weight(k, j) = integral over segment j of
/// N_k r^power (power 1 for forces and 3 for the theta dashpot's torque per angular velocity in
/// axisymmetric mode, 2 for a theta traction's torque; 0 for every force in plane strain). Returns,
/// per segment j, the weights of its lower node and its upper node.
std::vector<std::array<double, 2>> segment_weights(const Grid& grid, const AbsorbingFace& face,
                                                   int power);

/// The current coordinate of face node k along the face.
double along_face(const Grid& grid, const AbsorbingFace& face, std::size_t k);

/// The power of r in a weight (segment_weights) for the translational DOFs and for the theta
/// DOF's dashpot and holding torque.
struct WeightPowers {
  int force = 0;
  int theta_dashpot = 0;
  int theta_torque = 0;
};
constexpr WeightPowers weight_powers(GeometryMode mode) {
  return has_theta(mode) ? WeightPowers{1, 3, 2} : WeightPowers{0, 0, 0};
}

/// Samples the impedances of the soil beside the face from the particles in the cells along it:
/// per segment the mass-weighted mean of sqrt(rho M) and sqrt(rho G) at each particle's current
/// density and stress (M the constrained and G the shear modulus its material reports there).
/// Rigid bodies' particles do not count.
void sample_face_impedance(const Scene& scene, AbsorbingFace& face);

/// The face's impedances interpolated to the segment between nodes k and k + 1 now (the edges it
/// had when switched on hold the profile; the segment's midpoint looks it up).
std::array<double, 2> segment_impedance(const Grid& grid, const AbsorbingFace& face, std::size_t k);

/// The holding traction at node k now, interpolated along the edges it was sampled at.
std::array<double, 3> holding_traction_now(const Grid& grid, const AbsorbingFace& face,
                                           std::size_t k);

} // namespace mpile
