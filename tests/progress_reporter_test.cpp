// The run's progress line: it speaks in the phase's own terms (a stop depth or the phase's end
// time) and its ETA comes from the rate at which that quantity has moved since the phase began.
// Before, the ETA counted simulated time to the end of the last phase, so a phase that stops at a
// penetration showed hours for a run of minutes.
#include "app/progress_reporter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace mpile {
namespace {

TEST(ProgressReporter, EtaOfAPenetrationPhaseFollowsThePenetrationRate) {
  // 0.063 m of a 0.6 m stop in 40 s of wall time: 0.537 m left at 1.575 mm/s is 340.95 s, well
  // before simulated time would reach the phase's 32 s duration (9 806 s at 0.13 s per 40 s).
  const PhaseGoal start{"penetration", 0.0, 0.6, "m", 0.07, 32.07};
  const PhaseGoal now{"penetration", 0.063, 0.6, "m", 0.2, 32.07};
  EXPECT_NEAR(ProgressReporter::eta(start, now, 40.0), 0.537 / (0.063 / 40.0), 1e-9);
}

TEST(ProgressReporter, EtaIsBoundedByThePhasesEndTime) {
  // A pile that barely moves: its depth would take 4e5 s, but the phase ends at its duration,
  // which simulated time reaches in (1.0 - 0.5) / (0.5 / 10) = 10 s.
  const PhaseGoal start{"penetration", 0.0, 0.6, "m", 0.0, 1.0};
  const PhaseGoal now{"penetration", 1e-5, 0.6, "m", 0.5, 1.0};
  EXPECT_NEAR(ProgressReporter::eta(start, now, 10.0), 10.0, 1e-12);
}

TEST(ProgressReporter, EtaOfATimedPhaseAndOfAPhaseThatHasNotMoved) {
  const PhaseGoal start{"t", 1.0, 3.0, "s", 1.0, 3.0};
  const PhaseGoal now{"t", 1.5, 3.0, "s", 1.5, 3.0};
  EXPECT_NEAR(ProgressReporter::eta(start, now, 2.0), 6.0, 1e-12); // 1.5 s left at 0.25 s/s
  EXPECT_TRUE(std::isinf(ProgressReporter::eta(start, start, 2.0)));
}

TEST(ProgressReporter, LineNamesThePhasesGoalAndItsEta) {
  // Off a terminal, a line every 5 s of wall time; the clock is the test's.
  std::ostringstream out;
  double clock = 0.0;
  ProgressReporter reporter(out, false, [&] { return clock; });
  reporter.update("installation", 1000, {"penetration", 0.0, 0.6, "m", 0.07, 32.07});
  clock = 4.0;
  reporter.update("installation", 1400, {"penetration", 0.004, 0.6, "m", 0.08, 32.07});
  EXPECT_EQ(out.str(), ""); // not yet 5 s
  clock = 6.0;
  reporter.update("installation", 1600, {"penetration", 0.006, 0.6, "m", 0.09, 32.07});
  // 600 steps in 6 s; 0.594 m left at 1 mm/s.
  EXPECT_EQ(out.str(), "penetration = 0.006 of 0.6 m  [installation]  100 steps/s  ETA 594 s\n");
  // A new phase restarts the rates: its first line waits for motion to measure.
  out.str("");
  clock = 12.0;
  reporter.update("hold", 1700, {"t", 0.09, 0.5, "s", 0.09, 0.5});
  EXPECT_EQ(out.str(), "t = 0.09 of 0.5 s  [hold]  0 steps/s  ETA -\n");
}

} // namespace
} // namespace mpile
