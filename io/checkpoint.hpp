#pragma once

#include "engine/scene.hpp"
#include "io/case_spec.hpp"
#include "solver/explicit_solver.hpp"

#include <string>
#include <utility>
#include <vector>

namespace mpile {

/// Where a run stands beyond the solver: its phase, and the bookkeeping of its outputs.
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

struct Checkpoint {
  SolverState solver;
  RunProgress progress;
  /// The keys of the case that changed since the checkpoint was written (those a restart may
  /// change: outputs and end criteria).
  std::vector<std::string> changed_keys;
};

/// Writes the full state (every particle array, the solver state and the run's progress) to an
/// HDF5 file, through a temporary file renamed at the end so that a checkpoint is never half
/// written. The case text and program version are stored to refuse a mismatched restart.
void write_checkpoint(const std::string& path, const CaseSpec& spec, const Scene& scene,
                      const SolverState& solver, const RunProgress& progress);

/// Reads a checkpoint into a scene built from the same case. Throws CaseError when the checkpoint
/// belongs to another case or program version, or does not fit the scene.
Checkpoint read_checkpoint(const std::string& path, const CaseSpec& spec, Scene& scene);

} // namespace mpile
