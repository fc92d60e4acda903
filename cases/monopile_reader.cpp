// The [monopile] table: parameters in, the case's geometry, bodies, contact, boundaries and
// moving mesh out (the geometry itself is built by cases/monopile_geometry).
#include "cases/monopile_reader.hpp"

#include "cases/absorbing_reader.hpp"
#include "cases/case_warnings.hpp"
#include "cases/monopile_geometry.hpp"

#include <algorithm>
#include <stdexcept>

namespace mpile {

namespace {

/// The material `name`, read under `key`.
const MaterialSpec& material_named(const TomlTable& table, const CaseSpec& spec,
                                   const std::string& key, const std::string& name) {
  const auto found = std::find_if(spec.materials.begin(), spec.materials.end(),
                                  [&](const MaterialSpec& m) { return m.name == name; });
  if (found == spec.materials.end()) {
    table.fail(key, "no material named '" + name + "' in [materials]");
  }
  return *found;
}

} // namespace

std::optional<TomlTable> read_monopile(TomlTable& table, CaseSpec& spec) {
  if (spec.mode != GeometryMode::axisymmetric) {
    table.fail("", "the monopile model is axisymmetric: remove geometry = \"plane_strain\"");
  }
  MonopileParameters p;
  table.read_into(p);
  note_one_cell_wall(table, p.wall_cells, spec.warnings);
  MonopileSetup setup;
  table.read_into(setup);
  const MaterialSpec& soil =
      material_named(table, spec, table.key_of(&MonopileSetup::soil_material), setup.soil_material);
  const MaterialSpec& pile_material =
      material_named(table, spec, table.key_of(&MonopileSetup::pile_material), setup.pile_material);
  ContactSpec contact;
  contact.structure = "pile";
  table.read_into(contact); // friction and adhesion
  warn_implausible_friction(table, table.key_of(&ContactSpec::friction), contact.friction,
                            spec.warnings);
  // The pile head is above the ground: its top edge is not a contact surface.
  contact.surfaces = {"tip", "external_shaft", "", "internal_shaft"};
  std::optional<TomlTable> drive = table.optional_table("drive");
  // setup.moving_mesh false: a fixed grid instead, for comparison (the tip then leaves its grid
  // line as it penetrates).
  read_absorbing_faces(table, spec, true);

  MonopileGeometry g;
  try {
    g = build_monopile_geometry(p);
  } catch (const MonopileParameterError& e) {
    // A check between parameters names the one the case wrote (a diameter in mm is refused by the
    // base's soil_width), quoting the other.
    const std::string blamed = table.nearest_key(e.parameter, e.with);
    if (blamed == e.parameter) {
      table.fail(e.parameter, e.reason);
    }
    const bool must = e.reason.rfind("must", 0) == 0; // "soil_width must exceed ..."
    table.fail(blamed, e.parameter + (must ? " " : ": ") + e.reason + " (" + e.parameter + " = " +
                           table.value_and_place(e.parameter) + ")");
  }
  table.finish();

  spec.r_zones = g.r_zones;
  spec.y_zones = g.y_zones;
  const int ppc = setup.particles_per_cell;
  const auto soil_body = [&](const char* name, const Rectangle& region) {
    BodySpec body;
    body.name = name;
    body.material = soil.name;
    body.region = region;
    body.particles_per_direction = ppc;
    spec.bodies.push_back(body);
  };
  soil_body("soil below the tip", g.soil_below_tip);
  soil_body("soil plug", g.soil_plug);
  soil_body("soil outside", g.soil_outside);
  BodySpec pile;
  pile.name = "pile";
  pile.material = pile_material.name;
  pile.region = g.pile;
  pile.particles_per_direction = ppc;
  const auto density = pile_material.parameters.find("density");
  if (density == pile_material.parameters.end()) {
    table.fail(&MonopileSetup::pile_material,
               "material '" + pile_material.name + "' has no density");
  }
  RigidSpec rigid;
  rigid.mass = g.pile_mass(p, density->second);
  rigid.polar_inertia = g.pile_polar_inertia(p, density->second);
  pile.rigid = rigid;
  spec.bodies.push_back(pile);
  spec.contacts.push_back(contact);
  // Seed section 3: lateral boundary fixed in its normal direction; the base fixed.
  spec.faces = {FaceCondition::free, FaceCondition::roller, FaceCondition::fixed,
                FaceCondition::free};
  if (setup.moving_mesh) {
    spec.moving_mesh = MovingMeshSpec{"pile", g.band_bottom, g.band_top, p.travel, std::nullopt};
  }
  return drive;
}

} // namespace mpile
