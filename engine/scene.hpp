#pragma once

#include "engine/boundary_conditions.hpp"
#include "engine/geometry_mode.hpp"
#include "engine/grid.hpp"
#include "engine/material.hpp"
#include "engine/particles.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace mpile {

/// A velocity imposed on every grid node as a function of (r, y, t): for kinematic (patch) tests
/// that prescribe the whole motion. Empty in ordinary runs, which then pay nothing for it.
using VelocityField = std::function<std::array<double, 3>(double r, double y, double t)>;

/// Everything a run simulates: grid, particles, materials, bodies and boundary conditions.
struct Scene {
  explicit Scene(GeometryMode geometry_mode, Grid background_grid)
      : mode(geometry_mode), grid(std::move(background_grid)) {
    particles.mode = mode;
  }

  GeometryMode mode;
  Grid grid;
  Particles particles;
  std::vector<std::unique_ptr<Material>> materials;
  std::vector<std::string> body_names;
  Boundaries boundaries;
  VelocityField velocity_field;

  /// Adds a material and returns its index; widens the per-particle state to what it needs.
  std::uint16_t add_material(std::unique_ptr<Material> material);
  std::uint16_t add_body(std::string name);
};

} // namespace mpile
