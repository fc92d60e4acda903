#include "engine/time_function.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace mpile {
namespace {

// Composite Simpson integral of f.value over [0, t]: an independent check of primitive().
double simpson(const TimeFunction& f, double t, int intervals = 20000) {
  const double h = t / intervals;
  double sum = f.value(0.0) + f.value(t);
  for (int i = 1; i < intervals; ++i) {
    sum += (i % 2 ? 4.0 : 2.0) * f.value(i * h);
  }
  return sum * h / 3.0;
}

TEST(TimeFunction, PrimitivesMatchNumericalIntegration) {
  const TimeFunction functions[] = {
      TimeFunction::constant(2.5),
      TimeFunction::ramp(3.0, 0.4),
      TimeFunction::table({{0.1, 1.0}, {0.3, -2.0}, {0.5, 0.5}}),
      TimeFunction::harmonic(414.5e3, 60.0, 0.3),
      TimeFunction::harmonic(20e3, 23.0, 0.0, -8e3), // an axial vibrator on a static weight
      TimeFunction::pulse_train(750e3, 0.005, 0.02),
  };
  for (const TimeFunction& f : functions) {
    for (const double t : {0.013, 0.25, 0.77}) {
      const double reference = simpson(f, t);
      // Simpson with 20000 intervals is exact to ~1e-9 relative for these smooth pieces; kinks of
      // tables and pulses inside an interval limit it to ~1e-7 of the function's scale.
      EXPECT_NEAR(f.primitive(t), reference, 1e-6 * (1.0 + std::abs(reference))) << "t = " << t;
    }
  }
}

TEST(TimeFunction, ValuesOfEachKind) {
  EXPECT_DOUBLE_EQ(TimeFunction::ramp(2.0, 1.0).value(0.25), 0.5);
  EXPECT_DOUBLE_EQ(TimeFunction::ramp(2.0, 1.0).value(5.0), 2.0);
  const TimeFunction pulses = TimeFunction::pulse_train(750e3, 0.005, 0.85);
  EXPECT_NEAR(pulses.value(0.0025), 750e3, 1e-6);
  EXPECT_DOUBLE_EQ(pulses.value(0.1), 0.0);
  EXPECT_NEAR(pulses.value(0.85 + 0.0025), 750e3, 1e-6);
  // Impulse of one half-sine blow: 2 F t1 / pi.
  EXPECT_NEAR(pulses.primitive(0.5), 2.0 * 750e3 * 0.005 / std::numbers::pi, 1e-6);
  const TimeFunction torque = TimeFunction::harmonic(1.0, 60.0);
  EXPECT_NEAR(torque.value(1.0 / 240.0), 1.0, 1e-12);
  EXPECT_NEAR(torque.mean(0.0, 1.0 / 60.0), 0.0, 1e-12);
  // About a mean: a vibrator's force on a static weight has that weight as its mean over any
  // whole number of periods, and the weight plus the amplitude at a quarter period.
  const TimeFunction axial = TimeFunction::harmonic(20e3, 25.0, 0.0, -8e3);
  EXPECT_NEAR(axial.value(0.01), 12e3, 1e-9);
  EXPECT_NEAR(axial.mean(0.013, 0.013 + 3.0 / 25.0), -8e3, 1e-9);
  EXPECT_NEAR(axial.primitive(0.4), -8e3 * 0.4, 1e-9);
}

TEST(TimeFunction, RejectsMeaninglessParameters) {
  EXPECT_THROW(TimeFunction::ramp(1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(TimeFunction::table({{0.0, 1.0}, {0.0, 2.0}}), std::invalid_argument);
  EXPECT_THROW(TimeFunction::harmonic(1.0, -60.0), std::invalid_argument);
  EXPECT_THROW(TimeFunction::pulse_train(1.0, 0.9, 0.85), std::invalid_argument);
}

} // namespace
} // namespace mpile

namespace mpile {
namespace {

TEST(TimeFunction, StartingLaterShiftsValueAndIntegralAndIsZeroBefore) {
  const TimeFunction ramp = TimeFunction::ramp(2.0, 1.0);
  const TimeFunction later = ramp.starting_at(3.0);
  EXPECT_DOUBLE_EQ(later.value(2.9), 0.0);
  EXPECT_DOUBLE_EQ(later.value(3.5), ramp.value(0.5));
  EXPECT_DOUBLE_EQ(later.primitive(2.0), 0.0);
  EXPECT_DOUBLE_EQ(later.primitive(4.5), ramp.primitive(1.5));
  EXPECT_DOUBLE_EQ(TimeFunction::constant(3.0).value(-1.0), 0.0); // at rest before its start
  EXPECT_DOUBLE_EQ(TimeFunction::constant(3.0).mean(-0.5, 0.5), 1.5);
}

} // namespace
} // namespace mpile
