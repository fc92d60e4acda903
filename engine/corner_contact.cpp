// Contact at a node where two surfaces of a structure's outline meet (physics.md section 5).
#include "engine/corner_contact.hpp"

#include <cmath>

namespace mpile {

namespace {

double dot(const std::array<double, 2>& a, const std::array<double, 2>& b) {
  return a[0] * b[0] + a[1] * b[1];
}

} // namespace

CornerProjection project_on_corner(const std::array<double, 2>& u, const std::array<double, 2>& n1,
                                   const std::array<double, 2>& n2) {
  const double d1 = dot(u, n1);
  const double d2 = dot(u, n2);
  if (d1 >= 0.0 && d2 >= 0.0) {
    // Admissible. Soil that does not move away from a surface is in contact with it, as at a node
    // of one surface, so that friction and adhesion act on soil at rest against it.
    if (d1 > 0.0 && d2 > 0.0) {
      return {CornerActive::none, u};
    }
    if (d1 == 0.0 && d2 == 0.0) {
      return {CornerActive::both, u};
    }
    return {d1 == 0.0 ? CornerActive::first : CornerActive::second, u};
  }
  // The nearest admissible point lies on a face of the cone or at its apex: take the nearest of
  // the admissible candidates. A face's candidate removes the approach along its normal.
  CornerProjection best{CornerActive::both, {0.0, 0.0}};
  double best_distance = dot(u, u);
  auto try_face = [&](double d, const std::array<double, 2>& n, const std::array<double, 2>& other,
                      CornerActive active) {
    if (d >= 0.0) {
      return;
    }
    const std::array<double, 2> v{u[0] - d * n[0], u[1] - d * n[1]};
    if (dot(v, other) >= 0.0 && d * d <= best_distance) { // a face before the apex on a tie
      best = {active, v};
      best_distance = d * d;
    }
  };
  try_face(d1, n1, n2, CornerActive::first);
  try_face(d2, n2, n1, CornerActive::second);
  return best;
}

std::array<double, 2> split_on_normals(const std::array<double, 2>& f,
                                       const std::array<double, 2>& n1,
                                       const std::array<double, 2>& n2) {
  const double det = n1[0] * n2[1] - n1[1] * n2[0];
  return {(f[0] * n2[1] - f[1] * n2[0]) / det, (n1[0] * f[1] - n1[1] * f[0]) / det};
}

} // namespace mpile
