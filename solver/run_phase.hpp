#pragma once

// A run as the phase runner sees it (solver/phase_runner.hpp): its phases, the end criteria of
// each, the output schedule observers are called on, and the progress a checkpoint saves.

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mpile {

/// Ends a phase once a rigid body has gone down by `penetration` (m, its total downward
/// displacement) or, with settlement > 0, by `settlement` since the phase started (a load test),
/// and, with at_rest, once it has also come to rest (before the next blow).
struct PenetrationStop {
  std::string body;
  /// With a settlement, the depth the phase is expected to end at (the deepest earlier stop plus
  /// the settlement), for the travel check and run-time estimates.
  double penetration = 0.0;
  double settlement = 0.0;
  bool at_rest = false;
};

/// One phase: its duration, the latest it can last, and what may end it earlier.
struct RunPhase {
  std::string name;
  double duration = 0.0;
  /// Ends the phase at equilibrium (physics.md 9, solver/equilibrium.hpp) within this tolerance.
  std::optional<double> equilibrium_tolerance;
  std::optional<PenetrationStop> stop_at;
};

/// When the observers write: history rows, snapshots and checkpoints (times in s).
struct OutputSchedule {
  double history_interval = 0.0;  // 0: a row every step
  double snapshot_interval = 0.0; // 0: no periodic snapshots
  std::vector<double> snapshot_times;
  /// Penetrations of penetration_body at which to take a snapshot.
  std::vector<double> snapshot_penetrations;
  std::string penetration_body;
  double checkpoint_interval = 0.0; // 0: only when the run stops
};

/// Where a run stands beyond the solver: its phase, and the bookkeeping of its outputs. A
/// checkpoint saves it, so that a restarted run goes on exactly as an uninterrupted one.
struct RunProgress {
  std::size_t phase = 0;
  std::vector<double> phase_starts; // start time of each phase begun so far
  /// Per phase begun, the penetration of its stop_at body when it began, for a settlement stop
  /// (NaN for a phase without one).
  std::vector<double> phase_start_depths;
  std::size_t history_rows = 0;
  double next_history_time = 0.0;
  double next_snapshot_time = 0.0;
  std::size_t next_listed_snapshot = 0;
  double next_checkpoint_time = 0.0;
  std::vector<std::pair<double, std::string>> snapshots;
  // The largest relative energy residual of a history row past the run's start-up, and when.
  double peak_residual = 0.0;
  double peak_residual_time = 0.0;
};

/// How far a phase has come, in its own terms: its stop depth, else its end time.
struct PhaseGoal {
  std::string_view quantity = "t"; // "t", "penetration" or "settlement"
  double value = 0.0;              // now
  double target = 0.0;             // where the phase ends
  std::string_view unit = "s";
  double time = 0.0;     // simulated time now
  double end_time = 0.0; // the phase's end time, the latest it can end
  /// With an equilibrium criterion, on the steps it is checked: how far the state is from it, the
  /// larger of its two ratios over the tolerance (below 1 ends the phase); NaN on other steps.
  double equilibrium = std::numeric_limits<double>::quiet_NaN();
  bool ends_at_equilibrium = false; // the phase has an equilibrium criterion
};

} // namespace mpile
