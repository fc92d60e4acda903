#pragma once

// The loop of a run (physics.md 9-10): steps each phase to its end (duration, equilibrium or a
// rigid body's penetration or settlement), lands steps on the times outputs are due, guards the
// energy balance every few steps, and tells its observers when a history row, a snapshot or a
// checkpoint is due. `mpile run` wires the history, snapshot, checkpoint and progress writers to
// it; anything else that runs phases (tests, the benchmark, verification) uses the same path.

#include "solver/energy_balance.hpp"
#include "solver/equilibrium.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/run_log.hpp"
#include "solver/run_phase.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace mpile {

/// Told by the phase runner what happens; each does its part (a file, a progress line).
class RunObserver {
public:
  virtual ~RunObserver() = default;
  virtual void phase_started(std::size_t /*phase*/, const RunPhase& /*phase*/, double /*start*/) {}
  /// A history row is due, of the state after the last step; `energy` is its energy balance.
  virtual void row_due(std::size_t /*phase*/, const EnergyBalance& /*energy*/) {}
  /// A snapshot of the state at `time` is due.
  virtual void snapshot_due(double /*time*/) {}
  /// A checkpoint is due (the progress is up to date).
  virtual void checkpoint_due() {}
  /// After every step, the one that ends a phase too (a progress display).
  virtual void stepped(const RunPhase& /*phase*/, long /*steps*/, const PhaseGoal& /*goal*/) {}
  /// The phase ended at `end`, for the reason `why` ("after its duration", "at equilibrium ...").
  virtual void phase_ended(std::size_t /*phase*/, double /*end*/, const std::string& /*why*/) {}
};

/// A rigid body's penetration: its total downward displacement (m).
double penetration_of(const RigidBody& body);
const RigidBody& rigid_body_named(const Scene& scene, const std::string& name);

/// Records that phase p begins at `time`: its start and, for a settlement stop, its body's depth.
void begin_phase(RunProgress& progress, const std::vector<RunPhase>& phases, const Scene& scene,
                 std::size_t p, double time);

class PhaseRunner {
public:
  /// Sets up the next phase's scene and settings as it begins (boundaries, K0 stresses, solver
  /// settings): called with the phase's index and start time, after begin_phase.
  using PhaseSetUp = std::function<void(std::size_t phase, double start)>;
  /// Whether the run should stop now (a signal, a step or wall-time budget), given the steps
  /// taken since this runner was made.
  using StopRequest = std::function<bool(long steps)>;

  enum class Outcome { complete, interrupted };

  struct ResidualSummary {
    double final = 0.0;
    double peak = 0.0;
    double peak_time = 0.0;
  };

  PhaseRunner(ExplicitSolver& solver, std::vector<RunPhase> phases, OutputSchedule schedule,
              RunProgress& progress, RunLog& log);

  void add_observer(RunObserver& observer) { observers_.push_back(&observer); }

  /// A fresh run's first outputs (row and snapshot of the initial state) and output times.
  void start();
  /// Runs from progress.phase to the end of the last phase, or until stop() asks. Throws
  /// SimulationError when the run goes unstable, after the row of the step that stopped it.
  Outcome run(const PhaseSetUp& set_up, const StopRequest& stop);
  /// A snapshot of the state now, unless one was taken at this time (a run stopping).
  void snapshot_now();

  ResidualSummary residual_summary() const {
    return {final_residual_, progress_.peak_residual, progress_.peak_residual_time};
  }

private:
  EnergyBalance record_row();
  void check_energy_residual(const EnergyBalance& energy, bool recorded);
  void outputs_after_step();
  bool ends_phase(const RunPhase& phase, const PhaseGoal& now,
                  const std::optional<EquilibriumMeasure>& equilibrium, std::string& why);
  PhaseGoal goal(const RunPhase& phase, double phase_end) const;
  PhaseGoal goal_of(const RunPhase& phase, double phase_end) const;
  void take_snapshot(double time);
  bool skip_reached_depths();

  ExplicitSolver& solver_;
  std::vector<RunPhase> phases_;
  OutputSchedule schedule_;
  RunProgress& progress_;
  RunLog& log_;
  std::vector<RunObserver*> observers_;

  std::size_t next_depth_ = 0;
  double last_snapshot_time_;
  long recorded_step_ = -1;
  bool residual_warned_ = false;
  long over_limit_since_ = -1;
  double final_residual_ = 0.0;
};

} // namespace mpile
