#include "engine/coulomb_slip.hpp"

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

} // namespace mpile
