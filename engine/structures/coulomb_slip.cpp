#include "engine/structures/coulomb_slip.hpp"

#include <algorithm>
#include <cmath>

namespace mpile {

SlipKept coulomb_slip(double slip_plane, double slip_theta, double mass, double theta_mass,
                      double limit) {
  const double stick_plane = mass * slip_plane;
  const double stick_theta = theta_mass * slip_theta;
  if (stick_plane * stick_plane + stick_theta * stick_theta <= limit * limit) {
    return {0.0, 0.0};
  }
  const double c_plane = limit / mass;
  const double c_theta = limit / theta_mass;
  const double a = slip_plane * slip_plane;
  const double b = slip_theta * slip_theta;
  // g(x) = a / (x + c_plane)^2 + b / (x + c_theta)^2 - 1 is convex and decreasing, and
  // g(x0) >= 0 at x0 = |t| - max(c) (each denominator is at most |t|^2 there), so Newton's
  // iterates rise monotonically to the root; they stop when rounding stops them rising.
  double x = std::max(0.0, std::sqrt(a + b) - std::max(c_plane, c_theta));
  for (int iteration = 0; iteration < 50; ++iteration) {
    const double p = 1.0 / (x + c_plane);
    const double q = 1.0 / (x + c_theta);
    const double g = a * p * p + b * q * q - 1.0;
    const double slope = -2.0 * (a * p * p * p + b * q * q * q);
    const double next = x - g / slope;
    if (!(next > x)) {
      break;
    }
    x = next;
  }
  return {x / (x + c_plane), x / (x + c_theta)};
}

ContactCorrection contact_correction(const std::array<double, 3>& relative,
                                     const std::array<double, 2>& n, double mass, double theta_mass,
                                     double friction, double adhesion_impulse,
                                     double pore_impulse) {
  const double normal_velocity = relative[0] * n[0] + relative[1] * n[1];
  const std::array<double, 3> tangential{relative[0] - normal_velocity * n[0],
                                         relative[1] - normal_velocity * n[1], relative[2]};
  const double limit =
      friction * std::max(mass * std::abs(normal_velocity) + pore_impulse, 0.0) + adhesion_impulse;
  ContactCorrection out;
  out.keep = coulomb_slip(std::hypot(tangential[0], tangential[1]), std::abs(tangential[2]), mass,
                          theta_mass, limit);
  const std::array<double, 3> kept{out.keep.plane, out.keep.plane, out.keep.theta};
  out.change = {-normal_velocity * n[0], -normal_velocity * n[1], 0.0};
  for (std::size_t d = 0; d < 3; ++d) {
    out.change[d] -= (1.0 - kept[d]) * tangential[d];
  }
  return out;
}

} // namespace mpile
