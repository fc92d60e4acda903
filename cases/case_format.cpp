// Every table and key of a case file, declared once. Defaults that the engine's own structs hold
// (SolverSettings, MonopileParameters, the output and contact settings) are taken from a default-
// constructed struct, so the number lives in one place.
//
// Outline:
//   KeySpec's builders (needed, or_default, ranges, choices) and default_description
//   a key of each kind (number, integer, boolean, string, numbers, time_function, tables, ...)
//   keys shared by several tables: a rigid body's drive, grid zones, node lines, a material's own
//   declare(): the tables in order: top level, grid, materials, bodies (region, velocity_profile,
//     rigid), time_function, contact, monopile, moving_mesh, affine_motion, boundaries, solver,
//     prescribed, loads, phases (k0, stop_at, drive), output (cpt, monitor)
//   case_format, find_table_spec, table_heading: the declaration as the readers and describe see it
#include "cases/case_format.hpp"

#include "cases/case_spec.hpp"
#include "cases/monopile_geometry.hpp"
#include "engine/materials/material_registry.hpp"
#include "engine/particle_bins.hpp"
#include "solver/solver_settings.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <variant>

namespace mpile {

KeySpec KeySpec::needed() && {
  required = true;
  return std::move(*this);
}
KeySpec KeySpec::or_default(DefaultValue value) && {
  fallback = std::move(value);
  return std::move(*this);
}
KeySpec KeySpec::or_computed(std::string text) && {
  default_text = std::move(text);
  return std::move(*this);
}
KeySpec KeySpec::above(double value) && {
  range.lower = Bound{value, false};
  return std::move(*this);
}
KeySpec KeySpec::at_least(double value) && {
  range.lower = Bound{value, true};
  return std::move(*this);
}
KeySpec KeySpec::below(double value) && {
  range.upper = Bound{value, false};
  return std::move(*this);
}
KeySpec KeySpec::at_most(double value) && {
  range.upper = Bound{value, true};
  return std::move(*this);
}
KeySpec KeySpec::one_of(std::vector<std::string> values) && {
  choices = std::move(values);
  return std::move(*this);
}
KeySpec KeySpec::length(std::size_t n) && {
  count = n;
  return std::move(*this);
}

std::string KeySpec::default_description() const {
  if (required) {
    return "required";
  }
  struct Text {
    std::string operator()(std::monostate) const { return ""; }
    std::string operator()(double x) const { return format_bound(x); }
    std::string operator()(long x) const { return std::to_string(x); }
    std::string operator()(bool x) const { return x ? "true" : "false"; }
    std::string operator()(const std::string& x) const { return "\"" + x + "\""; }
  };
  const std::string given = std::visit(Text{}, fallback);
  if (!given.empty()) {
    return given;
  }
  return default_text.empty() ? "none" : default_text;
}

namespace {

KeySpec make(std::string name, ValueKind kind, std::string unit, std::string meaning) {
  KeySpec k;
  k.name = std::move(name);
  k.kind = kind;
  k.unit = std::move(unit);
  k.meaning = std::move(meaning);
  return k;
}

} // namespace

KeySpec number(std::string name, std::string unit, std::string meaning) {
  return make(std::move(name), ValueKind::number, std::move(unit), std::move(meaning));
}
KeySpec integer(std::string name, std::string meaning) {
  return make(std::move(name), ValueKind::integer, "", std::move(meaning));
}
KeySpec boolean(std::string name, std::string meaning) {
  return make(std::move(name), ValueKind::boolean, "", std::move(meaning));
}
KeySpec string(std::string name, std::string meaning) {
  return make(std::move(name), ValueKind::string, "", std::move(meaning));
}
KeySpec numbers(std::string name, std::string unit, std::string meaning) {
  return make(std::move(name), ValueKind::numbers, std::move(unit), std::move(meaning));
}
KeySpec time_function(std::string name, std::string unit, std::string meaning) {
  return make(std::move(name), ValueKind::time_function, std::move(unit), std::move(meaning));
}
KeySpec table(std::string name, std::string meaning) {
  return make(std::move(name), ValueKind::table, "", std::move(meaning));
}
KeySpec tables(std::string name, std::string meaning) {
  return make(std::move(name), ValueKind::tables, "", std::move(meaning));
}
KeySpec named_tables(std::string name, std::string meaning) {
  return make(std::move(name), ValueKind::named_tables, "", std::move(meaning));
}
KeySpec strings(std::string name, std::string meaning) {
  return make(std::move(name), ValueKind::strings, "", std::move(meaning));
}
KeySpec any(std::string name, std::string unit, std::string meaning) {
  return make(std::move(name), ValueKind::any, std::move(unit), std::move(meaning));
}

const KeySpec* TableSpec::key(std::string_view name) const {
  const auto found =
      std::find_if(keys.begin(), keys.end(), [&](const KeySpec& k) { return k.name == name; });
  return found == keys.end() ? nullptr : &*found;
}

namespace {

const char* const first_phase = "the first phase";

/// The drive keys of a rigid body: one per DOF, a velocity or a force.
std::vector<KeySpec> drive_keys() {
  return {
      time_function("velocity_y", "m/s",
                    "prescribed vertical velocity (the force it takes is recorded); or force_y"),
      time_function("force_y", "N/rad", "applied vertical force (N/m in plane strain)"),
      time_function("angular_velocity", "rad/s",
                    "prescribed spin about the axis (in plane strain, in-plane about the centre); "
                    "or torque"),
      time_function("torque", "N m/rad",
                    "applied torque about the axis, per radian: the seed's \"kN m/rad\""),
      time_function("velocity_r", "m/s", "plane strain only: prescribed horizontal velocity"),
      time_function("force_r", "N/m", "plane strain only: applied horizontal force"),
  };
}

std::vector<KeySpec> zone_keys() {
  return {number("start", "m", "where the zone starts").needed().into(&AxisZone::start),
          number("end", "m", "where it ends, greater than start").needed().into(&AxisZone::end),
          integer("cells", "uniform cells in the zone")
              .needed()
              .at_least(1)
              .at_most(100000)
              .into(&AxisZone::cells)};
}

std::vector<KeySpec> node_line_keys() {
  return {any("r", "m",
              "a grid line r = value (the nodes along it), or with y = value a range [from, to]"),
          any("y", "m",
              "a grid line y = value (the nodes along it), or with r = value a range [from, to]")};
}

/// A material's own keys: its model, its drainage and its pore water (PoreWater's declaration).
std::vector<KeySpec> material_keys(const std::vector<std::string>& material_names) {
  std::vector<KeySpec> keys{
      string("type", "the material model")
          .needed()
          .one_of(material_names)
          .into(&MaterialSpec::type),
      string("drainage",
             "how the pore water drains: \"drained\" (no water state: a dry or drained soil, "
             "`density` its density), \"undrained\" (saturated, no flow: the water's stiffness "
             "K_w / n at each material point, PLAXIS's Undrained A) or \"coupled\" (saturated, "
             "the water flows through the skeleton against Darcy's drag: two-phase, with "
             "`hydraulic_conductivity`); saturated, `density` is the dry density and the "
             "particles weigh the saturated density")
          .or_default(std::string("drained"))
          .one_of(drainage_names())
          .choice_into(&PoreWater::drainage)};
  const PoreWater defaults;
  for (const PoreWaterParameter& w : pore_water_parameters()) {
    // The hydraulic conductivity has no default: a coupled material must give it.
    const bool conductivity = w.member == &PoreWater::hydraulic_conductivity;
    KeySpec key =
        conductivity
            ? number(w.name, w.unit, w.meaning).or_computed("none")
            : number(w.name, w.unit, w.meaning + "; saturated only").or_default(defaults.*w.member);
    key.range = w.range;
    keys.push_back(std::move(key).into(w.member));
  }
  return keys;
}

/// A setting's key from its declaration (solver/solver_settings.cpp): kind, unit, meaning, range,
/// and the default SolverSettings gives it (or the text of the default the solver computes).
KeySpec solver_key(const SolverParameter& p, const SolverSettings& defaults) {
  KeySpec key = std::visit(
      [&](auto member) {
        using Value = std::remove_cvref_t<decltype(defaults.*member)>;
        // Bound to its member of SolverSettings ([[phases]] binds its own to PhaseSpec's).
        if constexpr (std::is_same_v<Value, bool>) {
          return boolean(p.name, p.meaning).or_default(defaults.*member).into(member);
        } else if constexpr (std::is_same_v<Value, int>) {
          return integer(p.name, p.meaning)
              .or_default(static_cast<long>(defaults.*member))
              .into(member);
        } else {
          KeySpec k = number(p.name, p.unit, p.meaning);
          return (p.computed_default.empty() ? std::move(k).or_default(defaults.*member)
                                             : std::move(k).or_computed(p.computed_default))
              .into(member);
        }
      },
      p.member);
  key.range = p.range;
  return key;
}

/// A phase's override of a [solver] setting: the setting's kind and range, no default of its own.
KeySpec phase_override(std::string_view name) {
  const SolverParameter& p = solver_parameter(name);
  KeySpec key = std::holds_alternative<int SolverSettings::*>(p.member)
                    ? integer(p.name, "override of [solver]")
                    : number(p.name, p.unit, "override of [solver]");
  key.range = p.range;
  return std::move(key).or_computed("[solver] value");
}

/// [solver]: the declared settings, with the keys that are not a plain member between them.
std::vector<KeySpec> solver_keys() {
  const SolverSettings solver;
  std::vector<KeySpec> keys;
  for (const SolverParameter& p : solver_parameters()) {
    if (p.per_phase) {
      continue;
    }
    keys.push_back(solver_key(p, solver));
    if (p.name == "cell_mean_pore_pressure") {
      keys.push_back(string("scheme", "\"musl\" (strains from remapped velocities) or \"usl\"")
                         .one_of({"musl", "usl"})
                         .choice_into(&SolverSettings::musl, "musl"));
    } else if (p.name == "mass_scaling") {
      keys.push_back(
          numbers("gravity", "m/s^2", "gravitational acceleration (r, y), e.g. [0, -9.81]")
              .length(2)
              .or_computed("[0, 0]"));
    } else if (p.name == "block_cells") {
      keys.push_back(
          string("shape_functions", "\"linear\" or \"gimp\" (averaged over the particle's domain)")
              .one_of({"linear", "gimp"})
              .or_computed("\"linear\", \"gimp\" with a moving mesh")
              .choice_into(&SolverSettings::shape_functions));
    }
  }
  return keys;
}

std::vector<TableSpec> declare() {
  const SolverSettings solver;
  const MonopileParameters pile;
  const OutputSpec output;
  const OutputSpec::Cpt cpt;
  std::vector<std::string> material_names;
  for (const MaterialType& type : material_types()) {
    material_names.push_back(type.name);
  }
  std::vector<std::string> faces{"free", "roller", "fixed"};

  std::vector<TableSpec> t;
  t.push_back(
      {"",
       "The top level of a case file.",
       {string("base", "a case file this one is read over (relative to this file), or a list of "
                       "them merged in order: tables merge key by key (a table of another type "
                       "replaces the base's), other values replace the base's")
            .or_computed("none"),
        string("title", "shown in the log and stored in history.h5")
            .or_computed("the file name")
            .into(&CaseSpec::title),
        string("geometry", "\"axisymmetric\" (with the theta DOF; outputs per radian) or "
                           "\"plane_strain\" (outputs per metre)")
            .or_default(std::string("axisymmetric"))
            .one_of({"axisymmetric", "plane_strain"})
            .choice_into(&CaseSpec::mode),
        table("grid", "the grid's zones along r and y; required unless [monopile] builds it"),
        named_tables("materials", "the materials, by name").needed(),
        tables("bodies", "the bodies; required unless [monopile] builds them"),
        tables("contact", "soil-structure contact, one entry per structure"),
        table("monopile", "the seed's monopile model from a few parameters, instead of grid, "
                          "bodies, contact, boundaries and moving_mesh"),
        table("boundaries", "conditions on the grid's faces"), table("solver", "numerical choices"),
        table("moving_mesh", "y-lines that follow a rigid body"),
        tables("prescribed", "prescribed velocities on a grid line"),
        table("affine_motion", "a velocity linear in position on every node (patch tests)"),
        tables("loads", "distributed tractions on a grid line"),
        tables("phases", "the phases, run in order").needed(),
        table("water", "the sea above a saturated seabed; the pore water's cavitation"),
        table("output", "what is written, and when")},
       false});
  t.push_back(
      {"water",
       "The sea above the seabed and the pore water's cavitation, for saturated (undrained or "
       "coupled) soil (physics.md section 9c). The sea is its pressure: p_s = rho_w g (level - "
       "seabed) on the seabed and on the soil inside an open pile, in every pore below, and, "
       "through the seabed, on a rigid body's cross-section there (its uplift).",
       {number("level", "m",
               "y of the sea's free surface, at or above the seabed (the K0 surface of the "
               "saturated bodies); the pore pressures and total stresses written are then "
               "relative to the atmosphere")
            .or_computed("the seabed: no sea above it")
            .into(&WaterSpec::level),
        number("table", "m",
               "y of a water table inside the soil, instead of a sea: the saturated bodies lie "
               "below it, dry (or moist) ones above; the K0 procedure weighs every layer above "
               "a point (its bodies' K0 surface the ground's) and takes the pore water "
               "hydrostatic from the table")
            .or_computed("none")
            .into(&WaterSpec::table),
        number("cavitation_stress", "Pa",
               "the tension, relative to the atmosphere, at which the pore water cavitates: its "
               "pressure rises no further (100e3: the atmosphere's pressure, water's vapour "
               "pressure neglected)")
            .at_least(0.0)
            .or_computed("no cut-off")
            .into(&PoreWater::cavitation_stress)},
       false});
  t.push_back({"grid",
               "The grid: zones of uniform cells along r (x in plane strain) and y, contiguous.",
               {tables("r", "zones along r, from the smallest r").needed(),
                tables("y", "zones along y, from the bottom").needed()},
               false});
  t.push_back({"grid.r", "A zone of the grid along r.", zone_keys(), false});
  t.push_back({"grid.y", "A zone of the grid along y.", zone_keys(), false});
  t.push_back({"materials.*",
               "A material: its model (`type`), how its pore water drains, and that model's "
               "parameters (below).",
               material_keys(material_names), true});
  t.push_back(
      {"bodies",
       "A body: a region of one material filled with particles.",
       {string("name", "unique name").needed().into(&BodySpec::name),
        string("material", "a [materials.<name>]").needed().into(&BodySpec::material),
        table("region", "its shape, inside the grid").needed(),
        integer("particles_per_cell", "particles per cell direction (2 gives 4 per cell)")
            .at_least(1)
            .at_most(8)
            .into(&BodySpec::particles_per_direction),
        string("seeding",
               "\"centres\": a particle at each sub-cell centre in the region; \"cut_cells\": "
               "also the sub-cells the outline cuts, each a particle of the part inside")
            .or_default(std::string("centres"))
            .one_of({"centres", "cut_cells"})
            .choice_into(&BodySpec::cut_cells),
        numbers("velocity", "m/s", "initial velocity (v_r, v_y, v_theta)")
            .length(3)
            .or_computed("[0, 0, 0]"),
        table("velocity_profile",
              "an initial velocity varying along one direction, added to velocity"),
        table("rigid", "makes the body rigid, with its drives")},
       false});
  t.push_back({"bodies.region",
               "One shape: a rectangle (r and y), a polygon or a circle.",
               {numbers("r", "m", "a rectangle's [r_min, r_max]").length(2),
                numbers("y", "m", "a rectangle's [y_min, y_max]").length(2),
                any("polygon", "m",
                    "[[r0, y0], [r1, y1], ...]: at least 3 vertices of a simple polygon, either "
                    "orientation, not closed by repeating the first"),
                table("circle", "a circle (a torus or, centred on the axis, a sphere)")},
               false});
  t.push_back({"bodies.region.circle",
               "A circle.",
               {numbers("centre", "m", "[r, y]").length(2).needed(),
                number("radius", "m", "its radius; off the axis at most the centre's r")
                    .needed()
                    .above(0.0)
                    .into(&CircleSpec::radius)},
               false});
  t.push_back(
      {"bodies.velocity_profile",
       "An initial velocity component as a function of position along r or y.",
       {string("component", "the velocity component")
            .needed()
            .one_of({"r", "y", "theta"})
            .choice_into(&VelocityProfile::component),
        string("along", "the coordinate the function's argument is")
            .needed()
            .one_of({"r", "y"})
            .choice_into(&VelocityProfile::along_y),
        time_function("function", "m/s", "the velocity as a function of position (m)").needed()},
       false});
  {
    std::vector<KeySpec> keys{
        number("mass", "kg/rad", "the whole structure's mass (kg/m in plane strain)")
            .above(0.0)
            .or_computed("from the particles")
            .into(&RigidSpec::mass),
        number("polar_inertia", "kg m^2/rad", "axisymmetric: the moment of inertia about the axis")
            .above(0.0)
            .or_computed("from the particles")
            .into(&RigidSpec::polar_inertia),
        number("inertia", "kg m^2/m", "plane strain: the moment of inertia about the centre")
            .above(0.0)
            .or_computed("from the particles")
            .into(&RigidSpec::inertia)};
    for (KeySpec& k : drive_keys()) {
      keys.push_back(std::move(k));
    }
    keys.push_back(string("phase", "the phase in which the drives start (their functions count "
                                   "time from its start); before it every DOF is held at rest")
                       .or_computed(first_phase)
                       .into(&RigidSpec::phase));
    t.push_back({"bodies.rigid", "A rigid body's mass, inertia and drives.", keys, false});
  }
  t.push_back(
      {"time_function",
       "A function of time (or, in a velocity_profile, of position): a number is a constant; a "
       "table has a `type` and that type's keys.",
       {string("type", "constant: value; ramp: value, duration; table: points; harmonic: "
                       "amplitude, frequency, phase, mean; pulse_train: amplitude, duration, "
                       "interval")
            .needed()
            .one_of({"constant", "ramp", "table", "harmonic", "pulse_train"})
            .into(&TimeFunctionKeys::type),
        // No default: the types that take a key need it (TomlTable::read_members).
        number("value", "", "constant: the value; ramp: the value reached after duration")
            .or_computed("none")
            .into(&TimeFunctionKeys::value),
        number("duration", "s", "ramp: its rise time; pulse_train: one half-sine pulse's length")
            .above(0.0)
            .or_computed("none")
            .into(&TimeFunctionKeys::duration),
        any("points", "",
            "table: [[t0, v0], [t1, v1], ...], times strictly increasing; v0 "
            "before t0, the last value after the last time"),
        number("amplitude", "",
               "harmonic: mean + amplitude sin(2 pi frequency t + phase); "
               "pulse_train: the pulses' peak")
            .or_computed("none")
            .into(&TimeFunctionKeys::amplitude),
        number("frequency", "Hz", "harmonic: its frequency")
            .above(0.0)
            .or_computed("none")
            .into(&TimeFunctionKeys::frequency),
        number("phase", "rad", "harmonic: its phase angle")
            .or_default(0.0)
            .into(&TimeFunctionKeys::phase),
        number("mean", "",
               "harmonic: the value it oscillates about (a static load beside a vibration)")
            .or_default(0.0)
            .into(&TimeFunctionKeys::mean),
        number("interval", "s",
               "pulse_train: time from one pulse's start to the next's, at "
               "least duration")
            .above(0.0)
            .or_computed("none")
            .into(&TimeFunctionKeys::interval)},
       false});
  const ContactSpec contact;
  t.push_back(
      {"contact",
       "Contact between the soil and one structure body (Bardenhagen, Coulomb friction and "
       "adhesion).",
       {string("structure", "a [[bodies]] name (rigid or deformable)")
            .needed()
            .into(&ContactSpec::structure),
        number("friction", "-", "Coulomb coefficient mu = tan(delta)")
            .at_least(0.0)
            .into(&ContactSpec::friction),
        number("adhesion", "Pa", "adhesion c_a").at_least(0.0).into(&ContactSpec::adhesion),
        string("normals", "\"outline\": from the outline of the structure's region (a polygon must "
                          "be convex); \"mass_gradient\": from the structure's particles")
            .or_default(std::string("outline"))
            .one_of({"outline", "mass_gradient"})
            .choice_into(&ContactSpec::outline, "outline"),
        string("gap",
               "outline only: \"cells\": a node may be in contact once any soil particle of its "
               "cells touches the outline; \"surface\": on a straight run of one surface along r "
               "or y, once the soil's surface interpolated to the node does")
            .or_default(std::string("cells"))
            .one_of({"cells", "surface"})
            .choice_into(&ContactSpec::surface_gap),
        any("surfaces", "",
            "outline only: a rectangle's edges named in a table { bottom, right, top, left } (an "
            "edge left out is no contact surface); a polygon's, one name per edge in an array "
            "(\"\" for none); at most 8 surfaces")
            .or_computed("a rectangle's four edges, named bottom, right, top, left"),
        string("surface", "the single surface's name: mass-gradient normals, or a circle's outline")
            .or_computed("\"interface\" (mass gradient), \"surface\" (circle)")
            .into(&ContactSpec::surface)},
       false});
  {
    std::vector<KeySpec> edges;
    const char* names[] = {"bottom", "right", "top", "left"}; // rectangle_edges' order
    for (std::size_t e = 0; e < rectangle_edges.size(); ++e) {
      edges.push_back(string(names[e], std::string("the surface the rectangle's ") + names[e] +
                                           " edge belongs to")
                          .or_computed("no contact surface")
                          .into(rectangle_edges[e]));
    }
    t.push_back({"contact.surfaces", "A rectangle's contact surfaces, by edge.", edges, false});
  }
  t.push_back(
      {"monopile",
       "The seed paper's model (its section 3): soil from the axis to soil_width and from y = 0 to "
       "soil_depth, an open-ended rigid pile, a graded grid with a band that moves with the pile.",
       {number("pile_length", "m", "the whole pile's length (its mass and polar inertia)")
            .into(&MonopileParameters::pile_length)
            .above(0.0),
        number("diameter", "m", "outer diameter D").into(&MonopileParameters::diameter).above(0.0),
        number("wall_thickness", "m", "wall thickness t, below D / 2")
            .into(&MonopileParameters::wall_thickness)
            .above(0.0),
        number("embedment", "m", "initial depth of the tip below the surface, below pile_length")
            .into(&MonopileParameters::embedment)
            .above(0.0),
        number("soil_width", "m", "the soil's radius (the roller face)")
            .into(&MonopileParameters::soil_width)
            .above(0.0),
        number("soil_depth", "m", "the soil's depth (the fixed base at y = 0)")
            .into(&MonopileParameters::soil_depth)
            .above(0.0),
        number("head_room", "m", "grid above the surface (the meshed pile top stays above heave)")
            .into(&MonopileParameters::head_room)
            .above(0.0),
        string("soil_material", "the soil's [materials.<name>]")
            .needed()
            .into(&MonopileSetup::soil_material),
        string("pile_material", "the pile's [materials.<name>]; gives the density")
            .needed()
            .into(&MonopileSetup::pile_material),
        number("friction", "-", "contact mu = tan(delta) (0.4 = tan 21.8 deg)")
            .or_default(0.4)
            .at_least(0.0)
            .into(&ContactSpec::friction),
        number("adhesion", "Pa", "contact adhesion c_a")
            .or_default(0.0)
            .at_least(0.0)
            .into(&ContactSpec::adhesion),
        integer("particles_per_cell", "per direction")
            .or_default(2L)
            .at_least(1)
            .at_most(8)
            .into(&MonopileSetup::particles_per_cell),
        number("fine_cell", "m", "cell size at the wall and in the band")
            .into(&MonopileParameters::fine_cell)
            .above(0.0),
        number("fine_width", "m", "uniform fine cells on each side of the wall")
            .into(&MonopileParameters::fine_width)
            .at_least(0.0),
        integer("wall_cells", "cells across the wall; more than 1 grades from t / wall_cells at "
                              "the wall and tip to fine_cell")
            .into(&MonopileParameters::wall_cells)
            .at_least(1)
            .at_most(16),
        number("shaft_cell", "m", "the largest cell along the shaft, at least fine_cell")
            .into(&MonopileParameters::shaft_cell)
            .above(0.0),
        number("coarse_cell", "m", "the largest cell far from the pile, at least fine_cell")
            .into(&MonopileParameters::coarse_cell)
            .above(0.0),
        number("growth", "-", "size ratio of neighbouring cells where the mesh coarsens")
            .into(&MonopileParameters::growth)
            .at_least(1.0)
            .at_most(2.0),
        number("band_below", "m", "the band moving with the pile reaches this far below the tip")
            .into(&MonopileParameters::band_below)
            .above(0.0),
        number("band_above", "m", "and this far above it")
            .into(&MonopileParameters::band_above)
            .above(0.0),
        number("travel", "m",
               "how far the band may be carried down (the soil below is seeded "
               "for the cells it will then have)")
            .into(&MonopileParameters::travel)
            .above(0.0),
        boolean("moving_mesh", "false: the grid stays fixed (for comparison)")
            .or_default(true)
            .into(&MonopileSetup::moving_mesh),
        strings("absorbing", "faces that let waves out, as in [boundaries]")
            .one_of({"r_min", "r_max", "y_min", "y_max"})
            .or_computed("none"),
        string("absorbing_phase", "the phase at whose start the absorbing faces switch on")
            .or_computed(first_phase)
            .into(&CaseSpec::Absorbing::phase),
        table("drive", "the pile's drives: the keys of [bodies.rigid] but mass and inertia")},
       false});
  {
    std::vector<KeySpec> keys = drive_keys();
    keys.push_back(number("mass", "kg/rad", "not allowed: follows from the parameters")
                       .or_computed("none")
                       .into(&RigidSpec::mass));
    keys.push_back(number("polar_inertia", "kg m^2/rad", "not allowed: follows from the parameters")
                       .or_computed("none")
                       .into(&RigidSpec::polar_inertia));
    keys.push_back(string("phase", "the phase in which the drives start")
                       .or_computed(first_phase)
                       .into(&RigidSpec::phase));
    t.push_back({"monopile.drive", "The monopile's drives.", keys, false});
  }
  t.push_back(
      {"moving_mesh",
       "y-lines that translate with a rigid body; the lines beyond are squeezed and stretched.",
       {string("body", "a rigid body (axisymmetric cases)").needed().into(&MovingMeshSpec::body),
        numbers("band", "m",
                "[y_bottom, y_top], grid lines strictly inside the grid: the lines "
                "between them move with the body")
            .length(2)
            .needed(),
        number("travel", "m",
               "how far the band may move; the soil is seeded for the finest "
               "cells it will sit in")
            .above(0.0)
            .or_computed("until a zone beside the band is squeezed to a tenth")
            .into(&MovingMeshSpec::travel),
        numbers("stretch", "m",
                "[y_bottom, y_top], grid lines below and above the band: only "
                "the lines between them and the band move")
            .length(2)
            .or_computed("the grid's bottom and top")},
       false});
  t.push_back({"affine_motion",
               "Every grid node moves with v = L x for the whole run, whatever its supports: a "
               "patch test, whose every particle must reach the uniform strain L t.",
               {numbers("velocity_gradient", "1/s",
                        "L as [dv_r/dr, dv_r/dy, dv_y/dr, dv_y/dy] (x for r in plane strain)")
                    .length(4)
                    .needed()},
               false});
  {
    std::vector<KeySpec> keys;
    const std::pair<const char*, FaceCondition FaceConditions::*> conditions[] = {
        {"r_min", &FaceConditions::r_min},
        {"r_max", &FaceConditions::r_max},
        {"y_min", &FaceConditions::y_min},
        {"y_max", &FaceConditions::y_max}};
    for (const auto& [face, member] : conditions) {
      keys.push_back(string(face, std::string("the condition on the face ") + face +
                                      ": \"roller\" holds the normal velocity, \"fixed\" all")
                         .or_default(std::string("free"))
                         .one_of(faces)
                         .choice_into(member));
    }
    keys.push_back(strings("absorbing", "faces that let waves out (viscous dashpots from "
                                        "absorbing_phase on), each once")
                       .one_of({"r_min", "r_max", "y_min", "y_max"})
                       .or_computed("none"));
    keys.push_back(strings("drained", "held faces the pore water of coupled soil flows out "
                                      "through (p = 0 beyond them); other held faces are "
                                      "impermeable, a free face drains already")
                       .one_of({"r_min", "r_max", "y_min", "y_max"})
                       .or_computed("none"));
    keys.push_back(string("drained_pressure",
                          "the pore pressure beyond the drained faces: \"zero\" (an open drain: "
                          "under gravity a column empties through it) or \"hydrostatic\" (the far "
                          "field's water, at rest below the saturated soil's surface: [water] "
                          "seabed or the saturated bodies' K0 surface)")
                       .or_default(std::string("zero"))
                       .one_of({"zero", "hydrostatic"})
                       .choice_into(&FaceConditions::hydrostatic_drains, "hydrostatic"));
    keys.push_back(string("absorbing_phase", "the phase at whose start the absorbing faces "
                                             "switch on")
                       .or_computed(first_phase)
                       .into(&CaseSpec::Absorbing::phase));
    t.push_back({"boundaries", "Conditions on the grid's faces.", keys, false});
  }
  t.push_back({"solver", "Numerical choices.", solver_keys(), false});
  t.push_back(
      {"prescribed",
       "Prescribed velocities on a grid line; the reaction goes to /boundaries/<name>/.",
       {string("name", "unique").needed().into(&MotionSpec::name),
        table("nodes", "the grid line").needed(),
        time_function("velocity_r", "m/s", "the radial velocity"),
        time_function("velocity_y", "m/s", "the vertical velocity"),
        time_function("velocity_theta", "m/s", "the circumferential velocity"),
        time_function("angular_velocity", "rad/s",
                      "instead of velocity_theta: v_theta = omega r (a rigid rotation)"),
        string("phase", "the phase in which the motion starts; before it the DOFs are held")
            .or_computed(first_phase)
            .into(&MotionSpec::phase),
        string("body", "a deformable contact structure whose field alone the motion acts on")
            .or_computed("every field")
            .into(&MotionSpec::body)},
       false});
  t.push_back({"prescribed.nodes", "A grid line, or part of it.", node_line_keys(), false});
  t.push_back({"loads",
               "A distributed traction on a grid line, with consistent nodal weights.",
               {string("name", "unique").needed().into(&LoadSpec::name),
                table("nodes", "the grid line").needed(),
                string("component", "the traction's direction")
                    .needed()
                    .one_of({"r", "y", "theta"})
                    .choice_into(&LoadSpec::component),
                time_function("traction", "Pa", "positive along the component's axis").needed(),
                string("phase", "the phase in which the load starts; zero before")
                    .or_computed(first_phase)
                    .into(&LoadSpec::phase)},
               false});
  t.push_back({"loads.nodes", "A grid line, or part of it.", node_line_keys(), false});
  t.push_back(
      {"phases",
       "A phase of the run; each starts where the previous ended.",
       {string("name", "unique").needed().into<PhaseSpec>(&PhaseSpec::name),
        number("duration", "s", "the longest the phase can last")
            .needed()
            .above(0.0)
            .into<PhaseSpec>(&PhaseSpec::duration),
        solver_key(solver_parameter("local_damping"), SolverSettings{})
            .into(&PhaseSpec::local_damping),
        boolean("gravity", "whether [solver] gravity acts").into(&PhaseSpec::gravity),
        number("equilibrium_tolerance", "-",
               "end early once out-of-balance force and kinetic energy fall below this fraction of "
               "the forces holding the state and of the external work")
            .above(0.0)
            .or_computed("none")
            .into<PhaseSpec>(&PhaseSpec::equilibrium_tolerance),
        phase_override("flip_fraction").into(&PhaseSpec::flip_fraction),
        phase_override("xpic_order").into(&PhaseSpec::xpic_order),
        phase_override("mass_scaling").into(&PhaseSpec::mass_scaling),
        phase_override("courant_number").into(&PhaseSpec::courant_number),
        tables("k0", "K0 procedures at the phase start"),
        table("stop_at", "end the phase once a rigid body has penetrated"),
        table("drive", "a rigid body's drives from this phase's start")},
       false});
  t.push_back(
      {"phases.k0",
       "A K0 procedure: sigma_yy = -(surcharge + rho g (surface - y)), sigma_rr = sigma_thth = K0 "
       "sigma_yy, for one body or every body of one material.",
       {string("body", "the body; or material").or_computed("none").into(&K0Spec::body),
        string("material", "every body of this material; or body")
            .or_computed("none")
            .into(&K0Spec::material),
        number("surface", "m", "y of the soil surface").needed().into(&K0Spec::surface),
        number("k0", "-", "K0").needed().above(0.0).into(&K0Spec::k0),
        number("surcharge", "Pa", "a surface load q").at_least(0.0).into(&K0Spec::surcharge)},
       false});
  t.push_back(
      {"phases.stop_at",
       "End the phase once a rigid body has gone down far enough.",
       {string("body", "a rigid body").needed().into(&PenetrationStop::body),
        number("penetration", "m", "its total downward displacement; or settlement")
            .above(0.0)
            .or_computed("none")
            .into(&PenetrationStop::penetration),
        number("settlement", "m", "its downward displacement since the phase began (a load test)")
            .above(0.0)
            .or_computed("none")
            .into(&PenetrationStop::settlement),
        boolean("at_rest", "also wait until the body has come to rest (below 1 mm/s)")
            .or_default(false)
            .into(&PenetrationStop::at_rest)},
       false});
  {
    std::vector<KeySpec> keys{string("body", "a rigid body").needed().into(&PhaseDrive::body)};
    for (KeySpec& k : drive_keys()) {
      keys.push_back(std::move(k));
    }
    t.push_back({"phases.drive", "A rigid body's drives from this phase's start.", keys, false});
  }
  t.push_back(
      {"output",
       "What the run writes, and when.",
       {string("directory", "where outputs go (mpile run --out overrides it)")
            .or_computed("out/<case file name>")
            .into(&OutputSpec::directory),
        number("snapshot_interval", "s",
               "simulated time between particle snapshots; 0: only the "
               "first and the last")
            .into(&OutputSpec::snapshot_interval)
            .at_least(0.0),
        numbers("snapshot_times", "s", "further snapshot times; steps land on them")
            .or_computed("none"),
        number("history_interval", "s", "time between history rows; 0: every step")
            .into(&OutputSpec::history_interval)
            .at_least(0.0),
        number("checkpoint_interval", "s",
               "simulated time between checkpoints; 0: only when the "
               "run stops")
            .into(&OutputSpec::checkpoint_interval)
            .at_least(0.0),
        boolean("grid_snapshots",
                "also write the grid at every snapshot (nodal mass, velocity and contact)")
            .into(&OutputSpec::grid_snapshots),
        numbers("snapshot_penetrations", "m",
                "further snapshots when a rigid body's penetration "
                "first reaches each value")
            .or_computed("none"),
        string("penetration_body", "the body whose penetration snapshot_penetrations counts")
            .or_computed("the only rigid body")
            .into(&OutputSpec::penetration_body),
        table("cpt", "a cone penetration test's q_c, f_s and R_f in the history"),
        tables("monitor", "material points followed through the run")},
       false});
  t.push_back({"output.cpt",
               "A cone penetration test's /cpt/q_c, /cpt/f_s and /cpt/R_f (axisymmetric cases).",
               {string("body", "the contact structure that is the cone")
                    .or_computed("the only structure with outline normals")
                    .into(&OutputSpec::Cpt::body),
                string("cone", "its surface whose plan area q_c is quoted over")
                    .into(&OutputSpec::Cpt::cone),
                string("sleeve", "its surface whose side area f_s is quoted over")
                    .into(&OutputSpec::Cpt::sleeve)},
               false});
  t.push_back(
      {"output.monitor",
       "A material point followed through the run (/monitors/<name>/ in the history).",
       {string("name", "letters, digits and underscores; unique").needed().into(&MonitorSpec::name),
        numbers("position", "m",
                "[r, y]: the soil particle nearest this point at the "
                "start; or particle")
            .length(2),
        integer("particle", "the particle with this id; or position")
            .at_least(0)
            .into(&MonitorSpec::particle),
        boolean("fixed",
                "true: position is a point fixed in space (a transducer), read as the soil "
                "particles' average around it at every row")
            .or_default(false)
            .into(&MonitorSpec::fixed),
        string("material",
               "a fixed monitor's material; named, its point may lie where that soil arrives "
               "later (NaN rows until then)")
            .or_computed("that of the soil particle nearest position at the start")
            .into(&MonitorSpec::material)},
       false});
  return t;
}

} // namespace

const std::vector<TableSpec>& case_format() {
  static const std::vector<TableSpec> tables = declare();
  return tables;
}

const TableSpec* find_table_spec(std::string_view path) {
  static const std::map<std::string, const TableSpec*, std::less<>> by_path = [] {
    std::map<std::string, const TableSpec*, std::less<>> m;
    for (const TableSpec& t : case_format()) {
      m.emplace(t.path, &t);
    }
    return m;
  }();
  const auto found = by_path.find(path);
  return found == by_path.end() ? nullptr : found->second;
}

std::string table_heading(const TableSpec& table) {
  if (table.path.empty()) {
    return "top level";
  }
  const std::size_t dot = table.path.rfind('.');
  const std::string parent = dot == std::string::npos ? "" : table.path.substr(0, dot);
  const std::string leaf = dot == std::string::npos ? table.path : table.path.substr(dot + 1);
  std::string shown = table.path;
  if (leaf == "*") {
    shown = parent + ".<name>";
  }
  const TableSpec* owner = find_table_spec(parent);
  const KeySpec* key = owner != nullptr ? owner->key(leaf) : nullptr;
  if (key != nullptr && key->kind == ValueKind::tables) {
    return "[[" + shown + "]]";
  }
  return "[" + shown + "]";
}

} // namespace mpile
