#pragma once

// Element tests: one material point driven along a laboratory path (triaxial, oedometer,
// isotropic, unload-reload, cyclic triaxial, cyclic torsion, or a table of strain increments),
// with some components under stress control, to check a constitutive model against closed forms
// and laboratory curves without a grid. docs/element-tests.md documents the input file, which
// cases/element_test_file.hpp reads.

#include "engine/materials/material_registry.hpp"
#include "solver/element_point.hpp"

#include <array>
#include <string>
#include <vector>

namespace mpile {

enum class ElementPath {
  triaxial,
  oedometer,
  isotropic,
  unload_reload,
  cyclic_triaxial,
  cyclic_torsion,
  cyclic_deviator,
  cyclic_simple_shear,
  strain_table
};

/// An element test as read from its file. Stresses and strains here are in the soil-mechanics
/// convention (compression positive); shear strains are engineering.
struct ElementTestSpec {
  std::string file;
  std::string title;
  std::string material_type;
  MaterialParameters parameters;
  PoreWater water;              // undrained: the path is total stress, the water carries its share
  double vertical_stress = 0.0; // sigma_1 initial (Pa)
  double lateral_stress = 0.0;  // sigma_3 initial (Pa)
  /// State variables set by [initial_state] (index into the material's state, value), applied
  /// over the material's own initial state.
  std::vector<std::pair<std::size_t, double>> initial_state;

  ElementPath path = ElementPath::triaxial;
  std::string path_where;             // "file:line: path" for errors found when running
  long increments = 100;              // per stage, per cycle for the cyclic paths
  double axial_strain = 0.0;          // triaxial target; unload_reload final
  std::vector<double> stress_targets; // oedometer vertical stresses, isotropic mean stresses
  double deviator = 0.0;              // unload_reload: reverse at this q (Pa)
  double unload_deviator = 0.0;       // unload_reload: reload from this q (Pa)
  double amplitude = 0.0;             // cyclic: axial or engineering shear strain, q or tau (Pa)
  long cycles = 0;
  /// cyclic_deviator (axial strain) and cyclic_simple_shear (engineering shear strain): the
  /// double amplitude, largest minus smallest since the start, that counts as liquefaction; the
  /// path ends at the first increment that reaches it.
  double liquefaction_strain = 0.05;
  std::vector<std::array<double, 6>> strain_increments; // strain_table, compression positive
  long repeat = 1;                                      // strain_table
};

/// The results, one row per increment after the initial state. Columns: eps_1, eps_v, sigma_1,
/// sigma_3, p, q (compression positive: eps_1 and sigma_1 vertical, sigma_3 radial, q signed as
/// sigma_1 - sigma_3 and equal in size to sqrt(3 J2)), the material's state variables, and for
/// cyclic torsion and simple shear gamma_ytheta and tau_ytheta, for the stress-controlled cyclic
/// paths the cycle (N, fractional).
struct ElementTestTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  /// cyclic_deviator and cyclic_simple_shear: the cycles run until the strain's double amplitude
  /// reached liquefaction_strain; 0 when it was not reached.
  double cycles_to_liquefaction = 0.0;
  /// The column's index; throws std::out_of_range for an unknown name.
  std::size_t column(const std::string& name) const;
};

/// Runs the test. A path the material cannot follow (a stress target beyond its strength, a
/// deviator never reached) throws std::runtime_error naming the file, line and key.
ElementTestTable run_element_test(const ElementTestSpec& spec);

} // namespace mpile
