#pragma once

#include "cases/case_spec.hpp"
#include "engine/scene.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/run_phase.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mpile {

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

/// The case a checkpoint was written with (its resolved text) and the index of the phase the run
/// was in; nullopt for a checkpoint of a format that stored only the case file's text.
struct CheckpointCase {
  std::string resolved;
  std::size_t phase = 0;
};
std::optional<CheckpointCase> checkpoint_case(const std::string& path);

/// Reads a checkpoint into a scene built from the same case. Throws CaseError when the checkpoint
/// belongs to another case or program version, or does not fit the scene.
Checkpoint read_checkpoint(const std::string& path, const CaseSpec& spec, Scene& scene);

} // namespace mpile
