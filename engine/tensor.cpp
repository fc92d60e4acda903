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

} // namespace mpile
