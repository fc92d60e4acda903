#include "engine/materials/undrained_soil.hpp"

#include <stdexcept>

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
  water_stiffness_ = water.bulk_modulus / porosity_;
  density_ = skeleton_->density() + porosity_ * water.density;
  water_density_ = water.density;
  const auto names = skeleton_->state_names();
  state_names_.assign(names.begin(), names.end());
  pore_index_ = static_cast<int>(state_names_.size());
  state_names_.push_back("pore_pressure");
  state_names_.push_back("excess_pore_pressure");
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
    const double dp = water_stiffness_ * (de[RR] + de[YY] + de[TT]);
    water[0] += dp;
    water[1] += dp;
    Stress& s = batch.stress[i];
    s[RR] += water[0];
    s[YY] += water[0];
    s[TT] += water[0];
    batch.constrained_modulus[k] += water_stiffness_;
  }
}

double UndrainedSoil::constrained_modulus(const Stress& stress, const double* state) const {
  return skeleton_->constrained_modulus(effective(stress, state), state) + water_stiffness_;
}

double UndrainedSoil::shear_modulus(const Stress& stress, const double* state) const {
  return skeleton_->shear_modulus(effective(stress, state), state);
}

UndrainedResponse UndrainedSoil::response(const Stress& stress, const double* state) const {
  const Stress sigma = effective(stress, state);
  const double shear = skeleton_->shear_modulus(sigma, state);
  const double bulk = skeleton_->constrained_modulus(sigma, state) - 4.0 / 3.0 * shear;
  return undrained_response(bulk, shear, water_stiffness_);
}

double UndrainedSoil::elastic_energy_density(const Stress& stress, const double* state) const {
  const double p = state[pore_index_];
  return skeleton_->elastic_energy_density(effective(stress, state), state) +
         0.5 * p * p / water_stiffness_;
}

} // namespace mpile
