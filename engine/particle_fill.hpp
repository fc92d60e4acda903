#pragma once

#include "engine/scene.hpp"

#include <cstdint>

namespace mpile {

/// An axis-aligned region of the r-y plane.
struct Rectangle {
  double r_min, r_max, y_min, y_max;
  bool contains(double r, double y) const {
    return r >= r_min && r <= r_max && y >= y_min && y <= y_max;
  }
};

/// Fills a rectangle with particles: per cell, per_direction x per_direction particles at the
/// centres of equal sub-cells, keeping those inside the rectangle. Mass rho A_p r_p and weight
/// A_p r_p per radian (axisymmetric) or rho A_p and A_p (plane strain). Returns how many were
/// added.
std::size_t fill_rectangle(Scene& scene, const Rectangle& region, int per_direction,
                           std::uint16_t material, std::uint16_t body);

/// Geostatic stress from a horizontal surface: sigma_yy = -rho g (y_surface - y) and
/// sigma_rr = sigma_thth = K0 sigma_yy, no shear, for every particle of a body; then each
/// particle's material sets its state consistently.
void initialise_geostatic_stress(Scene& scene, std::uint16_t body, double y_surface,
                                 double unit_weight, double k0);

} // namespace mpile
