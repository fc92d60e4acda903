#include "engine/principal_stress.hpp"

#include <Eigen/Eigenvalues>

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

PrincipalStress principal_compression(const Stress& stress) {
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

Stress compose_from_principal(const std::array<double, 3>& compression,
                              const Eigen::Matrix3d& directions) {
  const Eigen::Vector3d values(compression[0], compression[1], compression[2]);
  const Eigen::Matrix3d m = directions * values.asDiagonal() * directions.transpose();
  return from_matrix(-m);
}

} // namespace mpile
