#include "engine/materials/undrained_soil.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace mpile {

UndrainedSoil::UndrainedSoil(std::unique_ptr<Material> skeleton, const PoreWater& water)
    : skeleton_(std::move(skeleton)) {
  if (skeleton_->is_rigid()) {
    throw std::invalid_argument("drainage: a rigid material has no pores");
  }
  porosity_ = mpile::porosity(skeleton_->density(), water);
  if (!(porosity_ > 0.0 && porosity_ < 1.0)) {
    throw std::invalid_argument("grain_density must exceed the (dry) density for pores to hold "
                                "water: the porosity 1 - density / grain_density is " +
                                std::to_string(porosity_));
  }
  void_ratio_index_ = skeleton_->void_ratio_index();
  if (void_ratio_index_ >= 0) {
    // A skeleton that carries its void ratio holds the porosity: the density must say the same
    // (to 1e-3, a density given to four digits), and the pores are those of e0.
    std::vector<double> start(skeleton_->state_size(), 0.0);
    skeleton_->initialise_state(Stress{}, start.data());
    const double e0 = start[static_cast<std::size_t>(void_ratio_index_)];
    const double from_void_ratio = e0 / (1.0 + e0);
    if (std::abs(from_void_ratio - porosity_) > 1e-3) {
      throw std::invalid_argument(
          "density gives the porosity 1 - density / grain_density = " + std::to_string(porosity_) +
          " differs from the void ratio's e0 / (1 + e0) = " + std::to_string(from_void_ratio) +
          ": give the dry density grain_density / (1 + e0) = " +
          std::to_string(water.grain_density / (1.0 + e0)) + " kg/m^3");
    }
    porosity_ = from_void_ratio;
  }
  if (!(water.column_pressure >= 0.0) || !(water.cavitation_stress >= 0.0)) {
    throw std::invalid_argument("the water column's pressure and the cavitation stress must be "
                                ">= 0 Pa");
  }
  water_stiffness_ = water.bulk_modulus / porosity_;
  column_pressure_ = water.column_pressure;
  pore_limit_ = water.column_pressure + water.cavitation_stress;
  density_ = skeleton_->density() + porosity_ * water.density;
  water_density_ = water.density;
  const auto names = skeleton_->state_names();
  state_names_.assign(names.begin(), names.end());
  pore_index_ = static_cast<int>(state_names_.size());
  state_names_.push_back("pore_pressure");
  state_names_.push_back("excess_pore_pressure");
  coupled_ = water.drainage == Drainage::coupled;
  if (coupled_) {
    if (!(water.hydraulic_conductivity > 0.0)) {
      throw std::invalid_argument("hydraulic_conductivity: a coupled material needs its Darcy "
                                  "hydraulic conductivity k > 0 (m/s)");
    }
    liquid_.pore_slot = pore_index_;
    liquid_.velocity_slot = static_cast<int>(state_names_.size());
    state_names_.push_back("water_velocity_r");
    state_names_.push_back("water_velocity_y");
    state_names_.push_back("water_velocity_theta");
    liquid_.porosity_slot = static_cast<int>(state_names_.size());
    state_names_.push_back("porosity");
    liquid_.water_density = water.density;
    // The grains' density the dry density implies at the porosity the material starts with (for
    // a skeleton with its own void ratio, that void ratio's): the first step's mass is the
    // density's, whatever rounding the density was given to.
    liquid_.grain_density = skeleton_->density() / (1.0 - porosity_);
    liquid_.drag_per_mass = standard_gravity / water.hydraulic_conductivity;
    liquid_.bulk_modulus = water.bulk_modulus;
    liquid_.pore_limit = pore_limit_;
  }
  implicit_ = water.implicit_pressure;
  storage_.pore_slot = pore_index_;
  storage_.porosity_slot = coupled_ ? liquid_.porosity_slot : -1;
  storage_.porosity = porosity_;
  storage_.bulk_modulus = water.bulk_modulus;
  storage_.pore_limit = pore_limit_;
}

Stress UndrainedSoil::effective(const Stress& stress, const double* state) const {
  const double p = state[pore_index_];
  Stress s = stress;
  s[RR] -= p;
  s[YY] -= p;
  s[TT] -= p;
  return s;
}

void UndrainedSoil::initialise_state(const Stress& stress, double* state) const {
  skeleton_->initialise_state(effective(stress, state), state);
  state[pore_index_ + 1] = 0.0;
  if (coupled_) {
    // The water starts with the skeleton (at rest), in the pores of the dry density.
    state[liquid_.velocity_slot] = 0.0;
    state[liquid_.velocity_slot + 1] = 0.0;
    state[liquid_.velocity_slot + 2] = 0.0;
    state[liquid_.porosity_slot] = porosity_of(state);
  }
}

void UndrainedSoil::update_stress(const StressUpdateBatch& batch) const {
  const auto stride = static_cast<std::size_t>(batch.state_stride);
  const auto pore = static_cast<std::size_t>(pore_index_);
  for (const std::int32_t i : batch.particles) {
    Stress& s = batch.stress[i];
    const double p = batch.state[static_cast<std::size_t>(i) * stride + pore];
    s[RR] -= p;
    s[YY] -= p;
    s[TT] -= p;
  }
  // The skeleton sees the effective stress and the same strain, and keeps its state where it
  // always does: the first entries of each particle's state.
  skeleton_->update_stress(batch);
  for (std::size_t k = 0; k < batch.particles.size(); ++k) {
    const auto i = static_cast<std::size_t>(batch.particles[k]);
    const StrainIncrement& de = batch.strain[k];
    double* water = batch.state + i * stride + pore;
    const double volumetric = de[RR] + de[YY] + de[TT];
    // With the implicit pore pressure the solver has found this step's increment on the grid and
    // adds it after this pass, and the water sets no step: dp and the stiffness stay 0.
    double stiffness = 0.0;
    double dp = 0.0;
    if (coupled_) {
      // The skeleton's share of the water's volume change, (1 - n) d eps_vol: the grains it moves
      // into or out of the pores; the water's own flow adds n d eps_vol,w (the solver's water
      // pass). The grains are incompressible, so their volume (1 - n) V is kept.
      double& n = batch.state[i * stride + static_cast<std::size_t>(liquid_.porosity_slot)];
      if (!implicit_) {
        dp = liquid_.bulk_modulus * (1.0 - n) / n * volumetric;
      }
      // The grains' volume kept, or the skeleton's own void ratio where it carries one (the same
      // law, e' = (1 + e)(1 + d eps_vol) - 1 to first order: one state, not two copies).
      n = void_ratio_index_ >= 0 ? porosity_of(batch.state + i * stride)
                                 : 1.0 - (1.0 - n) / (1.0 + volumetric);
      // The step follows the undrained P-wave, the faster of the two phases' (Biot's fast wave
      // lies between the drained skeleton's and it).
      stiffness = implicit_ ? 0.0 : liquid_.bulk_modulus / n;
    } else if (!implicit_) {
      dp = water_stiffness_ * volumetric;
      stiffness = water_stiffness_;
    }
    // Beyond the cavitation stress the water boils out of solution and carries no more tension:
    // the skeleton alone takes the rest of the dilation (its work is then dissipated).
    dp = std::min(dp, pore_limit_ - water[0]);
    water[0] += dp;
    water[1] += dp;
    Stress& s = batch.stress[i];
    s[RR] += water[0];
    s[YY] += water[0];
    s[TT] += water[0];
    batch.constrained_modulus[k] += stiffness;
  }
}

double UndrainedSoil::constrained_modulus(const Stress& stress, const double* state) const {
  return skeleton_->constrained_modulus(effective(stress, state), state) + step_stiffness(state);
}

double UndrainedSoil::shear_modulus(const Stress& stress, const double* state) const {
  return skeleton_->shear_modulus(effective(stress, state), state);
}

UndrainedResponse UndrainedSoil::response(const Stress& stress, const double* state) const {
  const Stress sigma = effective(stress, state);
  const double shear = skeleton_->shear_modulus(sigma, state);
  const double bulk = skeleton_->constrained_modulus(sigma, state) - 4.0 / 3.0 * shear;
  return undrained_response(bulk, shear, water_stiffness(state));
}

double UndrainedSoil::elastic_energy_density(const Stress& stress, const double* state) const {
  const double p = state[pore_index_];
  return skeleton_->elastic_energy_density(effective(stress, state), state) +
         0.5 * p * p / water_stiffness(state);
}

} // namespace mpile
