#pragma once

#include "engine/geometry_mode.hpp"
#include "engine/tensor.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace mpile {

/// Material points as flat arrays (one array per field), kept sorted by cell. In axisymmetric mode
/// mass and volume are per radian (m = rho A r, Omega = A r); positions use the r slot for x in
/// plane strain. Theta fields exist only in axisymmetric mode.
struct Particles {
  // Kinematics.
  std::vector<double> r, y;     // current position (m)
  std::vector<double> r0, y0;   // initial position (m), for displacements
  std::vector<double> v_r, v_y; // velocity (m/s)
  std::vector<double> v_theta;  // circumferential velocity (m/s), axisymmetric only
  std::vector<double> u_theta;  // circumferential displacement (m), axisymmetric only
  // Mass and integration weight.
  std::vector<double> mass;   // kg (per radian in axisymmetric mode)
  std::vector<double> volume; // Omega (m^3, per radian in axisymmetric mode)
  // Half the size of the particle's domain along r and y (m): the sub-cell it was seeded in. GIMP
  // averages the shape functions over it; uGIMP keeps it as seeded.
  std::vector<double> half_r, half_y;
  // Constitutive state.
  std::vector<Stress> stress; // Cauchy, tension positive (Pa)
  std::vector<double> state;  // material state variables, state_stride per particle
  int state_stride = 0;
  // Identity.
  /// A particle's number for life: it follows the particle through every re-sort, so that a
  /// snapshot's particle can be found in the next. A split's new half takes the next unused one.
  std::vector<std::int32_t> id;
  std::int32_t next_id = 0;
  std::vector<std::uint16_t> material; // index into the scene's materials
  std::vector<std::uint16_t> body;     // index into the scene's bodies
  // Location: the cell holding the particle, found in O(1) from the graded axes.
  std::vector<std::int32_t> cell_r, cell_y;
  // Scratch of one step: position increment from grid-to-particle, applied after the stress
  // update so that every pass of the step uses the shape functions at the old position.
  std::vector<double> du_r, du_y;

  std::size_t size() const { return r.size(); }
  GeometryMode mode = GeometryMode::axisymmetric;

  /// Appends one particle at rest with zero stress, with a domain of half-sizes (half_r_size,
  /// half_y_size); cell indices are set by the caller (binning).
  void add(double r_pos, double y_pos, double particle_mass, double particle_volume,
           double half_r_size, double half_y_size, std::uint16_t material_index,
           std::uint16_t body_index);

  /// Appends a copy of particle i (every field) and returns its index.
  std::size_t duplicate(std::size_t i);
  /// Reorders every per-particle array so that new index k holds old particle order[k]; particles
  /// the order leaves out are removed.
  void permute(std::span<const std::int32_t> order);

  /// Bytes held by the particle arrays (capacity), for memory reports.
  std::size_t bytes() const;
};

/// The area a body's particles cut on the line y = at (per radian in axisymmetry, the integral of
/// r dr; per metre in plane strain, the width): each particle whose extent [y - h_y, y + h_y)
/// spans the line gives its volume over its height, exactly a row of particles' cross-section.
double cross_section(const Particles& p, std::uint16_t body, double at);

} // namespace mpile
