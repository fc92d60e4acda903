// The phase runner (solver/phase_runner.hpp), the one loop every run goes through: steps land
// exactly on snapshot times and phase ends, observers hear of every output in time order, a run
// stopped and continued by a new runner from its progress gives the same events and the same
// state bit for bit, and the end criteria (equilibrium, a penetration) end a phase where they say.
#include "case_run.hpp"
#include "solver/equilibrium.hpp"
#include "solver/phase_runner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

namespace mpile {
namespace {

struct Event {
  std::string kind;
  double time;
  bool operator==(const Event&) const = default;
};

void PrintTo(const Event& e, std::ostream* os) {
  *os << e.kind << " at " << e.time;
}

/// The events without the repeated announcement of the phase a continued run goes on in (a new
/// runner announces its phase, as a restarted run announces it to its history).
std::vector<Event> without_repeated_starts(const std::vector<Event>& events) {
  std::vector<Event> kept;
  for (const Event& e : events) {
    if (e.kind.starts_with("start") && std::find(kept.begin(), kept.end(), e) != kept.end()) {
      continue;
    }
    kept.push_back(e);
  }
  return kept;
}

/// Writes down what it is told, with the solver's time.
class Recorder final : public RunObserver {
public:
  explicit Recorder(const ExplicitSolver& solver) : solver_(solver) {}
  void phase_started(std::size_t, const RunPhase& phase, double start) override {
    events.push_back({"start " + phase.name, start});
  }
  void row_due(std::size_t, const EnergyBalance&) override { events.push_back({"row", now()}); }
  void snapshot_due(double time) override { events.push_back({"snapshot", time}); }
  void checkpoint_due() override { events.push_back({"checkpoint", now()}); }
  void phase_ended(std::size_t, double end, const std::string&) override {
    events.push_back({"end", end});
  }
  std::vector<double> times_of(const std::string& kind) const {
    std::vector<double> times;
    for (const Event& e : events) {
      if (e.kind == kind) {
        times.push_back(e.time);
      }
    }
    return times;
  }
  std::vector<Event> events;

private:
  double now() const { return solver_.time(); }
  const ExplicitSolver& solver_;
};

// The V1 bar (period 10 s, a step of about 0.08 s) in two phases of 7.3 and 9.1 s.
const std::vector<RunPhase> bar_phases{{"first", 7.3, std::nullopt, std::nullopt},
                                       {"second", 9.1, std::nullopt, std::nullopt}};

OutputSchedule bar_schedule() {
  OutputSchedule schedule;
  schedule.history_interval = 1.0;
  schedule.snapshot_interval = 2.5;
  schedule.snapshot_times = {4.05, 1.7}; // unsorted on purpose: the runner sorts them
  schedule.checkpoint_interval = 5.0;
  return schedule;
}

/// Runs the bar's two phases; with stop_after > 0 the first runner stops after that many steps
/// and a second one, made from the same progress, goes on to the end.
Recorder run_bar(CaseRun& run, long stop_after) {
  RunProgress progress;
  begin_phase(progress, bar_phases, *run.scene, 0, 0.0);
  Recorder recorder(*run.solver);
  auto never = [](long) { return false; };
  auto nothing_to_set_up = [](std::size_t, double) {};
  {
    PhaseRunner runner(*run.solver, bar_phases, bar_schedule(), progress, run.log);
    runner.add_observer(recorder);
    runner.start();
    const auto outcome = runner.run(
        nothing_to_set_up, [&](long steps) { return stop_after > 0 && steps >= stop_after; });
    if (stop_after == 0) {
      EXPECT_EQ(outcome, PhaseRunner::Outcome::complete);
      return recorder;
    }
    EXPECT_EQ(outcome, PhaseRunner::Outcome::interrupted);
  }
  PhaseRunner runner(*run.solver, bar_phases, bar_schedule(), progress, run.log);
  runner.add_observer(recorder);
  EXPECT_EQ(runner.run(nothing_to_set_up, never), PhaseRunner::Outcome::complete);
  return recorder;
}

TEST(PhaseRunner, StepsLandOnSnapshotTimesAndPhaseEndsAndObserversHearEachOutput) {
  CaseRun run(read_text(source / "cases/verification/vibrating_bar.toml"));
  const Recorder recorder = run_bar(run, 0);
  // Landings are sums of steps that each end on the target: exact to round-off of the sum.
  const double tol = 1e-12 * 16.4;
  const std::vector<double> snapshots{0.0, 1.7, 2.5, 4.05, 5.0, 7.3, 7.5, 10.0, 12.5, 15.0, 16.4};
  const std::vector<double> got = recorder.times_of("snapshot");
  ASSERT_EQ(got.size(), snapshots.size());
  for (std::size_t k = 0; k < got.size(); ++k) {
    EXPECT_NEAR(got[k], snapshots[k], tol) << k;
  }
  const std::vector<double> ends = recorder.times_of("end");
  ASSERT_EQ(ends.size(), 2u);
  EXPECT_NEAR(ends[0], 7.3, tol);
  EXPECT_NEAR(ends[1], 16.4, tol);
  // Checkpoints at 5, 10 and 15 s: snapshot landings, so exact.
  const std::vector<double> checkpoints = recorder.times_of("checkpoint");
  ASSERT_EQ(checkpoints.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(checkpoints[k], 5.0 * static_cast<double>(k + 1), tol);
  }
  // A row at the start, at the first step at or past each whole second (rows do not shorten
  // steps), and at each phase's end; no more.
  const std::vector<double> rows = recorder.times_of("row");
  const double dt = run.solver->stable_time_step();
  std::size_t k = 0;
  EXPECT_EQ(rows.at(k++), 0.0);
  for (int second = 1; second <= 16; ++second) {
    if (second == 8) {
      EXPECT_NEAR(rows.at(k++), 7.3, tol); // the first phase's end
    }
    EXPECT_GE(rows.at(k), second - tol);
    EXPECT_LT(rows.at(k++), second + dt);
  }
  EXPECT_NEAR(rows.at(k++), 16.4, tol);
  EXPECT_EQ(k, rows.size());
  // Time order, phase by phase.
  for (std::size_t e = 1; e < recorder.events.size(); ++e) {
    EXPECT_LE(recorder.events[e - 1].time, recorder.events[e].time) << e;
  }
  EXPECT_EQ(recorder.events.front(), (Event{"row", 0.0}));
}

TEST(PhaseRunner, AStoppedRunContinuedByANewRunnerIsTheUninterruptedRun) {
  CaseRun whole(read_text(source / "cases/verification/vibrating_bar.toml"));
  const Recorder uninterrupted = run_bar(whole, 0);
  // 95 steps: inside the first phase; 110: in the second (the first ends near step 92).
  for (const long stop_after : {37L, 95L, 110L}) {
    CaseRun resumed(read_text(source / "cases/verification/vibrating_bar.toml"));
    const Recorder continued = run_bar(resumed, stop_after);
    EXPECT_EQ(without_repeated_starts(continued.events), uninterrupted.events) << stop_after;
    EXPECT_EQ(resumed.solver->step_count(), whole.solver->step_count());
    EXPECT_EQ(resumed.scene->particles.y, whole.scene->particles.y) << stop_after;
    EXPECT_EQ(resumed.scene->particles.v_y, whole.scene->particles.v_y) << stop_after;
  }
}

// A run continued under a case whose snapshot and checkpoint intervals are now 0 ("first and
// last only", "only when stopped"): what its checkpoint had scheduled is not due at every step
// (it was: a continued resolved-wall GDP run spent its time writing a checkpoint per step), and
// an interval newly set counts from the time the run goes on at.
TEST(PhaseRunner, ARunContinuedWithChangedIntervalsFollowsTheNewOnes) {
  CaseRun run(read_text(source / "cases/verification/vibrating_bar.toml"));
  RunProgress progress;
  begin_phase(progress, bar_phases, *run.scene, 0, 0.0);
  auto nothing_to_set_up = [](std::size_t, double) {};
  {
    PhaseRunner first(*run.solver, bar_phases, bar_schedule(), progress, run.log);
    first.start();
    ASSERT_EQ(first.run(nothing_to_set_up, [](long steps) { return steps >= 37; }),
              PhaseRunner::Outcome::interrupted);
  }
  const double stopped_at = run.solver->time();
  ASSERT_LT(stopped_at, progress.next_checkpoint_time); // one was scheduled ahead
  OutputSchedule quiet = bar_schedule();
  quiet.snapshot_interval = 0.0;
  quiet.snapshot_times.clear();
  quiet.checkpoint_interval = 0.0;
  Recorder recorder(*run.solver);
  {
    PhaseRunner second(*run.solver, bar_phases, quiet, progress, run.log);
    second.add_observer(recorder);
    ASSERT_EQ(second.run(nothing_to_set_up, [](long) { return false; }),
              PhaseRunner::Outcome::complete);
  }
  EXPECT_TRUE(recorder.times_of("checkpoint").empty());
  // Only the states the two phases end in (the runner keeps each phase's end).
  EXPECT_EQ(recorder.times_of("snapshot"), recorder.times_of("end"));
  EXPECT_EQ(recorder.times_of("snapshot").size(), 2u);

  // A checkpoint interval set on continuing: due at its multiples from where the run goes on.
  CaseRun again(read_text(source / "cases/verification/vibrating_bar.toml"));
  RunProgress restored;
  begin_phase(restored, bar_phases, *again.scene, 0, 0.0);
  OutputSchedule none = bar_schedule();
  none.checkpoint_interval = 0.0;
  {
    PhaseRunner first(*again.solver, bar_phases, none, restored, again.log);
    first.start();
    ASSERT_EQ(first.run(nothing_to_set_up, [](long steps) { return steps >= 37; }),
              PhaseRunner::Outcome::interrupted);
  }
  const double continued_at = again.solver->time();
  Recorder every_three(*again.solver);
  OutputSchedule three = bar_schedule();
  three.checkpoint_interval = 3.0;
  PhaseRunner second(*again.solver, bar_phases, three, restored, again.log);
  second.add_observer(every_three);
  ASSERT_EQ(second.run(nothing_to_set_up, [](long) { return false; }),
            PhaseRunner::Outcome::complete);
  // Due on the first step at or past each multiple of 3 s after the time the run went on at (a
  // step is about 0.08 s; none of the bar's 16.4 s is skipped).
  const std::vector<double> checkpoints = every_three.times_of("checkpoint");
  double due = 3.0 * (std::floor(continued_at / 3.0) + 1.0);
  ASSERT_EQ(checkpoints.size(), static_cast<std::size_t>(std::floor(16.4 / 3.0)) -
                                    static_cast<std::size_t>(std::floor(continued_at / 3.0)));
  for (const double t : checkpoints) {
    EXPECT_GE(t, due - 1e-9);
    EXPECT_LT(t, due + 0.1);
    due += 3.0;
  }
}

// Intervals shorter than a step (1e-3 s against the bar's 0.08 s) or below the rounding of the
// time itself (1e-300 s): a row and a checkpoint at every step, as an interval of 0 gives rows.
// At 1e-300 s the schedule was kept by adding the interval until it passed t, which never
// happened: the run spun in its first step.
TEST(PhaseRunner, IntervalsShorterThanAStepGiveAnOutputEveryStepAndEnd) {
  for (const double interval : {1e-3, 1e-300}) {
    CaseRun run(read_text(source / "cases/verification/vibrating_bar.toml"));
    RunProgress progress;
    begin_phase(progress, bar_phases, *run.scene, 0, 0.0);
    OutputSchedule every_step = bar_schedule();
    every_step.history_interval = interval;
    every_step.checkpoint_interval = interval;
    Recorder recorder(*run.solver);
    PhaseRunner runner(*run.solver, bar_phases, every_step, progress, run.log);
    runner.add_observer(recorder);
    runner.start();
    ASSERT_EQ(runner.run([](std::size_t, double) {}, [](long) { return false; }),
              PhaseRunner::Outcome::complete);
    const auto steps = static_cast<std::size_t>(run.solver->step_count());
    // A row at the start and one after each step; a phase's end adds none (its step's row is it).
    EXPECT_EQ(recorder.times_of("row").size(), steps + 1) << interval;
    EXPECT_EQ(recorder.times_of("checkpoint").size(), steps) << interval;
    EXPECT_NEAR(run.solver->time(), 16.4, 1e-12 * 16.4) << interval;
  }
}

TEST(PhaseRunner, APhaseEndsAtEquilibriumOnTheCheckStepWhereTheMeasurePasses) {
  // The damped self-weight column: equilibrium within 1e-5 long before its 4 s.
  CaseRun run(read_text(source / "cases/verification/self_weight_column.toml"));
  const double tolerance = *run.spec.phases[0].equilibrium_tolerance;
  const std::vector<RunPhase> phases{{"settle", 4.0, tolerance, std::nullopt}};
  RunProgress progress;
  begin_phase(progress, phases, *run.scene, 0, 0.0);
  PhaseRunner runner(*run.solver, phases, OutputSchedule{}, progress, run.log);
  Recorder recorder(*run.solver);
  runner.add_observer(recorder);
  std::string why;
  class Why final : public RunObserver {
  public:
    explicit Why(std::string& why) : why_(why) {}
    void phase_ended(std::size_t, double, const std::string& why) override { why_ = why; }

  private:
    std::string& why_;
  } reason(why);
  runner.add_observer(reason);
  runner.start();
  runner.run([](std::size_t, double) {}, [](long) { return false; });
  EXPECT_LT(run.solver->time(), 4.0);
  EXPECT_EQ(run.solver->step_count() % 20, 0); // checked every 20 steps
  const EquilibriumMeasure measure = measure_equilibrium(*run.solver, tolerance);
  EXPECT_TRUE(measure.reached);
  EXPECT_LT(measure.force_ratio, tolerance);
  EXPECT_LE(measure.kinetic_ratio, tolerance);
  EXPECT_EQ(why.rfind("at equilibrium (out-of-balance force ratio ", 0), 0u) << why;
}

TEST(PhaseRunner, APenetrationStopEndsThePhaseOnTheFirstStepPastTheDepth) {
  // The block falls at 0.5 m/s: 0.05 m of penetration after 0.1 s, well before the 1 s duration.
  const std::string text = std::string(block_above_soil) + R"(
[solver]
courant_number = 0.5
[[phases]]
name = "push"
duration = 1.0
)";
  CaseRun run(text);
  PenetrationStop stop;
  stop.body = "block";
  stop.penetration = 0.05;
  const std::vector<RunPhase> phases{{"push", 1.0, std::nullopt, stop}};
  RunProgress progress;
  begin_phase(progress, phases, *run.scene, 0, 0.0);
  PhaseRunner runner(*run.solver, phases, OutputSchedule{}, progress, run.log);
  runner.start();
  runner.run([](std::size_t, double) {}, [](long) { return false; });
  const double depth = penetration_of(rigid_body_named(*run.scene, "block"));
  const double dt = run.solver->last_time_step();
  EXPECT_GE(depth, 0.05);
  EXPECT_LT(depth - 0.5 * dt, 0.05); // the step before was short of it
}

} // namespace
} // namespace mpile
