#pragma once

// (1 + delta)^a for a small delta by short series instead of std::pow. The hypoplastic rate's
// second evaluation in a substep sits at a state a small step from the first, so each of its
// powers (Bauer's (3 p / h_s)^n, f_e, f_d, rho^chi) is the first one's times a power of a number
// near one; the series cost a tenth of a pow there (docs/hypoplasticity.md, "Integration").

#include <cmath>

namespace mpile {

/// The largest |delta| power_near_one's series takes: log(1 + delta) to delta^7 then leaves out
/// below 2.5e-16 of it.
inline constexpr double NEAR_ONE = 1.0 / 128.0;

/// The largest |y| exp_near_zero's series takes: to y^8 / 8! it then leaves out below 5e-17.
inline constexpr double NEAR_ZERO = 1.0 / 16.0;

/// exp(y): the series where |y| <= NEAR_ZERO, std::exp otherwise.
inline double exp_near_zero(double y) {
  if (!(std::abs(y) <= NEAR_ZERO)) {
    return std::exp(y);
  }
  return 1.0 +
         y * (1.0 +
              y * (1.0 / 2.0 +
                   y * (1.0 / 6.0 +
                        y * (1.0 / 24.0 +
                             y * (1.0 / 120.0 +
                                  y * (1.0 / 720.0 + y * (1.0 / 5040.0 + y * (1.0 / 40320.0))))))));
}

/// log(1 + delta): the series to delta^7 where |delta| <= NEAR_ONE, std::log1p otherwise.
inline double log_near_one(double delta) {
  if (!(std::abs(delta) <= NEAR_ONE)) {
    return std::log1p(delta);
  }
  const double d = delta;
  return d * (1.0 +
              d * (-1.0 / 2.0 +
                   d * (1.0 / 3.0 +
                        d * (-1.0 / 4.0 + d * (1.0 / 5.0 + d * (-1.0 / 6.0 + d * (1.0 / 7.0)))))));
}

/// (1 + delta)^a: exp(a log(1 + delta)) by the series where |delta| <= NEAR_ONE, std::pow
/// otherwise. Relative error within a few units of rounding either way
/// (tests/power_near_one_test.cpp).
inline double power_near_one(double delta, double a) {
  if (!(std::abs(delta) <= NEAR_ONE)) {
    return std::pow(1.0 + delta, a);
  }
  return exp_near_zero(a * log_near_one(delta));
}

} // namespace mpile
