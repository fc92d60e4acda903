#include "solver/element_test.hpp"

#include "engine/parameter_range.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace mpile {

std::size_t ElementTestTable::column(const std::string& name) const {
  const auto found = std::find(columns.begin(), columns.end(), name);
  if (found == columns.end()) {
    throw std::out_of_range("no column named '" + name + "'");
  }
  return static_cast<std::size_t>(found - columns.begin());
}

namespace {

class PathRunner {
public:
  PathRunner(const ElementTestSpec& spec, const Material& material)
      : spec_(spec), point_(material,
                            Stress{-spec.lateral_stress, -spec.vertical_stress,
                                   -spec.lateral_stress, 0.0, 0.0, 0.0},
                            spec.initial_state) {
    table_.columns = {"eps_1", "eps_v", "sigma_1", "sigma_3", "p", "q"};
    for (const std::string& name : material.state_names()) {
      table_.columns.push_back(name);
    }
    if (spec.path == ElementPath::cyclic_torsion || spec.path == ElementPath::cyclic_simple_shear) {
      table_.columns.push_back("gamma_ytheta");
      table_.columns.push_back("tau_ytheta");
    }
    if (stress_cycles()) {
      table_.columns.push_back("cycle");
    }
    record();
  }

  ElementTestTable run() {
    switch (spec_.path) {
    case ElementPath::triaxial:
      for (long k = 0; k < spec_.increments; ++k) {
        step(triaxial(spec_.axial_strain / static_cast<double>(spec_.increments)));
      }
      break;
    case ElementPath::oedometer:
      for (const double target : spec_.stress_targets) {
        const double start = vertical();
        for (long k = 1; k <= spec_.increments; ++k) {
          MixedIncrement increment; // lateral strain and shear strain zero
          increment.stress_controlled[YY] = true;
          increment.value[YY] = -(start + (target - start) * fraction(k));
          step(increment);
        }
      }
      break;
    case ElementPath::isotropic:
      for (const double target : spec_.stress_targets) {
        const Stress start = point_.stress();
        const double change = target - mean_pressure(start);
        for (long k = 1; k <= spec_.increments; ++k) {
          MixedIncrement increment; // equal changes of the three normal stresses
          for (Component c : {RR, YY, TT}) {
            increment.stress_controlled[c] = true;
            increment.value[c] = start[c] - change * fraction(k);
          }
          step(increment);
        }
      }
      break;
    case ElementPath::unload_reload:
      unload_reload();
      break;
    case ElementPath::cyclic_triaxial:
    case ElementPath::cyclic_torsion:
      cyclic();
      break;
    case ElementPath::cyclic_deviator:
    case ElementPath::cyclic_simple_shear:
      stress_controlled_cycles();
      break;
    case ElementPath::strain_table:
      for (long r = 0; r < spec_.repeat; ++r) {
        for (const std::array<double, 6>& row : spec_.strain_increments) {
          MixedIncrement increment;
          for (std::size_t c = 0; c < 6; ++c) {
            increment.value[c] = -row[c]; // compression positive in the file
          }
          step(increment);
        }
      }
      break;
    }
    return std::move(table_);
  }

private:
  double fraction(long k) const {
    return static_cast<double>(k) / static_cast<double>(spec_.increments);
  }
  double vertical() const { return -point_.stress()[YY]; }
  double axial_strain() const { return -point_.strain()[YY]; }
  double deviator() const { return -point_.stress()[YY] + point_.stress()[RR]; }

  /// Drained triaxial: axial strain increment (compression positive), radial and hoop stress held
  /// at the initial lateral stress, no shear strain.
  MixedIncrement triaxial(double axial) const {
    MixedIncrement increment;
    increment.value[YY] = -axial;
    for (Component c : {RR, TT}) {
      increment.stress_controlled[c] = true;
      increment.value[c] = -spec_.lateral_stress;
    }
    return increment;
  }

  void step(const MixedIncrement& increment) {
    ++increments_;
    try {
      point_.apply(increment);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(spec_.path_where + ": increment " + std::to_string(increments_) +
                               ": " + e.what());
    }
    record();
  }

  void unload_reload() {
    const double d = spec_.axial_strain / static_cast<double>(spec_.increments);
    while (deviator() < spec_.deviator) {
      if (axial_strain() >= spec_.axial_strain) {
        throw std::runtime_error(spec_.path_where + ": deviator " + format_bound(spec_.deviator) +
                                 " Pa not reached by the axial strain " +
                                 format_bound(spec_.axial_strain) + " (it is " +
                                 format_bound(deviator()) + " Pa there)");
      }
      step(triaxial(d));
    }
    const long limit = increments_ + 10 * spec_.increments;
    while (deviator() > spec_.unload_deviator) {
      if (increments_ >= limit) {
        throw std::runtime_error(spec_.path_where + ": unload_deviator " +
                                 format_bound(spec_.unload_deviator) + " Pa not reached (it is " +
                                 format_bound(deviator()) + " Pa after unloading by " +
                                 std::to_string(10 * spec_.increments) + " increments)");
      }
      step(triaxial(-d));
    }
    // Reload to the final axial strain; the last increment lands on it exactly.
    while (spec_.axial_strain - axial_strain() > 1e-12 * spec_.axial_strain) {
      step(triaxial(std::min(d, spec_.axial_strain - axial_strain())));
    }
  }

  void cyclic() {
    const bool torsion = spec_.path == ElementPath::cyclic_torsion;
    const Stress held = point_.stress();
    const long total = spec_.increments * spec_.cycles;
    auto wave = [&](long k) {
      return spec_.amplitude * std::sin(2.0 * std::numbers::pi * static_cast<double>(k) /
                                        static_cast<double>(spec_.increments));
    };
    for (long k = 1; k <= total; ++k) {
      const double change = wave(k) - wave(k - 1);
      if (torsion) {
        // Constant normal stresses, y-theta shear strain imposed: the principal axes rotate.
        MixedIncrement increment;
        for (Component c : {RR, YY, TT}) {
          increment.stress_controlled[c] = true;
          increment.value[c] = held[c];
        }
        increment.value[YT] = -change;
        step(increment);
      } else {
        step(triaxial(change));
      }
    }
  }

  bool stress_cycles() const {
    return spec_.path == ElementPath::cyclic_deviator ||
           spec_.path == ElementPath::cyclic_simple_shear;
  }

  /// Stress-controlled cycles of amplitude A, sin(2 pi k / increments) on top of the initial
  /// stress. cyclic_deviator: q cycles, the radial and hoop (total) stresses held (the cyclic
  /// triaxial test). cyclic_simple_shear: tau_ytheta cycles, every normal strain held at zero
  /// (constant-volume simple shear; the soil beside a shaft twisted in cycles). Undrained with the
  /// material's water, drained without. Ends at the first increment where the double amplitude of
  /// the axial strain (or the shear strain gamma_ytheta), its largest minus its smallest value
  /// since the start, reaches liquefaction_strain (under cyclic mobility the strain also walks to
  /// one side, so that a range within one cycle may stay small while the sample has failed), or
  /// after the cycles.
  void stress_controlled_cycles() {
    const bool shear = spec_.path == ElementPath::cyclic_simple_shear;
    const Stress held = point_.stress();
    const double n = static_cast<double>(spec_.increments);
    const long total = spec_.increments * spec_.cycles;
    auto measured = [&] { return shear ? -point_.strain()[YT] : axial_strain(); };
    double lowest = measured(), highest = measured();
    for (long k = 1; k <= total; ++k) {
      const double wave =
          spec_.amplitude * std::sin(2.0 * std::numbers::pi * static_cast<double>(k) / n);
      MixedIncrement increment; // strains zero unless stress-controlled
      if (shear) {
        increment.stress_controlled[YT] = true;
        increment.value[YT] = held[YT] - wave;
      } else {
        for (Component c : {RR, YY, TT}) {
          increment.stress_controlled[c] = true;
          increment.value[c] = held[c];
        }
        increment.value[YY] -= wave;
      }
      cycle_ = static_cast<double>(k) / n;
      step(increment);
      lowest = std::min(lowest, measured());
      highest = std::max(highest, measured());
      if (highest - lowest >= spec_.liquefaction_strain) {
        table_.cycles_to_liquefaction = cycle_;
        return;
      }
    }
  }

  void record() {
    // Soil-mechanics signs; 0 - x rather than -x, so that no "-0" reaches the file.
    auto compression = [](double x) { return 0.0 - x; };
    const Stress& s = point_.stress();
    const StrainIncrement& e = point_.strain();
    const double sigma_1 = compression(s[YY]), sigma_3 = compression(s[RR]);
    const double q = deviatoric_stress(s);
    std::vector<double> row = {
        compression(e[YY]),          compression(e[RR] + e[YY] + e[TT]), sigma_1, sigma_3,
        compression(trace(s) / 3.0), sigma_1 >= sigma_3 ? q : -q};
    row.insert(row.end(), point_.state().begin(), point_.state().end());
    if (spec_.path == ElementPath::cyclic_torsion ||
        spec_.path == ElementPath::cyclic_simple_shear) {
      row.push_back(compression(e[YT]));
      row.push_back(compression(s[YT]));
    }
    if (stress_cycles()) {
      row.push_back(cycle_);
    }
    table_.rows.push_back(std::move(row));
  }

  const ElementTestSpec& spec_;
  ElementPoint point_;
  ElementTestTable table_;
  long increments_ = 0;
  double cycle_ = 0.0; // cyclic_deviator: cycles run so far
};

} // namespace

ElementTestTable run_element_test(const ElementTestSpec& spec) {
  const auto material = create_material(spec.material_type, spec.parameters, spec.water);
  PathRunner runner(spec, *material);
  return runner.run();
}

} // namespace mpile
