// The run-time estimate from a pilot run, on pilot records whose rates are known exactly.
#include "app/run_estimate.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mpile {
namespace {

// Two phases like the monopile cases': a geostatic phase ending at equilibrium, then an
// installation stopping at 0.1 m of penetration, at the latest after 30 s.
CaseSpec two_phases() {
  CaseSpec spec;
  PhaseSpec geostatic;
  geostatic.name = "geostatic";
  geostatic.duration = 2.0;
  geostatic.equilibrium_tolerance = 0.01;
  PhaseSpec installation;
  installation.name = "installation";
  installation.duration = 30.0;
  installation.stop_at = PenetrationStop{"pile", 0.1, false};
  spec.phases = {geostatic, installation};
  return spec;
}

// A pilot that ran the geostatic phase to t = 0.01 s in 1 s of wall time, then the installation
// for 2 s of wall time at 100 s of wall per simulated second, the pile going down at 0.5 m/s.
PilotRecord pilot_in_installation() {
  PilotRecord pilot;
  for (int i = 0; i <= 10; ++i) {
    pilot.time.push_back(0.001 * i);
    pilot.phase.push_back(0.0);
    pilot.wall.push_back(0.1 * i);
    pilot.penetration["pile"].push_back(0.0);
  }
  for (int i = 1; i <= 20; ++i) {
    const double t = 0.01 + 0.001 * i;
    pilot.time.push_back(t);
    pilot.phase.push_back(1.0);
    pilot.wall.push_back(1.0 + 0.1 * i);
    pilot.penetration["pile"].push_back(0.5 * (t - 0.01));
  }
  return pilot;
}

TEST(RunEstimate, ThePhaseThePilotStoppedInIsExtrapolatedFromItsPenetrationRate) {
  const std::vector<PhaseEstimate> e = estimate_phases(two_phases(), pilot_in_installation());
  ASSERT_EQ(e.size(), 2u);
  // Geostatic: measured, 1 s. Installation: its rows run from 0.011 s (penetration 0.0005 m) to
  // 0.030 s (0.01 m): 0.5 m/s, so 0.09 m remain, 0.18 s of simulated time at 100 s per simulated
  // second, on top of the 2 s already spent: 20 s.
  EXPECT_DOUBLE_EQ(e[0].wall, 1.0);
  EXPECT_FALSE(e[0].bound);
  EXPECT_NEAR(e[1].wall, 2.0 + 0.18 * 100.0, 1e-9);
  // At constant speed the range is one number: no acceleration to extrapolate.
  EXPECT_NEAR(e[1].low, e[1].wall, 1e-6);
  EXPECT_FALSE(e[1].bound);
  EXPECT_NE(e[1].basis.find("penetration rate"), std::string::npos) << e[1].basis;
}

TEST(RunEstimate, APileThatGathersSpeedIsGivenARangeFromKeepingItToItsMeanSpeed) {
  PilotRecord pilot = pilot_in_installation();
  // The pile accelerates: p = 25 (t - 0.01)^2, 0.01 m at 0.03 s. The later half of the phase's
  // rows (from 0.021 s, the first row past the middle 0.0205 s) gives (0.01 - 0.003025) /
  // 0.009 = 0.775 m/s, its present speed; since the phase's first row (0.011 s) it averaged
  // (0.01 - 0.000025) / 0.019 = 0.525 m/s.
  for (std::size_t r = 11; r < pilot.time.size(); ++r) {
    const double s = pilot.time[r] - 0.01;
    pilot.penetration["pile"][r] = 25.0 * s * s;
  }
  const std::vector<PhaseEstimate> e = estimate_phases(two_phases(), pilot);
  const double mean = (0.01 - 25.0 * 0.001 * 0.001) / 0.019;
  // The upper end: the pile back at its mean speed, as a pile may slow again when the soil's grip
  // grows with depth (before, the estimate was the present speed's alone, 1.3 to 2 times off on
  // gdp_quick with short pilots, on either side).
  EXPECT_NEAR(e[1].wall, 2.0 + 0.09 / mean * 100.0, 1e-9);
  EXPECT_NE(e[1].basis.find("over the pilot's last 0.0095 s, 0.775 m/s to 0.1 m (0.525 m/s since "
                            "the phase began)"),
            std::string::npos)
      << e[1].basis;
  // The lower end keeps the acceleration the later half shows (the progress line's quadratic
  // fit): at a constant 50 m/s^2 it is exact, 0.1 m at s = sqrt(0.1 / 25).
  EXPECT_NEAR(e[1].low, 2.0 + (std::sqrt(0.1 / 25.0) - 0.02) * 100.0, 1e-6);
}

// The pile of two_phases() driven by blows every 4 ms (a pulse train).
CaseSpec driven_by_blows() {
  CaseSpec spec = two_phases();
  BodySpec pile;
  pile.name = "pile";
  pile.rigid = RigidSpec{};
  pile.rigid->drive[RIGID_Y] =
      RigidDrive{RigidDrive::Kind::force, TimeFunction::pulse_train(-1e5, 0.001, 0.004)};
  spec.bodies.push_back(pile);
  return spec;
}

TEST(RunEstimate, APeriodicDriveIsExtrapolatedOverWholePeriods) {
  // Blows every 4 ms: each moves the pile 0.002 m in its first millisecond, then it rests.
  PilotRecord pilot = pilot_in_installation();
  for (std::size_t r = 11; r < pilot.time.size(); ++r) {
    const double s = pilot.time[r] - 0.01;
    const double blows = std::floor(s / 0.004);
    pilot.penetration["pile"][r] = 0.002 * (blows + std::min((s - 0.004 * blows) / 0.001, 1.0));
  }
  // The phase's rows cover 0.019 s (from 0.011 s): the last two whole periods (8 ms, from
  // 0.022 s) went 0.004 m down, 0.5 m/s. (The later half alone, from 0.0205 s, would take
  // 0.0055 m in 0.0095 s.)
  const std::vector<PhaseEstimate> e = estimate_phases(driven_by_blows(), pilot);
  const double rate = (pilot.penetration["pile"].back() - pilot.penetration["pile"][22]) / 0.008;
  EXPECT_NEAR(rate, 0.5, 1e-12);
  EXPECT_NEAR(e[1].wall, 2.0 + (0.1 - pilot.penetration["pile"].back()) / rate * 100.0, 1e-9);
  EXPECT_NE(e[1].basis.find("over the pilot's last 0.008 s, 0.5 m/s"), std::string::npos)
      << e[1].basis;

  // A pilot that stopped within the first period cannot tell the rate: the duration bounds the
  // phase, and the message says how long a pilot needs (the phase began at 1.1 s of wall and ran
  // 2 ms in 0.2 s: 0.4 s per period, so 1.5 s; with a margin of a fifth, 1.8, rounded up).
  for (auto* series : {&pilot.time, &pilot.phase, &pilot.wall, &pilot.penetration["pile"]}) {
    series->resize(14);
  }
  // The blow's millisecond is over at all three rows: the pile has stopped.
  pilot.penetration["pile"][11] = pilot.penetration["pile"][12] = pilot.penetration["pile"][13];
  const std::vector<PhaseEstimate> short_pilot = estimate_phases(driven_by_blows(), pilot);
  EXPECT_TRUE(short_pilot[1].bound);
  EXPECT_NE(short_pilot[1].basis.find(
                "at most its duration (the pilot ran 0.002 s of its drive's period of 0.004 s: "
                "longer if the pile does not get there within this period; "
                "--pilot 2 or more covers one period)"),
            std::string::npos)
      << short_pilot[1].basis;
}

TEST(RunEstimate, APilotStillAtEquilibriumBoundsTheRunByTheDurations) {
  PilotRecord pilot = pilot_in_installation();
  // Only the geostatic rows: 100 s of wall per simulated second there too.
  for (auto* series : {&pilot.time, &pilot.phase, &pilot.wall, &pilot.penetration["pile"]}) {
    series->resize(11);
  }
  const std::vector<PhaseEstimate> e = estimate_phases(two_phases(), pilot);
  ASSERT_EQ(e.size(), 2u);
  // Equilibrium cannot be extrapolated: the rest of its 2 s, and the installation's 30 s.
  EXPECT_TRUE(e[0].bound);
  EXPECT_NEAR(e[0].wall, 1.0 + (2.0 - 0.01) * 100.0, 1e-9);
  EXPECT_TRUE(e[1].bound);
  EXPECT_NEAR(e[1].wall, 30.0 * 100.0, 1e-9);
}

TEST(RunEstimate, APilotThatRanTheWholeCaseIsTheMeasurement) {
  PilotRecord pilot = pilot_in_installation();
  pilot.complete = true;
  const std::vector<PhaseEstimate> e = estimate_phases(two_phases(), pilot);
  EXPECT_DOUBLE_EQ(e[0].wall + e[1].wall, 3.0);
  EXPECT_FALSE(e[1].bound);
}

} // namespace
} // namespace mpile
