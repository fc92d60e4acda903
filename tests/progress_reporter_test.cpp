// The run's progress line: it speaks in the phase's own terms (a stop depth or the phase's end
// time), and its ETA is right from the first line: from the previous phase's cost of a step where
// the phase has just begun, from the trend of the equilibrium criterion where a phase ends on it,
// from the speed and acceleration of a pile that is still gathering speed (a range then), and
// marked as a bound ("ETA <= ...") where nothing but the phase's end time is known. The ETA used
// to be the distance left over the average rate since the phase began: 2 000 s for an equilibrium
// phase that ended within a second, 4.6 times the truth for an accelerating pile at 5 s, and "-"
// at a phase's start. The clocks here are the tests'.
#include "app/progress_estimate.hpp"
#include "app/progress_reporter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>
#include <string>

namespace mpile {
namespace {

/// Drives a reporter (off a terminal: a line every 5 s of wall time) through steps of `wall` s
/// each; the goal at each step comes from `at`.
void drive(ProgressReporter& reporter, double& clock, long first, long last, double wall,
           const std::string& phase, const std::function<PhaseGoal(long)>& at) {
  for (long step = first; step <= last; ++step) {
    clock = static_cast<double>(step) * wall;
    reporter.update(phase, step, at(step));
  }
}

// A pile driven from rest at 20 m/s^2 until it moves at 1 m/s, to a stop at 0.1 m (reached at
// 0.125 s); 250 s of wall time per simulated second (4e-5 s steps of 0.01 s).
double pile_depth(double tau) {
  return tau < 0.05 ? 10.0 * tau * tau : 0.025 + (tau - 0.05);
}

PhaseGoal pile_goal(long step) {
  const double tau = 4e-5 * static_cast<double>(step);
  return {"penetration", pile_depth(tau), 0.1, "m", tau, 30.0};
}

TEST(ProgressReporter, AnAcceleratingPileGetsARangeThatHoldsTheTruth) {
  std::ostringstream out;
  double clock = 0.0;
  ProgressReporter reporter(out, false, [&] { return clock; });
  drive(reporter, clock, 0, 500, 0.01, "installation", pile_goal);
  // At 5 s (0.02 s simulated, 4 mm down) the pile has 26.25 s of wall time to go. At its speed now
  // (0.4 m/s) it would take 60 s, accelerating as now 20 s. The average rate since the phase
  // began said 120 s.
  EXPECT_EQ(out.str(),
            "penetration = 0.004 of 0.1 m  [installation]  100 steps/s  ETA 20 to 60 s\n");
  out.str("");
  // At 25 s it has moved at 1 m/s for 0.05 s: 0.025 m left, 6.25 s.
  drive(reporter, clock, 501, 2500, 0.01, "installation", pile_goal);
  const std::string lines = out.str();
  EXPECT_NE(lines.find("penetration = 0.075 of 0.1 m  [installation]  100 steps/s  ETA 6 s\n"),
            std::string::npos)
      << lines;
}

TEST(ProgressReporter, AnEquilibriumPhaseFollowsItsCriterionsTrend) {
  // The case: "t = 0.00095 of 2 s ... ETA 464 s" for a phase that ended in a second. Here
  // the criterion's ratio falls as 100 exp(-steps / 400), checked every 20 steps: it reaches 1 at
  // step 1842, 4.2 s after the line at step 1000 (0.005 s of wall time per step).
  std::ostringstream out;
  double clock = 0.0;
  ProgressReporter reporter(out, false, [&] { return clock; });
  drive(reporter, clock, 1, 1000, 0.005, "geostatic", [](long step) {
    const double t = 1e-5 * static_cast<double>(step);
    PhaseGoal goal{"t", t, 2.0, "s", t, 2.0};
    goal.ends_at_equilibrium = true;
    if (step % 20 == 0) {
      goal.equilibrium = 100.0 * std::exp(-static_cast<double>(step) / 400.0);
    }
    return goal;
  });
  // The line shows how far the state is from the criterion (its last check, at step 1000:
  // 100 exp(-2.5) = 8.21), not the time against the phase's limit.
  EXPECT_EQ(out.str(),
            "out of balance = 8.21 x tolerance (1 ends the phase)  [geostatic]  200 steps/s  ETA "
            "4 s\n");
}

TEST(ProgressReporter, APhaseThatMayEndEarlyShowsItsEndOnlyAsABound) {
  // An equilibrium phase before its criterion has a trend, and a penetration phase whose pile has
  // not moved yet: the phase's end time at the measured rate is all that is known, and it is a
  // bound (it used to be shown as the ETA, or "-").
  std::ostringstream out;
  double clock = 0.0;
  ProgressReporter reporter(out, false, [&] { return clock; });
  drive(reporter, clock, 1, 1000, 0.005, "geostatic", [](long step) {
    const double t = 1e-5 * static_cast<double>(step);
    PhaseGoal goal{"t", t, 2.0, "s", t, 2.0};
    goal.ends_at_equilibrium = true;
    return goal;
  });
  EXPECT_EQ(out.str(), "t = 0.01 of 2 s  [geostatic]  200 steps/s  ETA <= 995 s\n");
  // The next phase's first line, one step into it: the previous phase's 0.005 s per step at its
  // own step of 1e-5 s, 30 s to its end: at most 15 000 s.
  out.str("");
  clock = 10.0;
  reporter.update("installation", 1001, {"penetration", 0.0, 0.1, "m", 0.01001, 30.01});
  EXPECT_EQ(out.str(), "penetration = 0 of 0.1 m  [installation]  0 steps/s  ETA <= 15000 s\n");
}

TEST(ProgressReporter, ATimedPhaseIsItsDurationAtTheMeasuredRate) {
  // 1.5 s of simulated time left at 0.25 s per wall second: 6 s, no bound about it.
  std::ostringstream out;
  double clock = 0.0;
  ProgressReporter reporter(out, false, [&] { return clock; });
  drive(reporter, clock, 0, 600, 0.01, "hold", [](long step) {
    const double t = 1.0 + 0.0025 * static_cast<double>(step);
    return PhaseGoal{"t", t, 3.0, "s", t, 3.0};
  });
  EXPECT_EQ(out.str(), "t = 2.25 of 3 s  [hold]  100 steps/s  ETA 3 s\n");
}

TEST(ProgressEstimator, NothingKnownBeforeTheFirstStepIsMeasured) {
  ProgressEstimator estimator;
  EXPECT_EQ(format_eta(estimator.estimate()), "ETA -");
  estimator.observe("installation", 0, {"penetration", 0.0, 0.1, "m", 0.0, 30.0}, 0.0);
  EXPECT_EQ(format_eta(estimator.estimate()), "ETA -");
}

TEST(ProgressEstimator, ALongPhaseKeepsABoundedNumberOfSamplesAndStaysExact) {
  // 200 000 steps of a pile at a constant 0.1 m/s: 1 m left at the end is 10 s simulated, 10 s of
  // wall time at one wall second per simulated second.
  ProgressEstimator estimator;
  for (long step = 0; step <= 200000; ++step) {
    const double t = 1e-4 * static_cast<double>(step);
    estimator.observe("installation", step, {"penetration", 0.1 * t, 3.0, "m", t, 100.0}, t);
  }
  const EtaEstimate eta = estimator.estimate();
  ASSERT_TRUE(eta.known);
  EXPECT_FALSE(eta.bound);
  EXPECT_NEAR(eta.low, 10.0, 1e-6);
  EXPECT_NEAR(eta.high, 10.0, 1e-6);
}

TEST(ProgressEstimator, FormatsAnEstimateARangeAndABound) {
  EXPECT_EQ(format_eta({true, false, 12.0, 12.4}), "ETA 12 s");
  EXPECT_EQ(format_eta({true, false, 21.0, 158.0}), "ETA 21 to 158 s");
  EXPECT_EQ(format_eta({true, true, 464.0, 464.0}), "ETA <= 464 s");
}

} // namespace
} // namespace mpile
