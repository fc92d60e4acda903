#pragma once

#include <array>

namespace mpile {

/// Symmetric tensors are stored as 6 components in this order (physics.md section 1):
/// rr, yy, thth, ry, ytheta, rtheta. Stress is Cauchy, tension positive. Strain increments carry
/// engineering shear (gamma = 2 eps) in the last three slots, as in the seed's B matrix.
/// In plane strain the "thth" slot holds the out-of-plane (zz) component.
enum Component : int { RR = 0, YY = 1, TT = 2, RY = 3, YT = 4, RT = 5 };

using Stress = std::array<double, 6>;
using StrainIncrement = std::array<double, 6>;

inline double trace(const Stress& s) {
  return s[RR] + s[YY] + s[TT];
}

/// Mean stress p = -tr(sigma)/3 (compression positive, the soil-mechanics sign).
inline double mean_pressure(const Stress& s) {
  return -trace(s) / 3.0;
}

/// Von Mises equivalent deviatoric stress q = sqrt(3 J2).
double deviatoric_stress(const Stress& s);

/// Adds the isotropic elastic response to a strain increment (engineering shear):
/// d sigma = lambda tr(d eps) I + 2 mu d eps.
void add_isotropic_elastic_increment(Stress& s, const StrainIncrement& de, double lambda,
                                     double mu);

/// Energy per unit volume (1/2) sigma : C^-1 : sigma of isotropic elasticity with bulk modulus K
/// and shear modulus mu, split into volumetric and deviatoric parts.
double isotropic_elastic_energy_density(const Stress& s, double bulk, double mu);

} // namespace mpile
