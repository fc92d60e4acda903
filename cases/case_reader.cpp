// The case file reader: TOML in, a validated CaseSpec out. Strict: unknown keys, missing required
// keys, wrong types and physically invalid values are errors that name file, line, key and reason.
//
// Outline:
//   pieces read in several tables: grid zones, node lines on grid lines, a component's index,
//     face conditions
//   the tables, each by one function: read_materials, read_bodies (and their rigid drives),
//     read_contacts, read_affine_motion, read_motions_and_loads, read_solver; the phases
//     (phase_reader), the outputs (output_reader), the water (water_reader), a [monopile]
//     (monopile_reader) read in files of their own
//   read_pore_water, read_material_table: a material's model, drainage and pore water
//   CaseSpec::end_time
//   read_case_text, read_case_tree (the tables in order, [monopile] or the tables it builds, the
//     memory budget and the checks across tables), read_case_file (bases and --set overrides)
#include "cases/absorbing_reader.hpp"
#include "cases/case_builder.hpp"
#include "cases/case_composition.hpp"
#include "cases/case_spec.hpp"
#include "cases/case_warnings.hpp"
#include "cases/dataset_name.hpp"
#include "cases/face_list_reader.hpp"
#include "cases/memory_budget.hpp"
#include "cases/monopile_geometry.hpp"
#include "cases/monopile_reader.hpp"
#include "cases/output_reader.hpp"
#include "cases/phase_reader.hpp"
#include "cases/region_reader.hpp"
#include "cases/rigid_drive_reader.hpp"
#include "cases/time_function_reader.hpp"
#include "cases/toml_reader.hpp"
#include "cases/water_reader.hpp"
#include "engine/particle_bins.hpp"
#include "engine/structures/contact.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mpile {

namespace {

std::vector<AxisZone> read_zones(TomlTable& grid, const std::string& key,
                                 std::vector<CaseWarning>& warnings) {
  std::vector<AxisZone> zones;
  for (TomlTable& zone : grid.tables(key)) {
    AxisZone z;
    zone.read_into(z);
    if (!(z.end > z.start)) {
      zone.fail(&AxisZone::end, "must be greater than start (" + format_number(z.start) + ")");
    }
    warn_implausible_zone(zone, z.start, z.end, warnings);
    zone.finish();
    zones.push_back(z);
  }
  if (zones.empty()) {
    grid.missing(key, "at least one zone {start, end, cells}");
  }
  try {
    GradedAxis axis(zones);
  } catch (const std::invalid_argument& e) {
    grid.fail(key, e.what());
  }
  return zones;
}

struct Axes {
  GradedAxis r;
  GradedAxis y;
};

Axes axes_of(const CaseSpec& spec) {
  return {GradedAxis(spec.r_zones), GradedAxis(spec.y_zones)};
}

bool on_grid_line(const GradedAxis& axis, double x) {
  const double tolerance = 1e-9 * std::max(1.0, axis.end() - axis.start());
  for (const double node : axis.nodes()) {
    if (std::abs(node - x) <= tolerance) {
      return true;
    }
  }
  return false;
}

NodeLineSpec read_node_line(TomlTable& owner, const Axes& axes) {
  TomlTable nodes = owner.table("nodes");
  NodeLineSpec line;
  const bool has_r = nodes.has("r"), has_y = nodes.has("y");
  auto is_number = [&](const std::string& key) {
    const TomlValue& v = nodes.raw(key);
    return v.is_floating() || v.is_integer();
  };
  if (has_r && is_number("r")) {
    line.along_y = true;
    line.at = nodes.number("r");
    if (!on_grid_line(axes.r, line.at)) {
      nodes.fail("r", format_number(line.at) + " is not on a grid line of r");
    }
    line.from = axes.y.start();
    line.to = axes.y.end();
    if (has_y) {
      const auto range = nodes.numbers("y", 2);
      line.from = range[0];
      line.to = range[1];
    }
  } else if (has_y && is_number("y")) {
    line.along_y = false;
    line.at = nodes.number("y");
    if (!on_grid_line(axes.y, line.at)) {
      nodes.fail("y", format_number(line.at) + " is not on a grid line of y");
    }
    line.from = axes.r.start();
    line.to = axes.r.end();
    if (has_r) {
      const auto range = nodes.numbers("r", 2);
      line.from = range[0];
      line.to = range[1];
    }
  } else {
    owner.fail("nodes", "needs r = <grid line> or y = <grid line> (the other may be a range)");
  }
  if (!(line.to >= line.from)) {
    nodes.fail(line.along_y ? "y" : "r", "range must be increasing");
  }
  // A range that holds no node would prescribe nothing, silently.
  const GradedAxis& along = line.along_y ? axes.y : axes.r;
  const double tolerance = 1e-9 * std::max(1.0, along.end() - along.start());
  const bool holds_a_node = std::any_of(along.nodes().begin(), along.nodes().end(), [&](double x) {
    return x >= line.from - tolerance && x <= line.to + tolerance;
  });
  if (!holds_a_node) {
    nodes.fail(line.along_y ? "y" : "r",
               "the range [" + format_number(line.from) + ", " + format_number(line.to) +
                   "] holds no node of the grid (" + (line.along_y ? "y" : "r") + " from " +
                   format_number(along.start()) + " to " + format_number(along.end()) + ")");
  }
  nodes.finish();
  return line;
}

void read_materials(TomlTable& top, CaseSpec& spec) {
  for (auto& [name, table] : top.named_tables("materials")) {
    spec.materials.push_back(read_material_table(table, name));
    warn_implausible_material(table, spec.materials.back(), spec.warnings);
  }
  if (spec.materials.empty()) {
    top.missing("materials", "at least one [materials.<name>] table");
  }
}

/// Reads the bodies; returns the [bodies.rigid] tables (by body index), read once the phases are
/// known, and keeps each body's table in `tables` for the checks that need the moving mesh.
std::vector<std::pair<std::size_t, TomlTable>>
read_bodies(TomlTable& top, CaseSpec& spec, const Axes& axes, std::vector<TomlTable>& tables) {
  std::vector<std::pair<std::size_t, TomlTable>> rigid_tables;
  std::set<std::string> names;
  // A structure's history is /bodies/<name> and /reactions/<name>: names are compared as written.
  GroupNames groups("/bodies");
  for (TomlTable& table : top.tables("bodies")) {
    BodySpec body;
    table.read_into(body);
    if (!names.insert(body.name).second) {
      table.fail(&BodySpec::name, "a body named '" + body.name + "' already exists");
    }
    if (const auto clash = groups.clash(body.name, table.location(table.key_of(&BodySpec::name)))) {
      table.fail(&BodySpec::name, *clash);
    }
    const bool known = std::any_of(spec.materials.begin(), spec.materials.end(),
                                   [&](const MaterialSpec& m) { return m.name == body.material; });
    if (!known) {
      table.fail(&BodySpec::material, "no material named '" + body.material + "' in [materials]");
    }
    body.region = read_region(table, spec.mode, axes.r, axes.y);
    body.line = table.line_of("region");
    body.key = table.key_path("region");
    if (std::optional<TomlTable> profile = table.optional_table("velocity_profile")) {
      VelocityProfile p;
      profile->read_into(p);
      if (p.component == 2 && spec.mode == GeometryMode::plane_strain) {
        profile->fail(&VelocityProfile::component, "plane strain has no theta velocity");
      }
      p.function = read_time_function(*profile, "function");
      profile->finish();
      body.velocity_profile = p;
    }
    if (table.has("velocity")) {
      const auto v = table.numbers("velocity", 3);
      body.velocity = {v[0], v[1], v[2]};
      if (spec.mode == GeometryMode::plane_strain && v[2] != 0.0) {
        table.fail("velocity", "plane strain has no theta velocity");
      }
    }
    if (std::optional<TomlTable> rigid = table.optional_table("rigid")) {
      // A rigid body's particles carry no stress and no pore water: a saturated material there
      // would be read and then silently ignored.
      const auto material =
          std::find_if(spec.materials.begin(), spec.materials.end(),
                       [&](const MaterialSpec& m) { return m.name == body.material; });
      if (material->water.drainage != Drainage::drained) {
        table.fail(&BodySpec::material,
                   "'" + body.material + "' is saturated (drainage = \"" +
                       drainage_names()[static_cast<std::size_t>(material->water.drainage)] +
                       "\"), but a rigid body has no pores: give it a dry material");
      }
      rigid_tables.emplace_back(spec.bodies.size(), std::move(*rigid));
    }
    table.finish();
    tables.push_back(table);
    spec.bodies.push_back(std::move(body));
  }
  if (spec.bodies.empty()) {
    top.missing("bodies", "at least one [[bodies]] table");
  }
  return rigid_tables;
}

/// `phase`, read under `key`, must be empty (the first phase) or name a phase.
void check_phase_reference(const TomlTable& table, const std::string& key, const std::string& phase,
                           const CaseSpec& spec) {
  const bool known =
      phase.empty() || std::any_of(spec.phases.begin(), spec.phases.end(),
                                   [&](const PhaseSpec& p) { return p.name == phase; });
  if (!known) {
    table.fail(key, "no phase named '" + phase + "' in [[phases]]");
  }
}

/// Reads a rigid body's drives (and mass and inertia unless a [monopile] table has derived them
/// from the whole pile already).
void read_rigid_body(TomlTable& table, BodySpec& body, const CaseSpec& spec,
                     std::vector<CaseWarning>& warnings) {
  RigidSpec rigid = body.rigid.value_or(RigidSpec{});
  const bool derived = body.rigid.has_value();
  const bool plane = spec.mode == GeometryMode::plane_strain;
  // Each mode turns a body about its own axis, under its own key.
  const auto inertia = plane ? &RigidSpec::inertia : &RigidSpec::polar_inertia;
  const auto other_mode = plane ? &RigidSpec::polar_inertia : &RigidSpec::inertia;
  for (const auto member : {&RigidSpec::mass, inertia}) {
    if (derived && table.has(table.key_of(member))) {
      table.fail(member, "the monopile's mass and polar inertia follow from pile_length, "
                         "diameter, wall_thickness and the pile material's density; remove this "
                         "key");
    }
  }
  // (The monopile's drive table declares neither: its finish() refuses them as unknown.)
  if (!derived && table.has(table.key_of(other_mode))) {
    table.fail(other_mode, plane ? "axisymmetric cases only: a plane-strain body turns about its "
                                   "centre, its moment of inertia given as inertia (kg m^2/m)"
                                 : "plane-strain cases only: an axisymmetric body turns about the "
                                   "axis, its moment of inertia given as polar_inertia "
                                   "(kg m^2/rad)");
  }
  table.read_into(rigid);
  rigid.drive = read_drives(table, spec, warnings);
  check_phase_reference(table, table.key_of(&RigidSpec::phase), rigid.phase, spec);
  table.finish();
  body.rigid = rigid;
}

void read_contacts(TomlTable& top, CaseSpec& spec) {
  for (TomlTable& table : top.tables("contact")) {
    ContactSpec contact;
    table.read_into(contact);
    const auto body = std::find_if(spec.bodies.begin(), spec.bodies.end(),
                                   [&](const BodySpec& b) { return b.name == contact.structure; });
    if (body == spec.bodies.end()) {
      table.fail(&ContactSpec::structure,
                 "no body named '" + contact.structure + "' in [[bodies]]");
    }
    for (const ContactSpec& other : spec.contacts) {
      if (other.structure == contact.structure) {
        table.fail(&ContactSpec::structure,
                   "'" + contact.structure + "' already has a [[contact]] entry");
      }
    }
    warn_implausible_friction(table, table.key_of(&ContactSpec::friction), contact.friction,
                              spec.warnings);
    if (contact.surface_gap && !contact.outline) {
      table.fail(&ContactSpec::surface_gap, "the soil's surface gap needs the outline's normals");
    }
    if (contact.outline) {
      contact.surfaces = read_outline_surfaces(table, contact, body->region, body->name);
    } else {
      if (table.has("surfaces")) {
        table.fail("surfaces", "mass-gradient normals have one surface: use the key surface");
      }
      contact.surfaces = {table.has(table.key_of(&ContactSpec::surface)) ? contact.surface
                                                                         : "interface"};
    }
    // Edges given one name are one surface; two names must not become one group.
    const std::string key =
        table.has("surfaces") ? "surfaces" : table.key_of(&ContactSpec::surface);
    GroupNames groups("/reactions/" + dataset_name(contact.structure));
    std::set<std::string> seen{""};
    for (const std::string& surface : contact.surfaces) {
      if (seen.insert(surface).second) {
        if (const auto clash = groups.clash(surface, table.location(key))) {
          table.fail(key, *clash);
        }
      }
    }
    table.finish();
    spec.contacts.push_back(std::move(contact));
  }
  if (!spec.contacts.empty() && spec.contacts.size() == spec.bodies.size()) {
    top.fail("contact", "every body is a contact structure: at least one body must be soil");
  }
  for (const BodySpec& body : spec.bodies) {
    const bool structure =
        std::any_of(spec.contacts.begin(), spec.contacts.end(),
                    [&](const ContactSpec& c) { return c.structure == body.name; });
    if (body.rigid && !structure) {
      top.fail("bodies", "body '" + body.name +
                             "' is rigid but has no [[contact]] entry: a rigid body acts on the "
                             "soil only through contact");
    }
  }
}

void read_moving_mesh(TomlTable& top, CaseSpec& spec, const Axes& axes,
                      const RigidNames& declared_rigid) {
  std::optional<TomlTable> table = top.optional_table("moving_mesh");
  if (!table) {
    return;
  }
  MovingMeshSpec mesh;
  table->read_into(mesh);
  check_rigid_body_name(*table, table->key_of(&MovingMeshSpec::body), mesh.body, spec,
                        declared_rigid, " (the band moves with one)");
  if (spec.mode == GeometryMode::plane_strain) {
    table->fail(&MovingMeshSpec::body,
                "the moving mesh follows a body that only translates along y and spins "
                "about the axis: axisymmetric cases only");
  }
  const auto band = table->numbers("band", 2);
  if (!(band[1] > band[0]) || !on_grid_line(axes.y, band[0]) || !on_grid_line(axes.y, band[1])) {
    table->fail("band", "must be [y_bottom, y_top], both on y grid lines, y_top > y_bottom");
  }
  if (!(band[0] > axes.y.start()) || !(band[1] < axes.y.end())) {
    table->fail("band", "must lie strictly inside the grid (the lines below and above it are "
                        "squeezed and stretched)");
  }
  if (table->has("stretch")) {
    const auto stretch = table->numbers("stretch", 2);
    if (!on_grid_line(axes.y, stretch[0]) || !on_grid_line(axes.y, stretch[1]) ||
        !(stretch[0] < band[0]) || !(stretch[1] > band[1])) {
      table->fail("stretch", "must be [y_bottom, y_top], both on y grid lines, below and above "
                             "the band: the lines between them and the band are squeezed and "
                             "stretched, those beyond stay put");
    }
    mesh.stretch = std::array<double, 2>{stretch[0], stretch[1]};
  }
  table->finish();
  mesh.band_bottom = band[0];
  mesh.band_top = band[1];
  if (mesh.travel > 0.0) {
    // The soil below the band is seeded for the lines carried the whole travel down.
    try {
      moving_mesh_of(mesh, axes.y).lines_at(-mesh.travel);
    } catch (const std::runtime_error& e) {
      table->fail(&MovingMeshSpec::travel, e.what());
    }
  }
  spec.moving_mesh = mesh;
}

void read_affine_motion(TomlTable& top, CaseSpec& spec) {
  std::optional<TomlTable> table = top.optional_table("affine_motion");
  if (!table) {
    return;
  }
  const auto gradient = table->numbers("velocity_gradient", 4);
  table->finish();
  spec.velocity_gradient =
      std::array<double, 4>{gradient[0], gradient[1], gradient[2], gradient[3]};
}

void read_motions_and_loads(TomlTable& top, CaseSpec& spec, const Axes& axes) {
  const bool theta = has_theta(spec.mode);
  std::set<std::string> names;
  auto unique_name = [&](const TomlTable& table, const std::string& key, const std::string& name) {
    if (!names.insert(name).second) {
      table.fail(key, "a prescribed motion or load named '" + name + "' already exists");
    }
  };
  // A prescribed motion's reactions go to /boundaries/<name>, beside the constrained faces'.
  GroupNames boundaries("/boundaries");
  const char* faces[] = {"r_min", "r_max", "y_min", "y_max"};
  for (std::size_t f = 0; f < 4; ++f) {
    if (spec.faces[f] != FaceCondition::free) {
      boundaries.clash(faces[f], "the condition of that face in [boundaries]");
    }
  }
  if (spec.mode == GeometryMode::axisymmetric && axes.r.start() == 0.0) {
    boundaries.clash("axis", "the axis, held by the grid starting on it");
  }
  for (TomlTable& table : top.tables("prescribed")) {
    MotionSpec motion;
    table.read_into(motion);
    const std::string& name_key = table.key_of(&MotionSpec::name);
    unique_name(table, name_key, motion.name);
    if (const auto clash = boundaries.clash(motion.name, table.location(name_key))) {
      table.fail(name_key, *clash);
    }
    motion.nodes = read_node_line(table, axes);
    const char* keys[] = {"velocity_r", "velocity_y", "velocity_theta"};
    for (std::size_t d = 0; d < 3; ++d) {
      if (table.has(keys[d])) {
        if (d == 2 && !theta) {
          table.fail(keys[d], "plane strain has no theta velocity");
        }
        motion.velocity[d] = read_time_function(table, keys[d]);
      }
    }
    if (table.has("angular_velocity")) {
      if (!theta) {
        table.fail("angular_velocity", "plane strain has no rotation about the axis");
      }
      if (motion.velocity[2]) {
        table.fail("angular_velocity", "give either velocity_theta or angular_velocity, not both");
      }
      motion.velocity[2] = read_time_function(table, "angular_velocity");
      motion.theta_is_rotation = true;
    }
    if (!motion.velocity[0] && !motion.velocity[1] && !motion.velocity[2]) {
      table.fail(name_key, "prescribes nothing: give velocity_r, velocity_y, velocity_theta or "
                           "angular_velocity");
    }
    check_phase_reference(table, table.key_of(&MotionSpec::phase), motion.phase, spec);
    if (!motion.body.empty()) {
      const auto body = std::find_if(spec.bodies.begin(), spec.bodies.end(),
                                     [&](const BodySpec& b) { return b.name == motion.body; });
      const bool structure =
          std::any_of(spec.contacts.begin(), spec.contacts.end(),
                      [&](const ContactSpec& c) { return c.structure == motion.body; });
      if (body == spec.bodies.end() || !structure) {
        table.fail(&MotionSpec::body,
                   "'" + motion.body +
                       "' is not a contact structure (only those have a field of their own)");
      }
      if (body->rigid) {
        table.fail(&MotionSpec::body,
                   "'" + motion.body + "' is rigid: drive it in its [bodies.rigid] table");
      }
    }
    table.finish();
    spec.motions.push_back(std::move(motion));
  }
  for (TomlTable& table : top.tables("loads")) {
    LoadSpec load;
    table.read_into(load);
    unique_name(table, table.key_of(&LoadSpec::name), load.name);
    load.nodes = read_node_line(table, axes);
    if (spec.moving_mesh && load.nodes.along_y) {
      // Its nodal weights come from the y spacing, which the moving mesh changes.
      table.fail("nodes", "a load along an r-line cannot be combined with a moving mesh");
    }
    if (load.component == 2 && !theta) {
      table.fail(&LoadSpec::component, "plane strain has no theta direction");
    }
    load.traction = read_time_function(table, "traction");
    check_phase_reference(table, table.key_of(&LoadSpec::phase), load.phase, spec);
    table.finish();
    spec.loads.push_back(std::move(load));
  }
}

void read_solver(TomlTable& top, CaseSpec& spec, const Axes& axes) {
  SolverSettings& s = spec.solver;
  std::optional<TomlTable> table = top.optional_table("solver");
  if (!table) {
    return;
  }
  // Each setting through its declaration (solver/solver_settings.cpp), bound to its member, its
  // range checked as it is read; an absent one keeps SolverSettings' default, which the
  // declaration documents.
  table->read_into(s);
  if (table->has("gravity")) {
    const auto g = table->numbers("gravity", 2);
    s.gravity = {g[0], g[1]};
    warn_implausible_gravity(*table, {g[0], g[1]}, spec.mode == GeometryMode::axisymmetric,
                             spec.warnings);
  }
  if (s.shape_functions == ShapeFunctions::gimp &&
      (axes.r.cell_count() < 2 || axes.y.cell_count() < 2)) {
    table->fail(&SolverSettings::shape_functions,
                "GIMP needs at least 2 cells along r and along y (a particle's domain may reach "
                "into the next cell)");
  }
  // The checks between keys; each key's own range was checked as it was read.
  if (s.xpic_order > 0 && s.flip_fraction != 1.0) {
    table->fail(&SolverSettings::xpic_order,
                "XPIC(" + std::to_string(s.xpic_order) +
                    ") replaces the FLIP/PIC blend: leave flip_fraction at 1 (got " +
                    format_number(s.flip_fraction) + ")");
  }
  if (s.bbar_consistent_force && !s.bbar) {
    table->fail(&SolverSettings::bbar_consistent_force,
                "is B-bar's transpose in the internal force: it needs "
                "bbar = true");
  }
  if (!(s.energy_residual_limit > s.energy_residual_warning)) {
    table->fail(&SolverSettings::energy_residual_limit,
                "must exceed energy_residual_warning (" + format_number(s.energy_residual_warning) +
                    "), got " + format_number(s.energy_residual_limit));
  }
  if (s.shape_functions == ShapeFunctions::gimp && s.block_cells < 3) {
    table->fail(&SolverSettings::block_cells, "must be at least 3 with GIMP shape functions, got " +
                                                  std::to_string(s.block_cells));
  }
  if (s.implicit_pore_pressure) {
    if (!s.musl) {
      table->fail(&SolverSettings::implicit_pore_pressure,
                  "the implicit pore pressure corrects the remapped "
                  "velocities the strains are taken from: it needs "
                  "scheme = \"musl\"");
    }
    bool saturated = false;
    for (MaterialSpec& material : spec.materials) {
      if (material.water.drainage != Drainage::drained) {
        material.water.implicit_pressure = true;
        saturated = true;
      }
    }
    if (!saturated) {
      table->fail(&SolverSettings::implicit_pore_pressure,
                  "no material is undrained or coupled: there is no "
                  "pore pressure to solve for; remove it");
    }
    if (!spec.absorbing.faces.empty()) {
      // Their dashpots take the impedance of the stiffness the step follows, the skeleton's: a
      // saturated P pulse came back from them and 15 % of its energy went unbooked.
      table->fail(&SolverSettings::implicit_pore_pressure,
                  "absorbing faces are not built for the implicit pore pressure (their dashpots "
                  "would take the drained skeleton's impedance, not the undrained soil's): leave "
                  "it off with absorbing faces");
    }
  }
  if (table->has(&SolverSettings::hold_wall_cells) && !s.implicit_pore_pressure) {
    table->fail(&SolverSettings::hold_wall_cells,
                "the wall cells are held or capped in the implicit pore pressure's solve: it "
                "needs implicit_pore_pressure = true; remove it");
  }
  if (s.cell_mean_pore_pressure &&
      std::none_of(spec.materials.begin(), spec.materials.end(),
                   [](const MaterialSpec& m) { return m.water.drainage != Drainage::drained; })) {
    table->fail(&SolverSettings::cell_mean_pore_pressure,
                "no material is undrained or coupled: there is no "
                "pore pressure to average; remove it");
  }
  s.validate(); // what the reader let through is valid; a failure here is the reader's fault
  table->finish();
}

/// A material's drainage and its pore water's parameters, which only a saturated (undrained or
/// coupled) material may give; the hydraulic conductivity only a coupled one, which must.
void read_pore_water(TomlTable& table, MaterialSpec& material) {
  // Drainage and the water's parameters, bound to PoreWater, each in its declared range.
  table.read_into(material.water);
  for (const PoreWaterParameter& parameter : pore_water_parameters()) {
    const bool conductivity = parameter.member == &PoreWater::hydraulic_conductivity;
    if (!table.has(parameter.name)) {
      if (conductivity && material.water.drainage == Drainage::coupled) {
        table.missing(parameter.name, "a coupled material's Darcy hydraulic conductivity k, in "
                                      "m/s (the water's discharge per unit hydraulic gradient)");
      }
      continue;
    }
    if (material.water.drainage == Drainage::drained) {
      table.fail(parameter.name, "a drained material has no pore water: give it with drainage = "
                                 "\"undrained\" or \"coupled\", or remove it");
    }
    if (conductivity && material.water.drainage != Drainage::coupled) {
      table.fail(parameter.name, "an undrained material's water does not flow: give k with "
                                 "drainage = \"coupled\", or remove it");
    }
  }
}

/// Whether `text` names `key` as a word ("friction_angle" in "in [0, friction_angle]", not in
/// "critical_friction_angle").
bool mentions(const std::string& text, const std::string& key) {
  const auto word = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
  };
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
    const bool starts = at == 0 || !word(text[at - 1]);
    const bool ends = at + key.size() == text.size() || !word(text[at + key.size()]);
    if (starts && ends) {
      return true;
    }
  }
  return false;
}

} // namespace

MaterialSpec read_material_table(TomlTable& table, const std::string& name) {
  MaterialSpec material;
  material.name = name;
  table.read_into(material); // its type, one of the registry's (the declaration's choices)
  const MaterialType* type =
      &*std::find_if(material_types().begin(), material_types().end(),
                     [&](const MaterialType& t) { return t.name == material.type; });
  read_pore_water(table, material);
  for (const MaterialParameterSpec& parameter : type->parameters) {
    if (table.has(parameter.name)) {
      const double x = table.number(parameter.name);
      if (!parameter.range.contains(x)) {
        const bool both = parameter.range.lower && parameter.range.upper;
        table.fail(parameter.name, material.type + ": " + parameter.name + " must " +
                                       (both ? "lie " : "be ") + parameter.range.text() +
                                       (parameter.unit == "-" ? "" : " " + parameter.unit) +
                                       ", got " + format_bound(x));
      }
      material.parameters[parameter.name] = x;
      material.where[parameter.name] =
          table.location(parameter.name) + ": " + table.key_path(parameter.name);
    } else if (!parameter.default_value) {
      table.missing(parameter.name, parameter.meaning + ", in " + parameter.unit);
    }
  }
  table.finish();
  try {
    create_material(material.type, material.parameters, material.water);
  } catch (const std::invalid_argument& e) {
    // What is left are checks between parameters; the model's message begins with the type and
    // the parameter it refuses ("hardening_soil: eur_ref must exceed ...").
    const std::string message = e.what();
    const std::string prefix = material.type + ": ";
    const std::string first =
        message.rfind(prefix, 0) == 0
            ? message.substr(prefix.size(), message.find(' ', prefix.size()) - prefix.size())
            : "";
    const bool named =
        std::any_of(type->parameters.begin(), type->parameters.end(),
                    [&](const MaterialParameterSpec& p) { return p.name == first; }) ||
        std::any_of(pore_water_parameters().begin(), pore_water_parameters().end(),
                    [&](const PoreWaterParameter& p) { return p.name == first; });
    // A value of the wrong unit often makes the model's checks between parameters fail (a
    // friction angle in radians, E50 in kPa: no cap then fits): the key of the likely slip is
    // blamed, with its hint, before a named parameter that a base file gave.
    const std::string blamed = named ? first : table.key_of(&MaterialSpec::type);
    std::vector<CaseWarning> hints;
    warn_implausible_material(table, material, hints);
    for (const CaseWarning& hint : hints) {
      if (!named || hint.key == first || table.nearest_key(first, {hint.key}) == hint.key) {
        table.fail(hint.key, message + "; " + hint.message);
      }
    }
    // Else the parameters the message compares: the one the case wrote is named.
    std::vector<std::string> compared;
    for (const MaterialParameterSpec& p : type->parameters) {
      if (p.name != first && mentions(message.substr(prefix.size()), p.name)) {
        compared.push_back(p.name);
      }
    }
    const std::string nearest = table.nearest_key(blamed, compared);
    if (nearest != blamed) {
      table.fail(nearest,
                 named ? message + " (" + blamed + " = " + table.value_and_place(blamed) + ")"
                       : message);
    }
    table.fail(blamed, message);
  }
  return material;
}

double CaseSpec::end_time() const {
  double total = 0.0;
  for (const PhaseSpec& phase : phases) {
    total += phase.duration;
  }
  return total;
}

CaseSpec read_case_text(const std::string& text, const std::string& file) {
  const TomlValue root = parse_toml(text, file);
  if (root.as_table().count("base") > 0) {
    throw CaseError(file + ": base names a file; read the case with read_case_file");
  }
  CaseSpec spec = read_case_tree(root, text, file);
  spec.resolved = toml::format(root);
  return spec;
}

CaseSpec read_case_tree(const TomlValue& root, const std::string& text, const std::string& file) {
  TomlTable top(root, "", file, find_table_spec(""));
  CaseSpec spec;
  spec.file = file;
  spec.text = text;
  top.read_into(spec); // title and geometry
  if (!top.has(&CaseSpec::title)) {
    spec.title = std::filesystem::path(file).stem().string();
  }

  // Either a [monopile] table builds grid, bodies, contact and boundaries, or the file gives them.
  std::vector<std::pair<std::size_t, TomlTable>> rigid_tables;
  std::vector<TomlTable> body_tables; // empty with [monopile], whose bodies are never empty
  Axes axes;
  // The table `absorbing` was read from, for its phase's check once the phases are read.
  std::optional<TomlTable> absorbing_table;
  if (std::optional<TomlTable> monopile = top.optional_table("monopile")) {
    for (const char* key : {"grid", "bodies", "contact", "boundaries", "moving_mesh"}) {
      if (top.has(key)) {
        top.fail(key, "[monopile] builds the grid, bodies, contact, boundaries and moving mesh; "
                      "remove this table");
      }
    }
    read_materials(top, spec);
    if (std::optional<TomlTable> drive = read_monopile(*monopile, spec)) {
      rigid_tables.emplace_back(spec.bodies.size() - 1, std::move(*drive));
    }
    absorbing_table = *monopile;
    axes = axes_of(spec);
  } else {
    TomlTable grid = top.table("grid");
    spec.r_zones = read_zones(grid, "r", spec.warnings);
    spec.y_zones = read_zones(grid, "y", spec.warnings);
    grid.finish();
    if (spec.mode == GeometryMode::axisymmetric && spec.r_zones.front().start < 0.0) {
      grid.fail("r", "starts at r = " + format_number(spec.r_zones.front().start) +
                         " < 0; an axisymmetric grid starts at the axis or beyond it");
    }
    axes = axes_of(spec);
    read_materials(top, spec);
    rigid_tables = read_bodies(top, spec, axes, body_tables);
  }
  std::optional<TomlTable> drained_table; // for the note below, once gravity is known
  bool hydrostatic_drains = false;        // ... and the far field's water, once phases are
  if (std::optional<TomlTable> boundaries = top.optional_table("boundaries")) {
    read_absorbing_faces(*boundaries, spec,
                         spec.mode == GeometryMode::axisymmetric && axes.r.start() == 0.0);
    absorbing_table = *boundaries;
    FaceConditions faces;
    boundaries->read_into(faces);
    spec.faces = {faces.r_min, faces.r_max, faces.y_min, faces.y_max};
    const char* face_names[] = {"r_min", "r_max", "y_min", "y_max"}; // the drained list's
    hydrostatic_drains = faces.hydrostatic_drains;
    if (faces.hydrostatic_drains && !boundaries->has("drained")) {
      boundaries->fail(&FaceConditions::hydrostatic_drains,
                       "no face is drained (give them with drained = [...]): there is no water "
                       "beyond a face for the pressure to act through");
    }
    if (boundaries->has("drained")) {
      spec.drained_faces = read_face_list(*boundaries, "drained");
      drained_table = *boundaries;
      for (const GridFace face : spec.drained_faces) {
        if (spec.faces[static_cast<std::size_t>(face)] == FaceCondition::free) {
          boundaries->fail("drained", std::string("lists \"") + face_names[static_cast<int>(face)] +
                                          "\", a free face: the water leaves a free face already");
        }
      }
      if (std::none_of(spec.materials.begin(), spec.materials.end(), [](const MaterialSpec& m) {
            return m.water.drainage == Drainage::coupled;
          })) {
        boundaries->fail("drained", "no material is coupled (drainage = \"coupled\"): only "
                                    "flowing pore water drains through a face");
      }
    }
    if (spec.mode == GeometryMode::axisymmetric && axes.r.start() == 0.0 &&
        boundaries->has(&FaceConditions::r_min)) {
      boundaries->fail(&FaceConditions::r_min,
                       "the grid starts on the axis, which is constrained "
                       "(u_r = u_theta = 0) automatically; remove this key");
    }
    boundaries->finish();
  }
  read_solver(top, spec, axes);
  if (drained_table && !hydrostatic_drains &&
      (spec.solver.gravity[0] != 0.0 || spec.solver.gravity[1] != 0.0)) {
    note_drained_face_under_gravity(*drained_table, spec.warnings);
  }
  RigidNames declared_rigid;
  for (const auto& [index, table] : rigid_tables) {
    declared_rigid.insert(spec.bodies[index].name);
  }
  // The moving mesh before the phases, so that a stop_at penetration is checked against its
  // travel whichever way the geometry is given.
  read_moving_mesh(top, spec, axes, declared_rigid);
  refuse_past_memory_budget(top, spec, axes.r, axes.y, body_tables);
  for (std::size_t b = 0; b < body_tables.size(); ++b) {
    const BodySpec& body = spec.bodies[b];
    if (count_body_particles(spec, body) == 0) {
      const std::string n = std::to_string(body.particles_per_direction);
      body_tables[b].fail("region",
                          "body '" + body.name +
                              "' gets no particle: no particle position (the centres of " + n +
                              " x " + n +
                              " sub-cells per cell) lies inside its region; make the "
                              "cells there finer or raise particles_per_cell");
    }
  }
  const bool shape_given =
      top.has("solver") && top.table("solver").has(&SolverSettings::shape_functions);
  if (spec.moving_mesh && shape_given && spec.solver.shape_functions == ShapeFunctions::linear) {
    top.table("solver").fail(
        &SolverSettings::shape_functions,
        "bilinear weights on a moving mesh shake the soil: every line moving under a particle "
        "jolts its nodal forces (soil at rest under a moving band: the base reaction swings by "
        "97 % of the weight; the quick jacked pile's base reaction 1.25 to 3.11 MN/rad against "
        "2.01 to 2.16 on a fixed grid); use \"gimp\", the default with a moving mesh");
  }
  if (spec.moving_mesh && !shape_given) {
    // Lines moving under soil at rest make every particle cross cells; with bilinear weights
    // each crossing jolts the nodal forces and shakes the soil (docs/design.md, "Shape
    // functions"), so a moving mesh takes GIMP unless the case says otherwise.
    spec.solver.shape_functions = ShapeFunctions::gimp;
    if (spec.solver.block_cells < 3) {
      top.table("solver").fail(&SolverSettings::block_cells,
                               "must be at least 3 with GIMP shape functions, the default with a "
                               "moving mesh");
    }
  }
  read_phases(top, spec, declared_rigid);
  read_water(top, spec, axes.y.start());
  if (hydrostatic_drains) {
    read_drained_water(*drained_table, spec);
  }
  for (auto& [name, table] : top.named_tables("materials")) {
    const auto m = std::find_if(spec.materials.begin(), spec.materials.end(),
                                [&](const MaterialSpec& x) { return x.name == name; });
    if (m != spec.materials.end() && m->water.drainage != Drainage::drained) {
      note_pure_flip_in_saturated_soil(table, spec, spec.warnings);
    }
  }
  if (absorbing_table) {
    check_absorbing_phase(*absorbing_table, spec);
  }
  for (auto& [index, table] : rigid_tables) {
    read_rigid_body(table, spec.bodies[index], spec, spec.warnings);
  }
  // After the rigid bodies are known: a pile resting on saturated sand is no dry layer.
  if (spec.solver.gravity[1] != 0.0 && !(spec.water && spec.water->phreatic)) {
    note_dry_soil_over_saturated(spec, body_tables, spec.warnings);
  }
  read_contacts(top, spec);
  read_motions_and_loads(top, spec, axes);
  read_affine_motion(top, spec);
  read_output(top, spec, axes.r, axes.y);
  top.finish();
  return spec;
}

CaseSpec read_case_file(const std::string& path, const std::vector<std::string>& overrides) {
  ComposedCase composed = compose_case(path, overrides);
  CaseSpec spec;
  try {
    spec = read_case_tree(composed.root, composed.text, path);
  } catch (const CaseError& e) {
    // A value in a base file is reported where it is written; the case that was read says how it
    // got there (its own value may be the cause: a phase it renamed).
    const std::string message = e.what();
    if (message.rfind(path, 0) != 0 && message.rfind("--set", 0) != 0) {
      throw CaseError(message + " (read as a base of " + path + ")");
    }
    throw;
  }
  spec.resolved = std::move(composed.resolved);
  spec.overrides = overrides;
  spec.bases = std::move(composed.bases);
  return spec;
}

} // namespace mpile
