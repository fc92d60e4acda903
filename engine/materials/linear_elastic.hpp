#pragma once

#include "engine/materials/material.hpp"

namespace mpile {

/// Isotropic linear elasticity in rate form: d sigma = lambda tr(d eps) I + 2 mu d eps.
class LinearElastic final : public Material {
public:
  /// Throws std::invalid_argument for E <= 0, nu outside (-1, 0.5) or density <= 0.
  LinearElastic(double young_modulus, double poisson_ratio, double density);

  std::string_view type() const override { return "linear_elastic"; }
  double density() const override { return density_; }
  void update_stress(const StressUpdateBatch& batch) const override;
  double constrained_modulus(const Stress&, const double*) const override {
    return lambda_ + 2.0 * mu_;
  }
  double shear_modulus(const Stress&, const double*) const override { return mu_; }
  double elastic_energy_density(const Stress& stress, const double* state) const override;

  double young_modulus() const { return young_; }
  double poisson_ratio() const { return poisson_; }
  using Material::shear_modulus;
  double shear_modulus() const { return mu_; }
  double lame_lambda() const { return lambda_; }

private:
  double young_;
  double poisson_;
  double density_;
  double lambda_;
  double mu_;
};

} // namespace mpile
