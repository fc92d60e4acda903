#include "engine/materials/principal_stress.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

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

/// The pair of a symmetric 2x2 block [[a11, a12], [a12, a22]]: its values in closed form and the
/// major direction (c, s) from the eigenvector equation's better-conditioned row (the first entry
/// is at least the radius, so the vector never cancels); the minor direction is (-s, c).
struct BlockPair {
  double major, minor, c, s;
};

BlockPair block_pair(double a11, double a22, double a12) {
  const double centre = 0.5 * (a11 + a22);
  const double half_difference = 0.5 * (a11 - a22);
  const double radius = std::sqrt(half_difference * half_difference + a12 * a12);
  double c = 1.0, s = 0.0;
  if (radius > 0.0) {
    const double x = half_difference >= 0.0 ? half_difference + radius : a12;
    const double y = half_difference >= 0.0 ? a12 : radius - half_difference;
    // x^2 + y^2 = 2 radius (radius + |half_difference|): no cancellation, and a square root
    // where std::hypot costs many times that.
    const double length = std::sqrt(2.0 * radius * (radius + std::abs(half_difference)));
    c = x / length;
    s = y / length;
  }
  return {centre + radius, centre - radius, c, s};
}

/// The decomposition of an r-y block and the out-of-plane stress (no theta shears, as everywhere
/// outside torsion): the block's pair in closed form, so without iterations or trigonometry.
PrincipalStress block_compression(const Stress& stress) {
  const BlockPair pair = block_pair(-stress[RR], -stress[YY], -stress[RY]);
  struct Pair {
    double value;
    Eigen::Vector3d direction;
  };
  std::array<Pair, 3> pairs{Pair{pair.major, Eigen::Vector3d(pair.c, pair.s, 0.0)},
                            Pair{pair.minor, Eigen::Vector3d(-pair.s, pair.c, 0.0)},
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

/// The full tensor (theta shears present) without iterations: the eigenvalue farther from the
/// other two from the characteristic cubic's trigonometric roots, its direction from the largest
/// cross product of two rows of A - lambda I (well conditioned: its gap is at least half the
/// spread of the values), then the other two as the closed-form pair of A projected on the plane
/// normal to it, which is exact however close they are (the method of D. Eberly, "A robust
/// eigensolver for 3 x 3 symmetric matrices", 2014). A is the compression-positive tensor.
PrincipalStress full_compression(const Stress& stress, double apart) {
  const Eigen::Matrix3d a = -to_matrix(stress);
  const Eigen::Matrix3d m = a - apart * Eigen::Matrix3d::Identity();
  const Eigen::Vector3d crosses[3] = {m.row(0).cross(m.row(1)), m.row(0).cross(m.row(2)),
                                      m.row(1).cross(m.row(2))};
  const double norms[3] = {crosses[0].squaredNorm(), crosses[1].squaredNorm(),
                           crosses[2].squaredNorm()};
  const int best =
      norms[0] >= norms[1] ? (norms[0] >= norms[2] ? 0 : 2) : (norms[1] >= norms[2] ? 1 : 2);
  PrincipalStress p;
  if (!(norms[best] > 0.0)) { // A = lambda I: isotropic, any basis
    p.values = {apart, apart, apart};
    return p;
  }
  const Eigen::Vector3d u = crosses[best] / std::sqrt(norms[best]);
  // An orthonormal basis (v, w) of the plane normal to u, from u's larger entries.
  const Eigen::Vector3d v = std::abs(u.x()) > std::abs(u.y())
                                ? Eigen::Vector3d(-u.z(), 0.0, u.x()).normalized()
                                : Eigen::Vector3d(0.0, u.z(), -u.y()).normalized();
  const Eigen::Vector3d w = u.cross(v);
  const Eigen::Vector3d av = a * v, aw = a * w;
  const BlockPair pair = block_pair(v.dot(av), w.dot(aw), v.dot(aw));
  // Descending: the pair is ordered, and the value apart (its Rayleigh quotient, accurate to
  // rounding) goes above, between or below it.
  const double value = u.dot(a * u);
  const Eigen::Vector3d major = pair.c * v + pair.s * w, minor = -pair.s * v + pair.c * w;
  if (value >= pair.major) {
    p.values = {value, pair.major, pair.minor};
    p.directions << u, major, minor;
  } else if (value >= pair.minor) {
    p.values = {pair.major, value, pair.minor};
    p.directions << major, u, minor;
  } else {
    p.values = {pair.major, pair.minor, value};
    p.directions << major, minor, u;
  }
  return p;
}

/// The eigenvalue of the full tensor farther from the other two, from its ordered values: the
/// largest if it lies at least as far above the middle one as the smallest lies below.
double value_apart(const std::array<double, 3>& v) {
  return v[0] - v[1] >= v[1] - v[2] ? v[0] : v[2];
}

} // namespace

PrincipalStress principal_compression(const Stress& stress) {
  if (stress[RT] == 0.0 && stress[YT] == 0.0) {
    return block_compression(stress); // without the values, which the block does not need
  }
  return principal_compression(stress, principal_compression_values(stress));
}

PrincipalStress principal_compression(const Stress& stress, const PrincipalValues& values) {
  if (stress[RT] == 0.0 && stress[YT] == 0.0) {
    return block_compression(stress);
  }
  return full_compression(stress, value_apart(values.values));
}

namespace {

/// The characteristic cubic of the deviator B = A - q I (A = -sigma) in trigonometric form: the
/// roots are q + 2 s cos(phi + 2 pi k / 3) with cos(3 phi) = r = det(B) / (2 s^3) and phi in
/// [0, pi/3], which orders them. s = 0 (theta shears so small that their squares underflow) means
/// isotropic.
struct TrigonometricCubic {
  double q, s, r;
};

TrigonometricCubic trigonometric_cubic(const Stress& stress) {
  const double q = -(stress[RR] + stress[YY] + stress[TT]) / 3.0;
  const double b11 = -stress[RR] - q, b22 = -stress[YY] - q, b33 = -stress[TT] - q;
  const double b12 = -stress[RY], b23 = -stress[YT], b13 = -stress[RT];
  const double off = b12 * b12 + b23 * b23 + b13 * b13;
  const double s2 = (b11 * b11 + b22 * b22 + b33 * b33 + 2.0 * off) / 6.0;
  if (!(s2 > 0.0)) {
    return {q, 0.0, 0.0};
  }
  const double s = std::sqrt(s2);
  const double determinant =
      b11 * (b22 * b33 - b23 * b23) - b12 * (b12 * b33 - b23 * b13) + b13 * (b12 * b23 - b22 * b13);
  return {q, s, std::clamp(determinant / (2.0 * s2 * s), -1.0, 1.0)};
}

/// cos(phi) and cos(phi + 2 pi / 3) of the cubic, the largest and the smallest of the roots of
/// 4 c^3 - 3 c = r, without acos and cosines (which cost about five times as much). The root
/// apart from the other two (the largest for r >= 0; for r < 0 the smallest, minus the largest
/// for -r) is simple. It is found as d = 1 - c, the root of (1 - x) - 9 d + 12 d^2 - 4 d^3 with
/// x = |r| (1 - x exact near 1), by Newton's method from a quartic fit of d / (1 - x) (relative
/// error 1.4e-5; two steps leave about 1e-19 of d): d keeps its relative accuracy as x -> 1, so
/// the sine sqrt(d (2 - d)) and the two roots meeting there, -c / 2 -+ sqrt(3) / 2 sin(phi), are
/// as accurate as acos and cosines gave them (cosines within 2e-16 over 2e7 values of r, r -> +-1
/// among them, against a long double reference).
struct CubicCosines {
  double major, minor;
};

CubicCosines cubic_cosines(double r) {
  const double x = std::abs(r);
  const double y = 1.0 - x;
  double d =
      y * ((((0.0015572785462282517 * y + 0.00015646483886003356) * y + 0.00475077838600148) * y +
            0.016395795253703296) *
               y +
           0.11111248254865923);
  for (int step = 0; step < 2; ++step) {
    d -= (y - d * (9.0 - d * (12.0 - 4.0 * d))) / (d * (24.0 - 12.0 * d) - 9.0);
  }
  const double c = 1.0 - d;
  const double half_root3_sine = 0.5 * std::numbers::sqrt3 * std::sqrt(d * (2.0 - d));
  const double other = -0.5 * c - half_root3_sine;
  return r >= 0.0 ? CubicCosines{c, other} : CubicCosines{-other, -c};
}

/// The r-y block's pair from the half-difference and the shear, without cancellation (centre +-
/// radius, compression positive).
struct BlockValues {
  double centre, radius;
};

BlockValues block_values(const Stress& stress) {
  const double centre = -0.5 * (stress[RR] + stress[YY]);
  const double half_difference = 0.5 * (stress[RR] - stress[YY]);
  return {centre, std::sqrt(half_difference * half_difference + stress[RY] * stress[RY])};
}

/// The ordered values of the r-y block and the out-of-plane stress, the theta shears left out.
std::array<double, 3> block_only_values(const Stress& stress) {
  const BlockValues block = block_values(stress);
  std::array<double, 3> v{block.centre + block.radius, block.centre - block.radius, -stress[TT]};
  if (v[2] > v[1]) {
    std::swap(v[1], v[2]);
    if (v[1] > v[0]) {
      std::swap(v[0], v[1]);
    }
  }
  return v;
}

} // namespace

PrincipalEstimate principal_compression_estimate(const Stress& stress) {
  if (stress[RT] != 0.0 || stress[YT] != 0.0) {
    // Weyl: the ordered values of block + coupling lie within the coupling's norm,
    // sqrt(RT^2 + YT^2) <= |RT| + |YT|, of the block's. Worth it where that is below the cubic's
    // uncertainty (1e-6 s, s at most the largest value's size): on the quick GDP scene most
    // decomposed trials that turned out inside had theta shears below 1e-8 s.
    const double coupling = std::abs(stress[RT]) + std::abs(stress[YT]);
    const std::array<double, 3> v = block_only_values(stress);
    if (coupling <= 1e-8 * (std::abs(v[0]) + std::abs(v[2]))) {
      return {PrincipalValues{v, coupling}, true};
    }
  }
  return {principal_compression_values(stress), false};
}

PrincipalValues principal_compression_values(const Stress& stress) {
  PrincipalValues p;
  std::array<double, 3>& v = p.values;
  if (stress[RT] == 0.0 && stress[YT] == 0.0) {
    v = block_only_values(stress); // an r-y block and the out-of-plane value
    return p;
  }
  const TrigonometricCubic cubic = trigonometric_cubic(stress);
  if (!(cubic.s > 0.0)) {
    v = {cubic.q, cubic.q, cubic.q};
    return p;
  }
  const CubicCosines cosines = cubic_cosines(cubic.r);
  v[0] = cubic.q + 2.0 * cubic.s * cosines.major;
  v[2] = cubic.q + 2.0 * cubic.s * cosines.minor;
  v[1] = std::clamp(3.0 * cubic.q - v[0] - v[2], v[2], v[0]); // ordered despite rounding
  // An error of a few ulps in r moves phi by sqrt(ulps) near r = +-1: about 3e-8 s.
  p.uncertainty = 1e-6 * cubic.s;
  return p;
}

double principal_compression_minor(const Stress& stress) {
  if (stress[RT] == 0.0 && stress[YT] == 0.0) {
    const BlockValues block = block_values(stress);
    const double minor = block.centre - block.radius;
    return -stress[TT] > minor ? minor : -stress[TT]; // as the values' sort picks it
  }
  const TrigonometricCubic cubic = trigonometric_cubic(stress);
  return cubic.s > 0.0 ? cubic.q + 2.0 * cubic.s * cubic_cosines(cubic.r).minor : cubic.q;
}

Stress compose_from_principal(const std::array<double, 3>& compression,
                              const Eigen::Matrix3d& directions) {
  // sigma = -sum_k c_k d_k d_k^T over the directions d_k (columns): its six distinct entries
  // alone, where the matrix product would form all nine and average the shear pairs.
  const Eigen::Matrix3d& d = directions;
  auto entry = [&](int i, int j) {
    return -(compression[0] * d(i, 0) * d(j, 0) + compression[1] * d(i, 1) * d(j, 1) +
             compression[2] * d(i, 2) * d(j, 2));
  };
  return {entry(0, 0), entry(1, 1), entry(2, 2), entry(0, 1), entry(1, 2), entry(0, 2)};
}

} // namespace mpile
