#include "engine/linear_elastic.hpp"

#include <stdexcept>
#include <string>

namespace mpile {

LinearElastic::LinearElastic(double young_modulus, double poisson_ratio, double density)
    : young_(young_modulus), poisson_(poisson_ratio), density_(density) {
  if (!(young_modulus > 0.0)) {
    throw std::invalid_argument("young_modulus must be positive, got " +
                                std::to_string(young_modulus));
  }
  if (!(poisson_ratio > -1.0 && poisson_ratio < 0.5)) {
    throw std::invalid_argument("poisson_ratio must lie in (-1, 0.5), got " +
                                std::to_string(poisson_ratio));
  }
  if (!(density > 0.0)) {
    throw std::invalid_argument("density must be positive, got " + std::to_string(density));
  }
  mu_ = young_ / (2.0 * (1.0 + poisson_));
  lambda_ = young_ * poisson_ / ((1.0 + poisson_) * (1.0 - 2.0 * poisson_));
}

void LinearElastic::update_stress(const StressUpdateBatch& batch) const {
  const double modulus = lambda_ + 2.0 * mu_;
  for (std::size_t k = 0; k < batch.particles.size(); ++k) {
    const StrainIncrement& de = batch.strain[k];
    Stress& s = batch.stress[batch.particles[k]];
    const double volumetric = lambda_ * (de[RR] + de[YY] + de[TT]);
    s[RR] += volumetric + 2.0 * mu_ * de[RR];
    s[YY] += volumetric + 2.0 * mu_ * de[YY];
    s[TT] += volumetric + 2.0 * mu_ * de[TT];
    s[RY] += mu_ * de[RY]; // engineering shear: d tau = mu d gamma
    s[YT] += mu_ * de[YT];
    s[RT] += mu_ * de[RT];
    batch.constrained_modulus[k] = modulus;
  }
}

double LinearElastic::elastic_energy_density(const Stress& s, const double*) const {
  // w = (1/2) sigma : C^-1 : sigma, split into volumetric and deviatoric parts.
  const double bulk = lambda_ + 2.0 * mu_ / 3.0;
  const double mean = trace(s) / 3.0;
  const double drr = s[RR] - mean;
  const double dyy = s[YY] - mean;
  const double dtt = s[TT] - mean;
  const double deviatoric_sq =
      drr * drr + dyy * dyy + dtt * dtt + 2.0 * (s[RY] * s[RY] + s[YT] * s[YT] + s[RT] * s[RT]);
  return 0.5 * mean * mean / bulk + deviatoric_sq / (4.0 * mu_);
}

} // namespace mpile
