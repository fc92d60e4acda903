// [water]: the sea above the seabed and the pore water's cavitation (physics.md section 9c). The
// sea is not modelled as particles: its column's pressure on the seabed p_s = rho_w g (level -
// seabed) is uniform over every saturated body and its free surfaces, so it only adds to the pore
// pressure and total stress the outputs report and to the uplift on a structure through the
// seabed; the materials keep their pore pressure relative to it.
#include "cases/water_reader.hpp"

#include "cases/case_error.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace mpile {

namespace {

bool saturated(const MaterialSpec& m) {
  return m.water.drainage != Drainage::drained;
}

const MaterialSpec& material_named(const CaseSpec& spec, const std::string& name) {
  for (const MaterialSpec& m : spec.materials) {
    if (m.name == name) {
      return m;
    }
  }
  throw std::logic_error("body of an unknown material " + name);
}

/// The seabed: the K0 surface of the first K0 procedure each saturated body gets. Every saturated
/// body must get one, on the same surface.
double seabed_of(const TomlTable& table, const std::string& level, const CaseSpec& spec) {
  bool found = false;
  double seabed = 0.0;
  for (const BodySpec& body : spec.bodies) {
    if (!saturated(material_named(spec, body.material))) {
      continue;
    }
    const K0Spec* first = nullptr;
    for (const PhaseSpec& phase : spec.phases) {
      for (const K0Spec& k0 : phase.k0) {
        if (first == nullptr && k0.body == body.name) {
          first = &k0;
        }
      }
    }
    if (first == nullptr) {
      table.fail(level, "body '" + body.name +
                            "' holds pore water but no phase gives it a K0 procedure, whose "
                            "surface is the seabed: the water's surface, where its hydrostatic "
                            "pressure starts");
    }
    if (found && first->surface != seabed) {
      table.fail(level, "the saturated bodies' K0 surfaces differ (" + format_number(seabed) +
                            " and " + format_number(first->surface) +
                            " m): the water stands on one horizontal seabed");
    }
    seabed = first->surface;
    found = true;
  }
  return seabed;
}

/// Water at rest is hydrostatic only under gravity along -y: `what` is refused at `key` otherwise.
void require_gravity_down(const TomlTable& table, const std::string& key, const CaseSpec& spec,
                          const std::string& what) {
  if (spec.solver.gravity[0] != 0.0 || !(spec.solver.gravity[1] < 0.0)) {
    table.fail(key, what + " is hydrostatic under gravity along -y; [solver] gravity is [" +
                        format_number(spec.solver.gravity[0]) + ", " +
                        format_number(spec.solver.gravity[1]) + "]");
  }
}

/// A water table inside the soil ([water] table): one sea level or the other; gravity along -y;
/// the saturated bodies below the table and the dry ones above it.
void read_water_table(const TomlTable& table, CaseSpec& spec, WaterSpec water, double grid_bottom) {
  const std::string& key = table.key_of(&WaterSpec::table);
  if (table.has(table.key_of(&WaterSpec::level))) {
    table.fail(key, "a water table inside the soil and a sea's level above it exclude each other: "
                    "give one");
  }
  require_gravity_down(table, key, spec, "a water table");
  if (!(water.table >= grid_bottom)) {
    table.fail(key, format_number(water.table) + " m lies below the grid (its bottom is " +
                        format_number(grid_bottom) + " m)");
  }
  const double touch = 1e-9 * std::max(1.0, std::abs(water.table));
  for (const BodySpec& body : spec.bodies) {
    if (body.rigid) {
      continue;
    }
    const Rectangle& bounds = body.region.bounds();
    if (saturated(material_named(spec, body.material)) && bounds.y_max > water.table + touch) {
      table.fail(key, "body '" + body.name +
                          "' is saturated but reaches y = " + format_number(bounds.y_max) +
                          " m, above the table at " + format_number(water.table) +
                          " m: split it at the table, dry (drainage = \"drained\") above");
    }
    if (!saturated(material_named(spec, body.material)) && bounds.y_min < water.table - touch) {
      table.fail(key, "body '" + body.name +
                          "' is dry but reaches y = " + format_number(bounds.y_min) +
                          " m, below the table at " + format_number(water.table) +
                          " m: its pores there hold water; split it at the table, saturated "
                          "(drainage = \"undrained\" or \"coupled\") below");
    }
  }
  // The pore pressure is zero at the table, as on a seabed without a sea above it.
  water.level = water.table;
  water.seabed = water.table;
  water.column_pressure = 0.0;
  water.phreatic = true;
  spec.water = water;
}

} // namespace

void read_water(TomlTable& top, CaseSpec& spec, double grid_bottom) {
  std::optional<TomlTable> table = top.optional_table("water");
  if (!table) {
    return;
  }
  WaterSpec water;
  table->read_into(water); // the level
  PoreWater cavitation;
  table->read_into(cavitation); // the cavitation stress
  const std::string& level = table->key_of(&WaterSpec::level);
  const std::string& cavitation_stress = table->key_of(&PoreWater::cavitation_stress);
  const std::string& phreatic = table->key_of(&WaterSpec::table);
  const std::string& given = table->has(level)      ? level
                             : table->has(phreatic) ? phreatic
                                                    : cavitation_stress;
  double water_density = 0.0;
  for (const MaterialSpec& m : spec.materials) {
    if (!saturated(m)) {
      continue;
    }
    if (water_density != 0.0 && m.water.density != water_density) {
      table->fail(given,
                  "the saturated materials' water_density differ: one sea fills their pores");
    }
    water_density = m.water.density;
  }
  if (water_density == 0.0) {
    table->fail(given, "no material holds pore water (drainage = \"undrained\" or \"coupled\")");
  }
  double column_pressure = 0.0;
  if (table->has(level)) {
    if (!(water.level >= grid_bottom)) {
      table->fail(level, format_number(water.level) + " m lies below the grid (its bottom is " +
                             format_number(grid_bottom) + " m)");
    }
    water.seabed = seabed_of(*table, level, spec);
    if (water.level < water.seabed) {
      table->fail(level, format_number(water.level) + " m lies below the seabed (the K0 surface, " +
                             format_number(water.seabed) +
                             " m): a water table inside the soil, dry soil above it, is given "
                             "as table");
    }
    const double g = std::hypot(spec.solver.gravity[0], spec.solver.gravity[1]);
    water.column_pressure = water_density * g * (water.level - water.seabed);
    // The deepest ocean is 11 km: 1.1e8 Pa on its floor. A level of 1e308 m made the pressure
    // infinite, and the run wrote inf and NaN into every total stress it reported.
    if (!std::isfinite(water.column_pressure) || water.column_pressure > 2e8) {
      table->fail(level, format_number(water.level) + " m puts " +
                             format_number(water.level - water.seabed) +
                             " m of water on the seabed, a pressure of " +
                             format_number(water.column_pressure) +
                             " Pa: above the 2e8 Pa of 20 km of water (a length in mm?)");
    }
    column_pressure = water.column_pressure;
    spec.water = water;
  }
  if (table->has(phreatic)) {
    read_water_table(*table, spec, water, grid_bottom);
  }
  table->finish();
  for (MaterialSpec& m : spec.materials) {
    if (saturated(m)) {
      m.water.column_pressure = column_pressure;
      if (table->has(cavitation_stress)) {
        m.water.cavitation_stress = cavitation.cavitation_stress;
      }
    }
  }
}

void read_drained_water(TomlTable& boundaries, CaseSpec& spec) {
  const std::string& key = boundaries.key_of(&FaceConditions::hydrostatic_drains);
  require_gravity_down(boundaries, key, spec, "the far field's water");
  CaseSpec::DrainedWater water;
  for (const MaterialSpec& m : spec.materials) {
    if (saturated(m)) {
      if (water.density != 0.0 && m.water.density != water.density) {
        boundaries.fail(key, "the saturated materials' water_density differ: the far field holds "
                             "one water");
      }
      water.density = m.water.density;
    }
  }
  // The pore pressure is kept relative to the sea's column (physics.md section 9c), so the far
  // field's is zero on the seabed as the soil's is.
  water.surface = spec.water ? spec.water->seabed : seabed_of(boundaries, key, spec);
  spec.drained_water = water;
}

} // namespace mpile
