#pragma once

namespace mpile {

/// The two kinematic settings of the engine (physics.md section 1).
/// Axisymmetric: coordinates (r, y), per-radian weights Omega = A r, hoop strain u_r / r and the
/// circumferential velocity v_theta. Plane strain: coordinates (x, y) stored in the r slot, weight
/// Omega = A (unit thickness), no hoop term and no theta degree of freedom.
enum class GeometryMode { axisymmetric, plane_strain };

/// True when the mode carries the circumferential (theta) velocity and the hoop terms.
constexpr bool has_theta(GeometryMode mode) {
  return mode == GeometryMode::axisymmetric;
}

} // namespace mpile
