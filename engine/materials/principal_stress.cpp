#include "engine/materials/principal_stress.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mpile {

Eigen::Matrix3d to_matrix(const std::array<double, 6>& t, bool engineering_shear) {
  const double f = engineering_shear ? 0.5 : 1.0;
  Eigen::Matrix3d m;
  m << t[RR], f * t[RY], f * t[RT], //
      f * t[RY], t[YY], f * t[YT],  //
      f * t[RT], f * t[YT], t[TT];
  return m;
}

std::array<double, 6> from_matrix(const Eigen::Matrix3d& m, bool engineering_shear) {
  const double f = engineering_shear ? 2.0 : 1.0;
  return {m(0, 0),
          m(1, 1),
          m(2, 2),
          f * 0.5 * (m(0, 1) + m(1, 0)),
          f * 0.5 * (m(1, 2) + m(2, 1)),
          f * 0.5 * (m(0, 2) + m(2, 0))};
}

namespace {

/// The decomposition of an r-y block and the out-of-plane stress (no theta shears, as everywhere
/// outside torsion): the block's pair in closed form, its directions from the eigenvector
/// equation's better-conditioned row, so without iterations or trigonometry.
PrincipalStress block_compression(const Stress& stress) {
  const double a11 = -stress[RR], a22 = -stress[YY], a12 = -stress[RY];
  const double centre = 0.5 * (a11 + a22);
  const double half_difference = 0.5 * (a11 - a22);
  const double radius = std::sqrt(half_difference * half_difference + a12 * a12);
  // The major direction: (lambda_1 - a22, a12) if a11 >= a22, else (a12, lambda_1 - a11); the
  // chosen first entry is at least the radius, so the vector never cancels.
  double c = 1.0, s = 0.0;
  if (radius > 0.0) {
    const double x = half_difference >= 0.0 ? half_difference + radius : a12;
    const double y = half_difference >= 0.0 ? a12 : radius - half_difference;
    const double length = std::hypot(x, y);
    c = x / length;
    s = y / length;
  }
  struct Pair {
    double value;
    Eigen::Vector3d direction;
  };
  std::array<Pair, 3> pairs{Pair{centre + radius, Eigen::Vector3d(c, s, 0.0)},
                            Pair{centre - radius, Eigen::Vector3d(-s, c, 0.0)},
                            Pair{-stress[TT], Eigen::Vector3d(0.0, 0.0, 1.0)}};
  if (pairs[2].value > pairs[1].value) {
    std::swap(pairs[1], pairs[2]);
    if (pairs[1].value > pairs[0].value) {
      std::swap(pairs[0], pairs[1]);
    }
  }
  PrincipalStress p;
  for (int k = 0; k < 3; ++k) {
    p.values[static_cast<std::size_t>(k)] = pairs[static_cast<std::size_t>(k)].value;
    p.directions.col(k) = pairs[static_cast<std::size_t>(k)].direction;
  }
  return p;
}

} // namespace

PrincipalStress principal_compression(const Stress& stress) {
  if (stress[RT] == 0.0 && stress[YT] == 0.0) {
    return block_compression(stress);
  }
  // Eigenvalues of the compression-positive tensor, ascending from Eigen; reversed so that
  // values[0] is the major (most compressive) stress.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(-to_matrix(stress));
  PrincipalStress p;
  for (int k = 0; k < 3; ++k) {
    p.values[static_cast<std::size_t>(k)] = solver.eigenvalues()(2 - k);
    p.directions.col(k) = solver.eigenvectors().col(2 - k);
  }
  return p;
}

PrincipalValues principal_compression_values(const Stress& stress) {
  PrincipalValues p;
  std::array<double, 3>& v = p.values;
  if (stress[RT] == 0.0 && stress[YT] == 0.0) {
    // An r-y block and the out-of-plane value: the block's pair from the half-difference and the
    // shear, without cancellation.
    const double centre = -0.5 * (stress[RR] + stress[YY]);
    const double half_difference = 0.5 * (stress[RR] - stress[YY]);
    const double radius = std::sqrt(half_difference * half_difference + stress[RY] * stress[RY]);
    v = {centre + radius, centre - radius, -stress[TT]};
    if (v[2] > v[1]) {
      std::swap(v[1], v[2]);
      if (v[1] > v[0]) {
        std::swap(v[0], v[1]);
      }
    }
    return p;
  }
  // Trigonometric roots of the characteristic cubic of the deviator B = A - q I (A = -sigma):
  // with s = |B| / sqrt(6), the roots are q + 2 s cos(phi + 2 pi k / 3), phi = acos(det(B) /
  // (2 s^3)) / 3, which lies in [0, pi/3] and so orders them.
  const double q = -(stress[RR] + stress[YY] + stress[TT]) / 3.0;
  const double b11 = -stress[RR] - q, b22 = -stress[YY] - q, b33 = -stress[TT] - q;
  const double b12 = -stress[RY], b23 = -stress[YT], b13 = -stress[RT];
  const double off = b12 * b12 + b23 * b23 + b13 * b13;
  const double s2 = (b11 * b11 + b22 * b22 + b33 * b33 + 2.0 * off) / 6.0;
  if (!(s2 > 0.0)) { // theta shears so small that their squares underflow: isotropic
    v = {q, q, q};
    return p;
  }
  const double s = std::sqrt(s2);
  const double determinant =
      b11 * (b22 * b33 - b23 * b23) - b12 * (b12 * b33 - b23 * b13) + b13 * (b12 * b23 - b22 * b13);
  const double r = std::clamp(determinant / (2.0 * s2 * s), -1.0, 1.0);
  const double phi = std::acos(r) / 3.0;
  v[0] = q + 2.0 * s * std::cos(phi);
  v[2] = q + 2.0 * s * std::cos(phi + 2.0 * std::numbers::pi / 3.0);
  v[1] = std::clamp(3.0 * q - v[0] - v[2], v[2], v[0]); // ordered despite rounding
  // An error of a few ulps in r moves phi by sqrt(ulps) near r = +-1: about 3e-8 s.
  p.uncertainty = 1e-6 * s;
  return p;
}

Stress compose_from_principal(const std::array<double, 3>& compression,
                              const Eigen::Matrix3d& directions) {
  const Eigen::Vector3d values(compression[0], compression[1], compression[2]);
  const Eigen::Matrix3d m = directions * values.asDiagonal() * directions.transpose();
  return from_matrix(-m);
}

} // namespace mpile
