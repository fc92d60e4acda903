#pragma once

#include "engine/boundary_conditions.hpp"
#include "engine/geometry_mode.hpp"
#include "engine/grid.hpp"
#include "engine/materials/material.hpp"
#include "engine/moving_mesh.hpp"
#include "engine/particles.hpp"
#include "engine/structures/contact.hpp"
#include "engine/structures/rigid_body.hpp"

#include <functional>
#include <memory>
#include <optional>
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
  /// The materials' names (the case's, or "<body> (rigid)" for a rigid body's), for outputs.
  std::vector<std::string> material_names;
  std::vector<std::string> body_names;
  /// Per body, 1 where its outline's cut sub-cells were seeded with the part inside (each
  /// particle's extent is then that part's): contact measures such a particle's gap with its
  /// extent along the outline's normal. Empty: no such body.
  std::vector<std::uint8_t> cut_cell_bodies;
  Boundaries boundaries;
  VelocityField velocity_field;
  /// Contact (physics.md section 5): the field each body maps to (empty: every body in field 0,
  /// no contact), one contact pair per structure with a field of its own, and the rigid bodies.
  std::vector<std::uint8_t> field_of_body;
  std::vector<ContactPair> contacts;
  std::vector<RigidBody> rigid_bodies;
  /// y-lines that follow a rigid body (physics.md section 7); none in a fixed-grid scene.
  std::optional<MovingMesh> moving_mesh;

  bool has_contact() const { return !contacts.empty(); }
  /// Per material, 1 where it is a rigid body's: such particles only mark the nodes their body
  /// occupies, carry no kinetic energy of their own and feel no gravity (the body's DOFs do).
  std::vector<char> rigid_materials() const;
  int field_of(std::uint16_t body) const { return field_of_body.empty() ? 0 : field_of_body[body]; }

  /// Adds a material and returns its index; widens the per-particle state to what it needs.
  /// Without a name it is called "material <index>".
  std::uint16_t add_material(std::unique_ptr<Material> material, std::string name = "");
  std::uint16_t add_body(std::string name);
  /// Gives a body its own velocity field in contact with the soil (field 0) and returns the pair
  /// to be filled in (friction, adhesion, surfaces, outline).
  ContactPair& add_contact_structure(std::uint16_t body);
  /// Makes a contact structure rigid: its particles switch to a rigid material of the given
  /// density, and mass and inertia are those of its particles unless given (> 0).
  RigidBody& make_rigid(std::uint16_t body, double density, double mass, double inertia);
};

/// Whether any material is coupled soil, whose water flows through its skeleton.
bool has_coupled_water(const Scene& scene);
/// Whether any material carries a pore pressure (undrained or coupled soil): contact then takes
/// friction on the effective normal force and splits each surface's force into its parts.
bool has_pore_water(const Scene& scene);

} // namespace mpile
