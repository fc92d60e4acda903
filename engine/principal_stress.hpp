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

/// Decomposes an engine stress (tension positive). Robust at repeated eigenvalues (K0 states,
/// triaxial corners): the directions are then any orthonormal basis of the repeated subspace.
PrincipalStress principal_compression(const Stress& stress);

/// Recomposes an engine stress (tension positive) from principal compressions and directions.
Stress compose_from_principal(const std::array<double, 3>& compression,
                              const Eigen::Matrix3d& directions);

} // namespace mpile
