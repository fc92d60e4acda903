#pragma once

// Values that read but are most likely a slip of units: a torque in kN m, a friction coefficient
// given as an angle in degrees, a density in g/cm^3, Hardening Soil's p_ref in kPa, gravity
// pointing up. Each lies outside what any soil, steel or installation uses (the ranges and their
// sources: docs/case-format.md, "Plausibility warnings"), and its message names the likely
// mistake. They are found while the case is read, where each key's file and line are known, and
// kept in CaseSpec::warnings; `mpile check` and `mpile run` print them (--strict refuses them).
// Beside them, notes on a mesh too coarse for what it is used for (CaseWarning::Kind::resolution),
// which no option turns into an error.

#include "cases/case_spec.hpp"
#include "cases/toml_reader.hpp"

#include <array>
#include <iosfwd>
#include <string>
#include <vector>

namespace mpile {

/// A material's density, moduli (a metal's modulus in MPa), friction angle, p_ref and its pore
/// water's density, bulk modulus, grain density and conductivity. A material whose moduli are all
/// below 1 kPa and whose density is below 100 kg/m^3 is a scaled one (the verification cases' bar
/// with E = 100, rho = 1): its units are its own and it is not judged.
void warn_implausible_material(const TomlTable& table, const MaterialSpec& material,
                               std::vector<CaseWarning>& warnings);

/// A contact's Coulomb coefficient mu = tan(delta) under `key`.
void warn_implausible_friction(const TomlTable& table, const std::string& key, double friction,
                               std::vector<CaseWarning>& warnings);

/// [solver] gravity (g_r, g_y): y is up, so g_y > 0 points up; about an axis of symmetry g_r = 0.
void warn_implausible_gravity(const TomlTable& table, const std::array<double, 2>& gravity,
                              bool axisymmetric, std::vector<CaseWarning>& warnings);

/// A grid zone reaching beyond 10 km: lengths typed in mm.
void warn_implausible_zone(const TomlTable& zone, double start, double end,
                           std::vector<CaseWarning>& warnings);

/// A rigid body's torque drive under `key` (a number or a time function's table): its largest
/// value given (a constant's value, a ramp's, a harmonic's or pulse train's amplitude, a table's
/// largest point). `unit` is the torque's unit as the geometry has it ("N m/rad").
void warn_implausible_torque(TomlTable& table, const std::string& key, const std::string& unit,
                             std::vector<CaseWarning>& warnings);

/// [monopile] wall_cells = 1: a note that the wall and tip forces depend on the grid lines.
void note_one_cell_wall(const TomlTable& table, int wall_cells, std::vector<CaseWarning>& warnings);
/// A note at [boundaries] drained in a scene with gravity: the water drains to p = 0 beyond it.
void note_drained_face_under_gravity(const TomlTable& boundaries,
                                     std::vector<CaseWarning>& warnings);
/// A note on a saturated material (its [materials.<name>] table) when a phase runs pure FLIP.
void note_pure_flip_in_saturated_soil(const TomlTable& material, const CaseSpec& spec,
                                      std::vector<CaseWarning>& warnings);

/// Whether --strict refuses the case: any warning of units (resolution notes never count).
bool refused_when_strict(const std::vector<CaseWarning>& warnings);

/// One line per warning ("mpile: warning: file:line: key: ..."; a resolution note "mpile: note:
/// ..."); with `strict`, warnings of units say that they refuse the case.
void print_case_warnings(std::ostream& out, const std::vector<CaseWarning>& warnings, bool strict);

/// A dry body resting on a saturated one (a water table inside the soil), which the engine does not
/// model yet: the saturated body's K0 state and pore pressure would start wrong. `body_tables` are
/// the [[bodies]] tables in order (empty when a generator made the bodies).
void note_dry_soil_over_saturated(const CaseSpec& spec, const std::vector<TomlTable>& body_tables,
                                  std::vector<CaseWarning>& warnings);

} // namespace mpile
