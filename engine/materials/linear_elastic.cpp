#include "engine/materials/linear_elastic.hpp"

#include <stdexcept>
#include <string>

namespace mpile {

LinearElastic::LinearElastic(double young_modulus, double poisson_ratio, double density)
    : young_(young_modulus), poisson_(poisson_ratio), density_(density) {
  require_in_range("young_modulus", young_modulus_range, young_modulus);
  require_in_range("poisson_ratio", poisson_ratio_range, poisson_ratio);
  require_in_range("density", density_range, density);
  mu_ = young_ / (2.0 * (1.0 + poisson_));
  lambda_ = young_ * poisson_ / ((1.0 + poisson_) * (1.0 - 2.0 * poisson_));
}

void LinearElastic::update_stress(const StressUpdateBatch& batch) const {
  const double modulus = lambda_ + 2.0 * mu_;
  for (std::size_t k = 0; k < batch.particles.size(); ++k) {
    add_isotropic_elastic_increment(batch.stress[batch.particles[k]], batch.strain[k], lambda_,
                                    mu_);
    batch.constrained_modulus[k] = modulus;
  }
}

double LinearElastic::elastic_energy_density(const Stress& s, const double*) const {
  return isotropic_elastic_energy_density(s, lambda_ + 2.0 * mu_ / 3.0, mu_);
}

} // namespace mpile
