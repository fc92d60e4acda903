#include "engine/tensor.hpp"

#include <cmath>

namespace mpile {

double deviatoric_stress(const Stress& s) {
  const double p = trace(s) / 3.0;
  const double drr = s[RR] - p;
  const double dyy = s[YY] - p;
  const double dtt = s[TT] - p;
  const double j2 =
      0.5 * (drr * drr + dyy * dyy + dtt * dtt) + s[RY] * s[RY] + s[YT] * s[YT] + s[RT] * s[RT];
  return std::sqrt(3.0 * j2);
}

void add_isotropic_elastic_increment(Stress& s, const StrainIncrement& de, double lambda,
                                     double mu) {
  const double volumetric = lambda * (de[RR] + de[YY] + de[TT]);
  s[RR] += volumetric + 2.0 * mu * de[RR];
  s[YY] += volumetric + 2.0 * mu * de[YY];
  s[TT] += volumetric + 2.0 * mu * de[TT];
  s[RY] += mu * de[RY]; // engineering shear: d tau = mu d gamma
  s[YT] += mu * de[YT];
  s[RT] += mu * de[RT];
}

double isotropic_elastic_energy_density(const Stress& s, double bulk, double mu) {
  const double mean = trace(s) / 3.0;
  const double drr = s[RR] - mean;
  const double dyy = s[YY] - mean;
  const double dtt = s[TT] - mean;
  const double deviatoric_sq =
      drr * drr + dyy * dyy + dtt * dtt + 2.0 * (s[RY] * s[RY] + s[YT] * s[YT] + s[RT] * s[RT]);
  return 0.5 * mean * mean / bulk + deviatoric_sq / (4.0 * mu);
}

} // namespace mpile
