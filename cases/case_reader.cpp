// The case file reader: TOML in, a validated CaseSpec out. Strict: unknown keys, missing required
// keys, wrong types and physically invalid values are errors that name file, line, key and reason.
//
// Outline:
//   pieces read in several tables: grid zones, time functions, node lines on grid lines, a
//     component's index, face conditions
//   the tables, each by one function: read_materials, read_bodies (and their rigid drives),
//     read_contacts, read_affine_motion, read_motions_and_loads, read_solver, read_phases
//   refuse_past_memory_budget: a case too large for the machine refused before it is built
//   read_cpt_output, read_output (monitors included)
//   read_pore_water, read_material_table: a material's model, drainage and pore water
//   CaseSpec::end_time
//   read_case_text, read_case_tree (the tables in order, [monopile] or the tables it builds, and
//     the checks across tables), read_case_file (bases and --set overrides)
#include "cases/absorbing_reader.hpp"
#include "cases/case_builder.hpp"
#include "cases/case_composition.hpp"
#include "cases/case_spec.hpp"
#include "cases/case_warnings.hpp"
#include "cases/dataset_name.hpp"
#include "cases/face_list_reader.hpp"
#include "cases/monopile_geometry.hpp"
#include "cases/monopile_reader.hpp"
#include "cases/region_reader.hpp"
#include "cases/toml_reader.hpp"
#include "cases/water_reader.hpp"
#include "engine/particle_bins.hpp"
#include "engine/structures/contact.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <variant>

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

TimeFunction read_time_function(TomlTable& parent, const std::string& key) {
  const TomlValue& raw = parent.raw(key);
  if (raw.is_floating() || raw.is_integer()) {
    return TimeFunction::constant(parent.number(key));
  }
  TomlTable f = parent.table(key);
  using Keys = TimeFunctionKeys;
  Keys k;
  f.read_members(k, {&Keys::type});
  TimeFunction result;
  try {
    // Each type reads its own keys; another type's is left unread and refused by finish().
    if (k.type == "constant") {
      f.read_members(k, {&Keys::value});
      result = TimeFunction::constant(k.value);
    } else if (k.type == "ramp") {
      f.read_members(k, {&Keys::value, &Keys::duration});
      result = TimeFunction::ramp(k.value, k.duration);
    } else if (k.type == "table") {
      const TomlValue& points = f.raw("points");
      std::vector<std::pair<double, double>> table;
      bool ok = points.is_array() && !points.as_array().empty();
      if (ok) {
        for (const TomlValue& point : points.as_array()) {
          if (!point.is_array() || point.as_array().size() != 2) {
            ok = false;
            break;
          }
          const auto& pair = point.as_array();
          auto number = [&](const TomlValue& v) {
            if (v.is_integer()) {
              return static_cast<double>(v.as_integer());
            }
            if (!v.is_floating()) {
              ok = false;
              return 0.0;
            }
            return v.as_floating();
          };
          table.emplace_back(number(pair[0]), number(pair[1]));
        }
      }
      if (!ok) {
        f.fail("points", "expected [[t0, value0], [t1, value1], ...] with numbers");
      }
      try {
        result = TimeFunction::table(std::move(table));
      } catch (const std::invalid_argument& e) {
        f.fail("points", e.what());
      }
    } else if (k.type == "harmonic") {
      f.read_members(k, {&Keys::amplitude, &Keys::frequency, &Keys::phase, &Keys::mean});
      result = TimeFunction::harmonic(k.amplitude, k.frequency, k.phase, k.mean);
    } else { // "pulse_train", the last of the declared types
      f.read_members(k, {&Keys::amplitude, &Keys::duration, &Keys::interval});
      if (k.interval < k.duration) {
        f.fail(&Keys::interval, "must not be shorter than the pulse duration");
      }
      result = TimeFunction::pulse_train(k.amplitude, k.duration, k.interval);
    }
  } catch (const std::invalid_argument& e) {
    f.fail(&Keys::type, e.what());
  }
  f.finish();
  return result;
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

/// Where a key's value was written, as a message quotes it ("case.toml:12").
std::string location(const TomlTable& table, const std::string& key) {
  return table.file_of(key) + ":" + std::to_string(table.line_of(key));
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
    if (const auto clash =
            groups.clash(body.name, location(table, table.key_of(&BodySpec::name)))) {
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

/// The names of the bodies a file declares rigid with a [bodies.rigid] table. Their drives are
/// read after the phases (a drive names its phase), while the phases' stop criteria and the moving
/// mesh name them first.
using RigidNames = std::set<std::string>;

/// `name`, read under `key`, must name a rigid body.
void check_rigid_body_name(const TomlTable& table, const std::string& key, const std::string& name,
                           const CaseSpec& spec, const RigidNames& declared_rigid,
                           const std::string& why) {
  const auto body = std::find_if(spec.bodies.begin(), spec.bodies.end(),
                                 [&](const BodySpec& b) { return b.name == name; });
  if (body == spec.bodies.end() || !(body->rigid || declared_rigid.contains(name))) {
    table.fail(key, "no rigid body named '" + name + "'" + why);
  }
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

/// The drive keys of a rigid body's table or a phase's `drive`: per DOF (RigidDof order) a velocity
/// or a force function, or neither (free).
std::array<std::optional<RigidDrive>, 3> read_drives(TomlTable& table, const CaseSpec& spec,
                                                     std::vector<CaseWarning>& warnings) {
  const bool plane = spec.mode == GeometryMode::plane_strain;
  const char* velocity_keys[] = {"velocity_r", "velocity_y", "angular_velocity"};
  const char* force_keys[] = {"force_r", "force_y", "torque"};
  std::array<std::optional<RigidDrive>, 3> drives;
  for (std::size_t d = 0; d < 3; ++d) {
    const bool velocity = table.has(velocity_keys[d]);
    const bool force = table.has(force_keys[d]);
    if (velocity && force) {
      table.fail(force_keys[d], std::string("give either ") + velocity_keys[d] + " or " +
                                    force_keys[d] + ", not both");
    }
    if (d == RIGID_X && !plane && (velocity || force)) {
      table.fail(velocity ? velocity_keys[d] : force_keys[d],
                 "an axisymmetric rigid body has no radial motion (zero by symmetry)");
    }
    if (velocity || force) {
      RigidDrive drive;
      drive.kind = velocity ? RigidDrive::Kind::velocity : RigidDrive::Kind::force;
      drive.function = read_time_function(table, velocity ? velocity_keys[d] : force_keys[d]);
      drives[d] = drive;
      if (d == RIGID_ROTATION && force) {
        warn_implausible_torque(table, force_keys[d], plane ? "N m/m" : "N m/rad", warnings);
      }
    }
  }
  return drives;
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
        if (const auto clash = groups.clash(surface, location(table, key))) {
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
    if (const auto clash = boundaries.clash(motion.name, location(table, name_key))) {
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

void read_phases(TomlTable& top, CaseSpec& spec, const RigidNames& declared_rigid) {
  std::set<std::string> names;
  for (TomlTable& table : top.tables("phases")) {
    PhaseSpec phase;
    table.read_into(phase);
    // The name heads the phase's log lines and outputs, and `--set phases.<name>` finds it.
    if (phase.name.empty()) {
      table.fail<PhaseSpec>(&PhaseSpec::name, "a phase needs a name (\"\" names none)");
    }
    if (!names.insert(phase.name).second) {
      table.fail<PhaseSpec>(&PhaseSpec::name, "a phase named '" + phase.name + "' already exists");
    }
    {
      // XPIC replaces the FLIP/PIC blend: the phase may not end up with both.
      const int order = phase.xpic_order.value_or(spec.solver.xpic_order);
      const double flip = phase.flip_fraction.value_or(spec.solver.flip_fraction);
      if (order > 0 && flip != 1.0) {
        table.fail(phase.flip_fraction ? table.key_of(&PhaseSpec::flip_fraction)
                                       : table.key_of(&PhaseSpec::xpic_order),
                   "the phase would run XPIC(" + std::to_string(order) + ") with flip_fraction " +
                       format_number(flip) +
                       ": XPIC replaces the FLIP/PIC blend, so set xpic_order = 0 for a blend or "
                       "leave flip_fraction at 1");
      }
    }
    for (TomlTable& k0 : table.tables("k0")) {
      // One body, or every body of one material (the monopile's three soil bodies).
      const bool by_material = k0.has(k0.key_of(&K0Spec::material));
      if (by_material == k0.has(k0.key_of(&K0Spec::body))) {
        k0.fail(&K0Spec::body, "give either body or material (every body of that material)");
      }
      K0Spec init;
      k0.read_into(init);
      k0.finish();
      const auto named = by_material ? &K0Spec::material : &K0Spec::body;
      const std::string name = init.*named;
      bool found = false;
      for (const BodySpec& body : spec.bodies) {
        if ((by_material ? body.material : body.name) == name) {
          init.body = body.name;
          phase.k0.push_back(init);
          found = true;
        }
      }
      if (!found) {
        k0.fail(named,
                "no body " + std::string(by_material ? "of material '" : "named '") + name + "'");
      }
    }
    if (std::optional<TomlTable> stop = table.optional_table("stop_at")) {
      PenetrationStop s;
      stop->read_into(s);
      check_rigid_body_name(*stop, stop->key_of(&PenetrationStop::body), s.body, spec,
                            declared_rigid, "");
      const std::string& penetration = stop->key_of(&PenetrationStop::penetration);
      const std::string& settlement_key = stop->key_of(&PenetrationStop::settlement);
      const bool settlement = stop->has(settlement_key);
      if (settlement == stop->has(penetration)) {
        stop->fail(penetration, "give either penetration (the total downward displacement) or "
                                "settlement (the displacement since the phase started)");
      }
      if (settlement) {
        // The deepest an earlier phase stops at, plus the settlement: how far the band must go
        // at least (an at-rest stop may overshoot; the run then ends the phase at the travel).
        double before = 0.0;
        for (const PhaseSpec& earlier : spec.phases) {
          if (earlier.stop_at && earlier.stop_at->body == s.body) {
            before = std::max(before, earlier.stop_at->penetration);
          }
        }
        s.penetration = before + s.settlement;
      }
      if (spec.moving_mesh && spec.moving_mesh->travel > 0.0 &&
          s.penetration >= spec.moving_mesh->travel) {
        // Equal is refused too: the phase stops after the step that reaches the depth, and that
        // step has already carried the band past its travel.
        std::ostringstream why;
        if (settlement) {
          why << "with the " << s.penetration - s.settlement
              << " m an earlier phase stops at, reaches the travel of the moving band ("
              << spec.moving_mesh->travel << " m); settle less";
        } else {
          why << "reaches the travel of the moving band (" << spec.moving_mesh->travel
              << " m): below that depth the soil is seeded for coarser cells than the band's, and "
                 "the step that reaches it carries the band past it; stop short of it";
        }
        why << " or raise " << (top.has("monopile") ? "[monopile]" : "[moving_mesh]") << " travel";
        stop->fail(settlement ? settlement_key : penetration, why.str());
      }
      stop->finish();
      phase.stop_at = s;
    }
    if (std::optional<TomlTable> drive = table.optional_table("drive")) {
      PhaseDrive d;
      drive->read_into(d);
      check_rigid_body_name(*drive, drive->key_of(&PhaseDrive::body), d.body, spec, declared_rigid,
                            "");
      d.drive = read_drives(*drive, spec, spec.warnings);
      drive->finish();
      phase.drive = d;
    }
    table.finish();
    spec.phases.push_back(std::move(phase));
  }
  if (spec.phases.empty()) {
    top.missing("phases", "at least one [[phases]] table with a duration");
  }
}

/// The memory a case will take, from its grid and its bodies' regions before anything is
/// allocated: refused past the machine's physical memory with the key that drives it (a mistyped
/// cell size or zone took 15 GB and ended in std::bad_alloc).
void refuse_past_memory_budget(TomlTable& top, const CaseSpec& spec, const Axes& axes,
                               std::vector<TomlTable>& body_tables) {
  // Per node: the 64-byte node and its constraint mask, per field; a contact pair's arrays take
  // about 100 bytes more. Per particle: its arrays with a Hardening Soil state, about 300 bytes.
  constexpr double node_bytes = 65.0, pair_node_bytes = 100.0, particle_bytes = 300.0;
  const double nodes =
      static_cast<double>(axes.r.node_count()) * static_cast<double>(axes.y.node_count());
  const auto structures = static_cast<double>(spec.contacts.size());
  const double grid_bytes =
      nodes * (node_bytes * (1.0 + structures) + pair_node_bytes * structures);
  // Particles: the cells of each region's bounding box times the particles per cell (an upper
  // bound short of the graded band's extra seeding).
  std::vector<double> body_bytes;
  double particles_bytes = 0.0;
  for (const BodySpec& body : spec.bodies) {
    const Rectangle& box = body.region.bounds();
    auto cells = [](const GradedAxis& axis, double from, double to) {
      const double a = std::max(from, axis.start()), b = std::min(to, axis.end());
      if (!(b > a)) {
        return 0.0;
      }
      const int first = axis.locate(a);
      const int last = b >= axis.end() ? axis.cell_count() - 1 : axis.locate(b);
      return static_cast<double>(last - first + 1);
    };
    const double n = cells(axes.r, box.r_min, box.r_max) * cells(axes.y, box.y_min, box.y_max) *
                     body.particles_per_direction * body.particles_per_direction;
    body_bytes.push_back(n * particle_bytes);
    particles_bytes += body_bytes.back();
  }
  double physical =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
  // A process limited in address space (ulimit -v, a batch system's memory limit) has less: the
  // budget is three quarters of the limit, the rest left to the program, its libraries and the
  // threads' stacks.
  std::string whose = "this machine's";
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
      0.75 * static_cast<double>(limit.rlim_cur) < physical) {
    physical = 0.75 * static_cast<double>(limit.rlim_cur);
    whose = "three quarters of this process's address-space limit,";
  }
  // A budget set for this process (a machine shared with others, or a sanitizer build, whose
  // address space cannot be limited) bounds it further.
  if (const char* budget = std::getenv("MPILE_MEMORY_BUDGET_MIB")) {
    char* end = nullptr;
    const double mib = std::strtod(budget, &end);
    // A budget that does not parse is an error, not no budget: "2MiB" or "0" switched it off
    // without a word.
    if (end == budget || *end != '\0' || !std::isfinite(mib) || !(mib > 0.0)) {
      throw CaseError(top.file() + ": MPILE_MEMORY_BUDGET_MIB = '" + budget +
                      "' is not a memory budget: give a number of MiB above zero (for example "
                      "2048), or unset it for none");
    }
    if (mib * 1048576.0 < physical) {
      physical = mib * 1048576.0;
      whose = "MPILE_MEMORY_BUDGET_MIB's";
    }
  }
  const double total = grid_bytes + particles_bytes;
  if (!(physical > 0.0) || total <= physical) {
    return;
  }
  std::ostringstream why;
  why << std::setprecision(3) << "the case needs about " << total / 1e9 << " GB ("
      << axes.r.cell_count() << " x " << axes.y.cell_count() << " cells: " << grid_bytes / 1e9
      << " GB; particles: " << particles_bytes / 1e9 << " GB), more than " << whose << " "
      << physical / 1e9 << " GB";
  if (grid_bytes >= particles_bytes || grid_bytes > physical) {
    if (top.has("monopile")) {
      top.table("monopile")
          .fail(&MonopileParameters::fine_cell, why.str() + "; check the cell sizes and extents");
    }
    const bool r_larger = axes.r.cell_count() >= axes.y.cell_count();
    top.table("grid").fail(r_larger ? "r" : "y", why.str() + "; check the zones' cells and ends");
  }
  const auto largest = static_cast<std::size_t>(
      std::max_element(body_bytes.begin(), body_bytes.end()) - body_bytes.begin());
  if (largest < body_tables.size()) {
    body_tables[largest].fail("region",
                              why.str() + "; body '" + spec.bodies[largest].name +
                                  "' takes the most: check its region, the cells there and "
                                  "particles_per_cell");
  }
  top.table("monopile").fail(&MonopileSetup::particles_per_cell, why.str());
}

/// [output.cpt]: the cone and sleeve must be surfaces of a structure's outline with the areas
/// their resistances are quoted over.
OutputSpec::Cpt read_cpt_output(TomlTable& table, const CaseSpec& spec) {
  OutputSpec::Cpt cpt;
  std::vector<std::string> outlined;
  for (const ContactSpec& c : spec.contacts) {
    if (c.outline) {
      outlined.push_back(c.structure);
    }
  }
  table.read_into(cpt);
  if (!table.has(&OutputSpec::Cpt::body)) {
    cpt.body = outlined.size() == 1 ? outlined[0] : "";
  }
  table.finish(); // a misspelt key is named before what its absence caused
  // "" marks an edge that is no contact surface: a cone named so would read the force on none.
  for (std::string OutputSpec::Cpt::*surface : {&OutputSpec::Cpt::cone, &OutputSpec::Cpt::sleeve}) {
    if ((cpt.*surface).empty()) {
      table.fail(surface, "names no surface (\"\" marks an edge that is no contact surface)");
    }
  }
  if (spec.mode != GeometryMode::axisymmetric) {
    table.fail(&OutputSpec::Cpt::cone, "a cone penetration test is axisymmetric: set geometry to "
                                       "\"axisymmetric\"");
  }
  const auto contact = std::find_if(spec.contacts.begin(), spec.contacts.end(),
                                    [&](const ContactSpec& c) { return c.structure == cpt.body; });
  if (contact == spec.contacts.end() || !contact->outline) {
    table.fail(&OutputSpec::Cpt::body,
               "must name the contact structure that is the cone, with outline normals" +
                   std::string(cpt.body.empty() ? "" : " (got '" + cpt.body + "')"));
  }
  if (cpt.cone == cpt.sleeve) {
    table.fail(&OutputSpec::Cpt::sleeve,
               "must be another surface than the cone's ('" + cpt.cone + "')");
  }
  // Surface 0 is the cone, 1 the sleeve, -1 every other edge.
  std::vector<int> edges;
  for (const std::string& name : contact->surfaces) {
    edges.push_back(name == cpt.cone ? 0 : name == cpt.sleeve ? 1 : -1);
  }
  const BodySpec& body = *std::find_if(spec.bodies.begin(), spec.bodies.end(),
                                       [&](const BodySpec& b) { return b.name == cpt.body; });
  const std::vector<SurfaceAreas> areas =
      surface_areas(region_outline(body.region, spec.mode, edges), 2, spec.mode);
  if (!(areas[0].plan > 0.0)) {
    table.fail(&OutputSpec::Cpt::cone,
               "'" + cpt.cone + "' is no surface of '" + cpt.body +
                   "' with a plan area (its horizontal projection, over which q_c is "
                   "quoted)");
  }
  if (!(areas[1].side > 0.0)) {
    table.fail(&OutputSpec::Cpt::sleeve,
               "'" + cpt.sleeve + "' is no surface of '" + cpt.body +
                   "' with a side area (its vertical projection, over which f_s is "
                   "quoted)");
  }
  return cpt;
}

MonitorSpec read_monitor(TomlTable& table, const Axes& axes, const CaseSpec& spec,
                         const std::vector<MonitorSpec>& earlier) {
  MonitorSpec monitor;
  table.read_into(monitor); // its name and particle
  const bool dataset_safe =
      !monitor.name.empty() && std::all_of(monitor.name.begin(), monitor.name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
      });
  if (!dataset_safe) {
    table.fail(&MonitorSpec::name, "use letters, digits and underscores (it names "
                                   "/monitors/<name> in history.h5)");
  }
  for (const MonitorSpec& other : earlier) {
    if (other.name == monitor.name) {
      table.fail(&MonitorSpec::name, "another monitor is named '" + monitor.name + "'");
    }
  }
  const std::string& particle = table.key_of(&MonitorSpec::particle);
  if (table.has("position") == table.has(particle)) {
    table.fail("position", "give either position = [r, y] (the soil particle nearest it at the "
                           "start) or particle = <id>");
  }
  const std::string key = monitor.particle ? particle : "position";
  if (!monitor.particle) {
    const std::vector<double> at = table.numbers("position", 2);
    if (!(at[0] >= axes.r.start() && at[0] <= axes.r.end() && at[1] >= axes.y.start() &&
          at[1] <= axes.y.end())) {
      table.fail("position", "lies outside the grid");
    }
    monitor.position = std::array<double, 2>{at[0], at[1]};
  } else if (*monitor.particle > std::numeric_limits<std::int32_t>::max()) {
    table.fail(particle,
               "must be a particle id (0 or more), got " + std::to_string(*monitor.particle));
  }
  if (monitor.fixed && monitor.particle) {
    table.fail(table.key_of(&MonitorSpec::fixed),
               "a fixed monitor is a point in space: give position = [r, y], not particle");
  }
  if (table.has(&MonitorSpec::material) && monitor.material.empty()) {
    table.fail(&MonitorSpec::material, "names no material (leave it out for the one nearest "
                                       "position at the start)");
  }
  if (!monitor.material.empty()) {
    if (!monitor.fixed) {
      table.fail(&MonitorSpec::material,
                 "names the material of a fixed monitor (fixed = true); a followed one reads its "
                 "particle's");
    }
    // Only a deformable body's particles carry the stress and state a monitor records.
    const bool soil = std::any_of(spec.bodies.begin(), spec.bodies.end(), [&](const BodySpec& b) {
      return b.material == monitor.material && !b.rigid;
    });
    if (!soil) {
      table.fail(&MonitorSpec::material, "no body that is not rigid is made of a material named '" +
                                             monitor.material + "'");
    }
  }
  monitor.where = location(table, key) + ": " + table.key_path(key);
  table.finish();
  return monitor;
}

void read_output(TomlTable& top, CaseSpec& spec, const Axes& axes) {
  std::optional<TomlTable> table = top.optional_table("output");
  if (!table) {
    return;
  }
  OutputSpec& out = spec.output;
  table->read_into(out);
  table->check_path(&OutputSpec::directory, out.directory);
  out.snapshot_times = table->numbers_or("snapshot_times", {});
  for (const double t : out.snapshot_times) {
    if (t < 0.0) {
      table->fail("snapshot_times", "times must not be negative");
    }
  }
  out.snapshot_penetrations = table->numbers_or("snapshot_penetrations", {});
  if (!out.snapshot_penetrations.empty()) {
    for (const double depth : out.snapshot_penetrations) {
      if (!(depth > 0.0)) {
        table->fail("snapshot_penetrations", "penetrations must be positive (m)");
      }
    }
    std::sort(out.snapshot_penetrations.begin(), out.snapshot_penetrations.end());
    std::vector<std::string> rigid;
    for (const BodySpec& body : spec.bodies) {
      if (body.rigid) {
        rigid.push_back(body.name);
      }
    }
    if (!table->has(&OutputSpec::penetration_body)) {
      out.penetration_body = rigid.size() == 1 ? rigid[0] : "";
    }
    if (std::find(rigid.begin(), rigid.end(), out.penetration_body) == rigid.end()) {
      table->fail(&OutputSpec::penetration_body,
                  "must name the rigid body whose penetration counts");
    }
  } else if (table->has(&OutputSpec::penetration_body)) {
    table->fail(&OutputSpec::penetration_body,
                "given without snapshot_penetrations, the penetrations it counts");
  }
  if (std::optional<TomlTable> cpt = table->optional_table("cpt")) {
    out.cpt = read_cpt_output(*cpt, spec);
  }
  for (TomlTable& monitor : table->tables("monitor")) {
    out.monitors.push_back(read_monitor(monitor, axes, spec, out.monitors));
  }
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
          location(table, parameter.name) + ": " + table.key_path(parameter.name);
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
  refuse_past_memory_budget(top, spec, axes, body_tables);
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
  read_output(top, spec, axes);
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
