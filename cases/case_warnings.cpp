// Plausibility warnings: the bounds are generous (a factor of ten or more beyond the softest,
// lightest or weakest of their kind), so that a warning means a unit, not an unusual soil.
#include "cases/case_warnings.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <ostream>
#include <sstream>

namespace mpile {

namespace {

// The bounds, each with where it comes from (docs/case-format.md, "Plausibility warnings").
constexpr double lightest = 100.0;       // kg/m^3: dry soils are 1 000 and more, peat about 1 000
constexpr double heaviest = 22600.0;     // kg/m^3: osmium, the densest element
constexpr double softest = 1e5;          // Pa: a tenth of a very soft clay's 1 MPa
constexpr double stiffest = 1.2e12;      // Pa: diamond
constexpr double largest_friction = 1.2; // mu: rough steel on dense sand stays below tan 45 deg
constexpr double smallest_p_ref = 1e3;   // Pa: p_ref is 100 kPa by convention (Schanz et al. 1999)
constexpr double smallest_torque = 1e3;  // N m/rad: GDP piles take hundreds of kN m/rad
constexpr double smallest_monopile_torque =
    1e4;                                 // N m/rad: the seed's monopile takes 414.5 kN m/rad
constexpr double longest_zone = 1e4;     // m: ten kilometres, beyond any soil block modelled
constexpr double softest_metal = 1e9;    // Pa: aluminium is 7e10, steel 2.1e11
constexpr double metal_density = 5000.0; // kg/m^3: no soil's grains reach it (iron ores aside)
constexpr double water_lightest = 500.0; // kg/m^3: water is 1 000, brines up to 1 300
constexpr double water_heaviest = 2000.0;
constexpr double softest_water = 1e6; // Pa: water's K_w is 2.2e9; even gassy water keeps MPa
constexpr double stiffest_water = 1e11;
constexpr double largest_conductivity = 10.0; // m/s: clean gravel reaches 1 m/s
constexpr double largest_gravity = 6000.0;    // m/s^2: 600 g, beyond geotechnical centrifuges
constexpr double smallest_gravity = 1.0;      // m/s^2: below the Moon's 1.62

/// The moduli among a material's parameters (Pa).
constexpr const char* modulus_keys[] = {"young_modulus", "e50_ref", "eoed_ref", "eur_ref"};

void add(std::vector<CaseWarning>& warnings, CaseWarning::Kind kind, const TomlTable& table,
         const std::string& key, const std::string& message) {
  warnings.push_back(
      {kind, table.location(key) + ": " + table.key_path(key) + ": " + message, key, message});
}

std::string fixed(double x, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << x;
  return s.str();
}

void warn_density(const TomlTable& table, double density, std::vector<CaseWarning>& warnings,
                  const std::string& key = "density") {
  std::string message = key + " = " + format_number(density) + " kg/m^3";
  if (density < lightest) {
    message += " is lighter than any soil or steel (1 000 to 2 600 for soils, 7 850 for steel)";
    const bool grams = density * 1e3 >= 1e3 && density * 1e3 <= heaviest;
    const bool unit_weight = density >= 10.0 && density <= 30.0;
    if (grams) {
      message += ": did you mean " + format_number(density * 1e3) + " (g/cm^3 given)";
    }
    if (unit_weight) {
      message += std::string(grams ? ", or " : ": did you mean ") +
                 format_number(std::round(density * 1e3 / 9.81)) +
                 " (a unit weight in kN/m^3 given)";
    }
    message += grams || unit_weight ? "?" : "";
  } else if (density > heaviest) {
    message += " is heavier than osmium (22 600), the densest element";
    if (density / 1e3 >= 1e3) {
      message += ": did you mean " + format_number(density / 1e3) + " (g/m^3 given)?";
    }
  } else {
    return;
  }
  add(warnings, CaseWarning::Kind::units, table, key, message);
}

void warn_modulus(const TomlTable& table, const std::string& key, double modulus,
                  std::vector<CaseWarning>& warnings) {
  std::string message = key + " = " + format_number(modulus) + " Pa";
  if (modulus < softest) {
    // kPa when that reaches a soil's stiffness, else MPa.
    const bool kilo = modulus * 1e3 >= 1e6;
    message += " is below any soil's (very soft clay about 1 MPa, dense sand up to 2 GPa): did "
               "you mean " +
               format_number(modulus) + (kilo ? " kPa = " : " MPa = ") +
               format_number(modulus * (kilo ? 1e3 : 1e6)) + "?";
  } else if (modulus > stiffest) {
    message += " is stiffer than diamond (1.2e12 Pa); steel is 2.1e11";
  } else {
    return;
  }
  add(warnings, CaseWarning::Kind::units, table, key, message);
}

bool scaled(const MaterialSpec& material) {
  const auto& p = material.parameters;
  const auto density = p.find("density");
  if (density == p.end() || density->second >= lightest) {
    return false;
  }
  return std::all_of(std::begin(modulus_keys), std::end(modulus_keys), [&](const char* key) {
    const auto found = p.find(key);
    return found == p.end() || found->second < 1e3;
  });
}

/// The largest magnitude a drive's value reaches as written, or 0 when it gives none.
double largest_value(const TomlValue& value) {
  const auto number = [](const TomlValue& v) {
    return v.is_integer() ? static_cast<double>(v.as_integer())
                          : (v.is_floating() ? v.as_floating() : 0.0);
  };
  if (!value.is_table()) {
    return std::abs(number(value));
  }
  const auto& table = value.as_table();
  double largest = 0.0;
  for (const char* key : {"value", "amplitude"}) {
    if (const auto found = table.find(key); found != table.end()) {
      largest = std::max(largest, std::abs(number(found->second)));
    }
  }
  if (const auto points = table.find("points");
      points != table.end() && points->second.is_array()) {
    for (const TomlValue& point : points->second.as_array()) {
      if (point.is_array() && point.as_array().size() == 2) {
        largest = std::max(largest, std::abs(number(point.as_array()[1])));
      }
    }
  }
  return largest;
}

/// The pore water's keys, where the table gives them: its density, bulk modulus, the grains'
/// density and Darcy's conductivity.
void warn_implausible_water(const TomlTable& table, const MaterialSpec& material,
                            std::vector<CaseWarning>& warnings) {
  const PoreWater& w = material.water;
  if (table.has("water_density") && (w.density < water_lightest || w.density > water_heaviest)) {
    std::string message = "water_density = " + format_number(w.density) +
                          " kg/m^3 is not water's (1 000; sea water 1 025, brines up to 1 300)";
    if (w.density * 1e3 >= water_lightest && w.density * 1e3 <= water_heaviest) {
      message += ": did you mean " + format_number(w.density * 1e3) + " (g/cm^3 given)?";
    }
    add(warnings, CaseWarning::Kind::units, table, "water_density", message);
  }
  if (table.has("water_bulk_modulus") &&
      (w.bulk_modulus < softest_water || w.bulk_modulus > stiffest_water)) {
    std::string message = "water_bulk_modulus = " + format_number(w.bulk_modulus) +
                          " Pa is not water's (K_w = 2.2e9 Pa)";
    if (w.bulk_modulus < softest_water) {
      const bool giga = w.bulk_modulus < 100.0;
      message += ": did you mean " + format_number(w.bulk_modulus) +
                 (giga ? " GPa = " : " MPa = ") +
                 format_number(w.bulk_modulus * (giga ? 1e9 : 1e6)) + "?";
    }
    add(warnings, CaseWarning::Kind::units, table, "water_bulk_modulus", message);
  }
  if (table.has("grain_density")) {
    warn_density(table, w.grain_density, warnings, "grain_density");
  }
  if (table.has("hydraulic_conductivity") && w.hydraulic_conductivity > largest_conductivity) {
    add(warnings, CaseWarning::Kind::units, table, "hydraulic_conductivity",
        "hydraulic_conductivity = " + format_number(w.hydraulic_conductivity) +
            " m/s is above any soil's (clean gravel up to 1 m/s, sand 1e-5 to 1e-2): did you "
            "mean " +
            format_number(w.hydraulic_conductivity) +
            " cm/s = " + format_number(w.hydraulic_conductivity * 1e-2) +
            " or mm/s = " + format_number(w.hydraulic_conductivity * 1e-3) + " m/s?");
  }
}

} // namespace

void warn_implausible_material(const TomlTable& table, const MaterialSpec& material,
                               std::vector<CaseWarning>& warnings) {
  if (scaled(material)) {
    return;
  }
  const auto& p = material.parameters;
  if (const auto density = p.find("density"); density != p.end()) {
    warn_density(table, density->second, warnings);
  }
  for (const char* key : modulus_keys) {
    if (const auto modulus = p.find(key); modulus != p.end()) {
      warn_modulus(table, key, modulus->second, warnings);
    }
  }
  // An angle in radians: soils' friction angles lie between about 15 and 50 degrees.
  if (const auto phi = p.find("friction_angle");
      phi != p.end() && phi->second > 0.0 && phi->second <= std::numbers::pi / 2.0) {
    add(warnings, CaseWarning::Kind::units, table, "friction_angle",
        "friction_angle = " + format_number(phi->second) +
            " degrees is below any soil's (15 to 50 degrees): did you mean " +
            format_number(phi->second) +
            " rad = " + fixed(phi->second * 180.0 / std::numbers::pi, 1) + " degrees?");
  }
  // A metal (the pile's steel) whose modulus reads as a soil's: MPa given.
  if (const auto density = p.find("density"), young = p.find("young_modulus");
      density != p.end() && young != p.end() && density->second >= metal_density &&
      density->second <= heaviest && young->second >= softest && young->second < softest_metal) {
    add(warnings, CaseWarning::Kind::units, table, "young_modulus",
        "young_modulus = " + format_number(young->second) + " Pa for a material of density " +
            format_number(density->second) +
            " kg/m^3 (a metal) is below any metal's (aluminium 7e10, steel 2.1e11): did you mean " +
            format_number(young->second) + " MPa = " + format_number(young->second * 1e6) + "?");
  }
  warn_implausible_water(table, material, warnings);
  if (const auto p_ref = p.find("p_ref"); p_ref != p.end() && p_ref->second < smallest_p_ref) {
    add(warnings, CaseWarning::Kind::units, table, "p_ref",
        "p_ref = " + format_number(p_ref->second) +
            " Pa is far below the 100 kPa taken by convention (Schanz et al. 1999): did you mean " +
            format_number(p_ref->second) + " kPa = " + format_number(p_ref->second * 1e3) + "?");
  }
}

void warn_implausible_friction(const TomlTable& table, const std::string& key, double friction,
                               std::vector<CaseWarning>& warnings) {
  if (friction <= largest_friction) {
    return;
  }
  std::string message =
      key + " = " + format_number(friction) +
      " is a coefficient mu = tan(delta), above any soil on steel or soil (0 to " +
      fixed(largest_friction, 1) + ")";
  if (friction < 90.0) {
    message += ": did you mean tan(" + format_number(friction) +
               " deg) = " + fixed(std::tan(friction * std::numbers::pi / 180.0), 2) + "?";
  }
  add(warnings, CaseWarning::Kind::units, table, key, message);
}

void warn_implausible_gravity(const TomlTable& table, const std::array<double, 2>& gravity,
                              bool axisymmetric, std::vector<CaseWarning>& warnings) {
  const double magnitude = std::hypot(gravity[0], gravity[1]);
  // About the vertical axis of symmetry gravity has no radial part; in plane strain a slope tilts
  // it, but not past the vertical.
  if (gravity[0] != 0.0 && (axisymmetric || std::abs(gravity[0]) > std::abs(gravity[1]))) {
    add(warnings, CaseWarning::Kind::units, table, "gravity",
        "gravity has a component along r (g_r = " + format_number(gravity[0]) + ")" +
            (axisymmetric ? ", which the axisymmetric geometry (r about a vertical axis) cannot "
                            "have"
                          : " larger than along y") +
            ": did you mean [0, " + format_number(-std::abs(gravity[0]) + 0.0) +
            "]? ([g_r, g_y], y "
            "up)");
  }
  if (gravity[1] > 0.0) {
    add(warnings, CaseWarning::Kind::units, table, "gravity",
        "gravity points up (g_y = " + format_number(gravity[1]) + " > 0; y is up): did you mean [" +
            format_number(gravity[0]) + ", " + format_number(-gravity[1]) + "]?");
  }
  if (magnitude > largest_gravity) {
    add(warnings, CaseWarning::Kind::units, table, "gravity",
        "|g| = " + format_number(magnitude) +
            " m/s^2 is more than 600 g, beyond any geotechnical centrifuge: did you mean " +
            format_number(magnitude / 1e3) + " (mm/s^2 given)?");
  } else if (magnitude > 0.0 && magnitude < smallest_gravity) {
    add(warnings, CaseWarning::Kind::units, table, "gravity",
        "|g| = " + format_number(magnitude) +
            " m/s^2 is below the Moon's 1.62: did you mean 9.81 (g given as a multiple of "
            "9.81 m/s^2)?");
  }
}

void warn_implausible_torque(TomlTable& table, const std::string& key, const std::string& unit,
                             std::vector<CaseWarning>& warnings) {
  const double torque = largest_value(table.raw(key));
  // The seed's monopile is a full-scale pile: 10 kN m/rad is below what turns it, so a torque of
  // thousands typed in kN m is caught too; a rigid body of any size is judged at 1 kN m/rad.
  const bool monopile = table.key_path(key).rfind("monopile.", 0) == 0;
  const double smallest = monopile ? smallest_monopile_torque : smallest_torque;
  if (torque <= 0.0 || torque >= smallest) {
    return;
  }
  add(warnings, CaseWarning::Kind::units, table, key,
      "torque amplitude " + format_number(torque) + " " + unit + " is below " +
          (monopile ? "10 k" : "1 k") + unit + ", less than turns " +
          (monopile ? "the monopile" : "any pile in soil") +
          " (the seed's GDP drives 414.5 and 829 k" + unit + "): did you mean " +
          format_number(torque) + " k" + unit + " = " + format_number(torque * 1e3) + "?");
}

void warn_implausible_zone(const TomlTable& zone, double start, double end,
                           std::vector<CaseWarning>& warnings) {
  if (std::abs(end - start) <= longest_zone && std::abs(end) <= longest_zone) {
    return;
  }
  add(warnings, CaseWarning::Kind::units, zone, "end",
      "a zone from " + format_number(start) + " to " + format_number(end) +
          " m reaches beyond 10 km, more than any soil block modelled: did you mean mm (" +
          format_number(start * 1e-3) + " to " + format_number(end * 1e-3) + " m)?");
}

void note_one_cell_wall(const TomlTable& table, int wall_cells,
                        std::vector<CaseWarning>& warnings) {
  if (wall_cells != 1) {
    return;
  }
  add(warnings, CaseWarning::Kind::resolution, table, "wall_cells",
      "the wall is one cell wide: tip and shaft forces depend on where the grid lines fall "
      "(docs/resolution.md: at 0.1 m the quick jacked tip carries 15.1 kN/rad against 17.2 +- 0.6 "
      "converged with 3 to 4 cells across the wall); set wall_cells = 3 or more for forces");
}

void note_pure_flip_in_saturated_soil(const TomlTable& material, const CaseSpec& spec,
                                      std::vector<CaseWarning>& warnings) {
  const bool pure_flip =
      std::any_of(spec.phases.begin(), spec.phases.end(), [&](const PhaseSpec& p) {
        return p.xpic_order.value_or(spec.solver.xpic_order) == 0 &&
               p.flip_fraction.value_or(spec.solver.flip_fraction) == 1.0;
      });
  // With the implicit pore pressure and one excess pore pressure per cell it does not grow
  // (docs/saturated.md: the quick GDP cases under FLIP, ledger within 0.03 %); with the implicit
  // pore pressure alone the quick coupled GDP case ends with its ledger 4.7 % out (9 % at its
  // peak; at f3801ae).
  if (pure_flip && !(spec.solver.implicit_pore_pressure && spec.solver.cell_mean_pore_pressure)) {
    add(warnings, CaseWarning::Kind::resolution, material, "drainage",
        "saturated soil is nearly incompressible, and under pure FLIP (xpic_order = 0, "
        "flip_fraction = 1) a mode the grid does not see can grow in it (docs/verification.md: "
        "1.9 % of a pulse came back at an absorbing face; docs/saturated.md: the quick GDP case "
        "with per-particle pressures ended 4.7 % out of energy balance); take [solver] "
        "implicit_pore_pressure = true with "
        "cell_mean_pore_pressure = true, as the saturated installation cases do");
  }
}

void note_dry_soil_over_saturated(const CaseSpec& spec, const std::vector<TomlTable>& body_tables,
                                  std::vector<CaseWarning>& warnings) {
  const auto drainage_of = [&](const BodySpec& body) {
    for (const MaterialSpec& m : spec.materials) {
      if (m.name == body.material) {
        return m.water.drainage;
      }
    }
    return Drainage::drained;
  };
  for (std::size_t d = 0; d < body_tables.size() && d < spec.bodies.size(); ++d) {
    const BodySpec& dry = spec.bodies[d];
    if (dry.rigid || drainage_of(dry) != Drainage::drained) {
      continue;
    }
    const Rectangle& above = dry.region.bounds();
    for (const BodySpec& wet : spec.bodies) {
      const Rectangle& below = wet.region.bounds();
      const double touch = 1e-9 * std::max(1.0, std::abs(below.y_max));
      if (wet.rigid || drainage_of(wet) == Drainage::drained || above.r_min >= below.r_max ||
          below.r_min >= above.r_max || std::abs(above.y_min - below.y_max) > touch) {
        continue;
      }
      add(warnings, CaseWarning::Kind::resolution, body_tables[d], "material",
          "dry '" + dry.material + "' rests on saturated '" + wet.material + "' (body '" +
              wet.name +
              "'): without [water] table the K0 procedure takes the saturated body's water "
              "hydrostatic, and its vertical stress, from that body's own k0 surface, without the "
              "dry layer's weight above it (or with it at the saturated unit weight, if the "
              "surface is the ground's), so its effective stress starts wrong; give the water "
              "table's level as [water] table (docs/physics.md section 9c)");
      break;
    }
  }
}

void note_drained_face_under_gravity(const TomlTable& boundaries,
                                     std::vector<CaseWarning>& warnings) {
  add(warnings, CaseWarning::Kind::resolution, boundaries, "drained",
      "a drained face has p = 0 beyond it (the atmosphere, or the sea's pressure on the seabed "
      "with [water]): under gravity the pore water flows out through it as from a column on an "
      "open drain; drained_pressure = \"hydrostatic\" drains it into a far field at "
      "hydrostatic pressure instead (docs/physics.md section 9b)");
}

bool refused_when_strict(const std::vector<CaseWarning>& warnings) {
  return std::any_of(warnings.begin(), warnings.end(),
                     [](const CaseWarning& w) { return w.kind == CaseWarning::Kind::units; });
}

void print_case_warnings(std::ostream& out, const std::vector<CaseWarning>& warnings, bool strict) {
  for (const CaseWarning& w : warnings) {
    const bool units = w.kind == CaseWarning::Kind::units;
    out << "mpile: " << (units ? (strict ? "error (--strict): " : "warning: ") : "note: ") << w.text
        << '\n';
  }
}

} // namespace mpile
