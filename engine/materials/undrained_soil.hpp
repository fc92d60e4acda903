#pragma once

// A soil skeleton with its pores full of water. Undrained (PLAXIS's "Undrained A"): the water
// cannot drain in the time of the loading; the skeleton's model works on the effective stress,
// and the water, of bulk modulus K_w in a porosity n, adds the volumetric stiffness K_w / n, its
// pressure changing by dp = (K_w / n) d eps_vol at each material point (incompressible grains).
// Coupled (two-phase): the water also flows, so its pressure follows both phases' volumetric
// strains, dp = (K_w / n) ((1 - n) d eps_vol + n d eps_vol,w); this model takes the skeleton's
// share and the solver's water pass the water's (solver/pore_water_passes.cpp). The particle's
// stress is the total stress sigma = sigma' + p 1, with p the pore pressure, tension positive
// like every stress here (so a compressed pore water has p < 0).

#include "engine/materials/material.hpp"
#include "engine/materials/pore_water.hpp"

#include <memory>
#include <string>
#include <vector>

namespace mpile {

class UndrainedSoil final : public Material {
public:
  /// Throws std::invalid_argument when the skeleton's density is not below the grains' (no pores)
  /// or is rigid, or when a coupled one has no hydraulic conductivity.
  UndrainedSoil(std::unique_ptr<Material> skeleton, const PoreWater& water);

  std::string_view type() const override { return skeleton_->type(); }
  /// The saturated density rho_d + n rho_w.
  double density() const override { return density_; }
  std::span<const std::string> state_names() const override { return state_names_; }
  int pore_pressure_index() const override { return pore_index_; }
  const LiquidPhase* liquid_phase() const override { return coupled_ ? &liquid_ : nullptr; }
  const PoreStorage* implicit_pore_storage() const override {
    return implicit_ ? &storage_ : nullptr;
  }
  /// The skeleton's state from the effective stress: the pore pressure must already be in state.
  void initialise_state(const Stress& stress, double* state) const override;
  Inadmissible inadmissible_state(const Stress& stress, const double* state) const override {
    return skeleton_->inadmissible_state(effective(stress, state), state);
  }
  void update_stress(const StressUpdateBatch& batch) const override;
  double constrained_modulus(const Stress& stress, const double* state) const override;
  double shear_modulus(const Stress& stress, const double* state) const override;
  /// The skeleton's plus the water's p^2 / (2 K_w / n).
  double elastic_energy_density(const Stress& stress, const double* state) const override;

  /// What the water makes of the skeleton's stiffness at this (total) stress and state: the
  /// undrained bulk modulus, Skempton's B and the undrained Poisson ratio.
  UndrainedResponse response(const Stress& stress, const double* state) const;

  /// The initial porosity n0 = 1 - rho_d / rho_s.
  double porosity() const { return porosity_; }
  /// K_w / n0 (Pa).
  double water_stiffness() const { return water_stiffness_; }
  double water_density() const { return water_density_; }
  double water_column_pressure() const override { return column_pressure_; }
  double pore_pressure_limit() const override { return pore_limit_; }
  Drainage drainage() const { return coupled_ ? Drainage::coupled : Drainage::undrained; }

private:
  Stress effective(const Stress& stress, const double* state) const;
  /// K_w / n at this state: n0's for undrained soil, the particle's porosity now for coupled.
  double water_stiffness(const double* state) const {
    return coupled_ ? liquid_.bulk_modulus / state[liquid_.porosity_slot] : water_stiffness_;
  }
  /// What the water adds to the stiffness the time step follows: nothing when the solver takes
  /// the pore pressure implicitly.
  double step_stiffness(const double* state) const {
    return implicit_ ? 0.0 : water_stiffness(state);
  }

  std::unique_ptr<Material> skeleton_;
  double porosity_ = 0.0;
  /// The skeleton's void ratio slot, or -1: with one, the coupled water's porosity is e / (1 + e).
  int void_ratio_index_ = -1;
  double porosity_of(const double* state) const {
    if (void_ratio_index_ < 0) {
      return porosity_;
    }
    const double e = state[void_ratio_index_];
    return e > 0.0 ? e / (1.0 + e) : porosity_;
  }
  double water_stiffness_ = 0.0;
  double density_ = 0.0;
  double water_density_ = 0.0;
  double column_pressure_ = 0.0;
  double pore_limit_ = 0.0;
  int pore_index_ = 0; // state[pore_index_] is p, state[pore_index_ + 1] its change since the start
  bool coupled_ = false;
  bool implicit_ = false; // the solver finds the pore pressure (PoreWater::implicit_pressure)
  LiquidPhase liquid_;
  PoreStorage storage_;
  std::vector<std::string> state_names_;
};

} // namespace mpile
