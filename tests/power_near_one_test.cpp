#include "engine/materials/power_near_one.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace mpile {
namespace {

// Against std::pow and std::exp in long double (64-bit mantissa: 1 + delta is exact there) over
// the whole range each series takes and across its edge. The series leave out below 2.5e-16
// (power_near_one.hpp) and round in about a dozen operations: 1e-15 relative holds them with room.
// Beyond the range std::pow(1 + delta, a) in double rounds 1 + delta first, which raised to a is
// up to a times 1.1e-16 (1.3e-15 at a = 12): the bound adds that. An error in one coefficient
// shows at 1e-9 or more (a wrong 1/5040 in the exponential is 1e-9 at y = 1/16).
TEST(PowerNearOne, MatchesPowAcrossTheSeriesRangeAndBeyond) {
  std::mt19937_64 random(20261202);
  std::uniform_real_distribution<double> delta(-2.0 * NEAR_ONE, 2.0 * NEAR_ONE);
  const double exponents[] = {0.1, 0.15, 0.285, 0.5, 1.05, 2.0, 5.5, 6.0, 12.0};
  for (const double a : exponents) {
    for (int k = 0; k < 20000; ++k) {
      const double d = delta(random);
      const double reference = static_cast<double>(
          std::pow(1.0L + static_cast<long double>(d), static_cast<long double>(a)));
      ASSERT_NEAR(power_near_one(d, a) / reference, 1.0, 1e-15 + a * 1.2e-16)
          << "delta " << d << " a " << a;
    }
  }
  EXPECT_EQ(power_near_one(0.0, 0.285), 1.0);
}

TEST(PowerNearOne, ExpNearZeroMatchesExpAcrossItsRange) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> y(-2.0 * NEAR_ZERO, 2.0 * NEAR_ZERO);
  for (int k = 0; k < 100000; ++k) {
    const double x = y(random);
    const double reference = static_cast<double>(std::exp(static_cast<long double>(x)));
    ASSERT_NEAR(exp_near_zero(x) / reference, 1.0, 1e-15) << "y " << x;
  }
}

} // namespace
} // namespace mpile
