#pragma once

// One material point driven under mixed control: some strain components given, the others found
// so that their stresses reach targets. The driver of the element tests (solver/element_test.hpp),
// with no grid.

#include "engine/materials/material.hpp"

#include <array>
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

} // namespace mpile
