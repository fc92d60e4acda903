#pragma once

// Principal stresses for the soil models: the full 3x3 stress (the r-theta and y-theta shears of
// torsion included) is decomposed spectrally, never reduced to an r-y shortcut. Soil models work in
// the soil-mechanics convention (compression positive, sigma_1 >= sigma_2 >= sigma_3) and convert
// at this boundary.

#include "engine/tensor.hpp"

#include <Eigen/Core>

#include <array>

namespace mpile {

/// Symmetric 3x3 matrix of a 6-component tensor in the basis (r, y, theta). With
/// engineering_shear, the last three components are halved (a strain increment).
Eigen::Matrix3d to_matrix(const std::array<double, 6>& tensor, bool engineering_shear = false);
std::array<double, 6> from_matrix(const Eigen::Matrix3d& matrix, bool engineering_shear = false);

/// Principal compressive stresses values[0] >= values[1] >= values[2] (compression positive) and
/// their unit directions (columns, in the same order).
struct PrincipalStress {
  std::array<double, 3> values{};
  Eigen::Matrix3d directions = Eigen::Matrix3d::Identity();
};

/// Decomposes an engine stress (tension positive), without iterations: an r-y block and the
/// out-of-plane stress in closed form; with theta shears, the value farther from the other two
/// and its direction first, then the other two as a closed-form pair in the plane normal to it.
/// Robust at repeated eigenvalues (K0 states, triaxial corners): the directions are then any
/// orthonormal basis of the repeated subspace.
PrincipalStress principal_compression(const Stress& stress);

/// Principal compressive stresses alone (compression positive, descending), for the test of a
/// trial stress, where directions are needed only if it turns out plastic. uncertainty bounds the
/// error of the values: zero (rounding only) when the theta shears vanish, as without torsion, for
/// the tensor is then an r-y block and the out-of-plane stress; otherwise the values come from the
/// closed form of the characteristic cubic, whose double root is ill-conditioned, so that where
/// two principal stresses nearly coincide they may be off by about 1e-8 of the deviatoric stress
/// (uncertainty is set 30 times higher). Decisions on them must keep that margin.
struct PrincipalValues {
  std::array<double, 3> values{};
  double uncertainty = 0.0;
};
PrincipalValues principal_compression_values(const Stress& stress);

/// Principal compressive stresses for a decision with a margin (is a trial inside the surfaces?):
/// where the theta shears are small against the stress, the values of the r-y block and the hoop
/// stress alone, uncertainty |RT| + |YT| (at least the norm of the coupling the block leaves out,
/// which by Weyl's inequality bounds how far each ordered value moves), otherwise
/// principal_compression_values. The bound is far tighter near a double root, where the cubic's
/// values are ill-conditioned, and the block costs a fraction of the cubic; but the values are
/// not the tensor's to rounding, so `bounded` says that a decomposition needs
/// principal_compression_values first.
struct PrincipalEstimate {
  PrincipalValues values;
  bool bounded = false;
};
PrincipalEstimate principal_compression_estimate(const Stress& stress);

/// The smallest principal compression alone, principal_compression_values(stress).values[2] to the
/// bit (for a stiffness law of sigma_3, which needs no other value).
double principal_compression_minor(const Stress& stress);

/// principal_compression for a stress whose values are known (principal_compression_values of the
/// same stress): the closed form of the cubic is not evaluated again.
PrincipalStress principal_compression(const Stress& stress, const PrincipalValues& values);

/// Recomposes an engine stress (tension positive) from principal compressions and directions.
Stress compose_from_principal(const std::array<double, 3>& compression,
                              const Eigen::Matrix3d& directions);

} // namespace mpile
