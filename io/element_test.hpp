#pragma once

// Element tests: one material point driven along a laboratory path (triaxial, oedometer,
// isotropic, unload-reload, cyclic triaxial, cyclic torsion, or a table of strain increments),
// with some components under stress control, to check a constitutive model against closed forms
// and laboratory curves without a grid. docs/element-tests.md documents the input file.

#include "engine/material.hpp"
#include "engine/material_registry.hpp"

#include <array>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace mpile {

/// One increment under mixed control, in the engine's convention (tension positive, engineering
/// shear): a stress-controlled component is driven to the target stress `value`, the others are
/// given the strain increment `value`.
struct MixedIncrement {
  std::array<bool, 6> stress_controlled{};
  std::array<double, 6> value{};
};

/// A single material point: its stress, total strain (sum of the increments, engineering shear)
/// and state. The material is never changed; every trial runs on copies of stress and state.
class ElementPoint {
public:
  /// The material's own initial state for this stress (its initialise_state), then any given
  /// state variables (index, value) on top.
  ElementPoint(const Material& material, const Stress& initial_stress,
               const std::vector<std::pair<std::size_t, double>>& state_overrides = {});

  /// Applies one increment. The strain of the stress-controlled components is found by Newton
  /// iterations with a forward-difference Jacobian of the material's own update; throws
  /// std::runtime_error when they do not converge (a target the material cannot carry).
  void apply(const MixedIncrement& increment);

  /// The stress the material would reach from the current state by this strain increment.
  Stress trial(const StrainIncrement& strain, std::vector<double>& state) const;

  const Stress& stress() const { return stress_; }
  const StrainIncrement& strain() const { return strain_; }
  const std::vector<double>& state() const { return state_; }
  const Material& material() const { return *material_; }
  /// Newton iterations of the last increment (0 when fully strain-controlled).
  int iterations() const { return iterations_; }

private:
  const Material* material_;
  Stress stress_;
  StrainIncrement strain_{};
  std::vector<double> state_;
  StrainIncrement previous_{}; // last increment: the first guess of the next one
  int iterations_ = 0;
};

enum class ElementPath {
  triaxial,
  oedometer,
  isotropic,
  unload_reload,
  cyclic_triaxial,
  cyclic_torsion,
  strain_table
};

/// An element test as read from its file. Stresses and strains here are in the soil-mechanics
/// convention (compression positive); shear strains are engineering.
struct ElementTestSpec {
  std::string file;
  std::string title;
  std::string material_type;
  MaterialParameters parameters;
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
  double amplitude = 0.0;             // cyclic: axial strain or engineering shear strain
  long cycles = 0;
  std::vector<std::array<double, 6>> strain_increments; // strain_table, compression positive
  long repeat = 1;                                      // strain_table
};

/// Reads an element-test file; every mistake is a CaseError "file:line: key: reason".
ElementTestSpec read_element_test_text(const std::string& text, const std::string& file);
ElementTestSpec read_element_test_file(const std::string& path);

/// The results, one row per increment after the initial state. Columns: eps_1, eps_v, sigma_1,
/// sigma_3, p, q (compression positive: eps_1 and sigma_1 vertical, sigma_3 radial, q signed as
/// sigma_1 - sigma_3 and equal in size to sqrt(3 J2)), the material's state variables, and for
/// cyclic torsion gamma_ytheta and tau_ytheta.
struct ElementTestTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  /// The column's index; throws std::out_of_range for an unknown name.
  std::size_t column(const std::string& name) const;
};

/// Runs the test. A path the material cannot follow (a stress target beyond its strength, a
/// deviator never reached) throws std::runtime_error naming the file, line and key.
ElementTestTable run_element_test(const ElementTestSpec& spec);

void write_csv(const ElementTestTable& table, std::ostream& out);

struct ElementTestOptions {
  std::string file;
  std::string csv; // empty: out/<file stem>.csv
};

/// `mpile element-test`: reads the file, runs the path, writes the CSV. Returns an ExitStatus:
/// 2 for a bad file (with file:line: key: reason), 1 when the path cannot be followed.
int element_test_command(const ElementTestOptions& options, std::ostream& out, std::ostream& err);

} // namespace mpile
