#pragma once

// What `mpile run` attaches to the phase runner (solver/phase_runner.hpp): the history file, the
// VTK snapshots, the checkpoint and the progress line, each told when its output is due.

#include "app/progress_reporter.hpp"
#include "io/history_writer.hpp"
#include "io/vtk_writer.hpp"
#include "solver/phase_runner.hpp"

#include <functional>

namespace mpile {

/// A row per history time, and the start and end of each phase, in history.h5.
class HistoryObserver final : public RunObserver {
public:
  HistoryObserver(HistoryWriter& history, const ExplicitSolver& solver)
      : history_(history), solver_(solver) {}
  void phase_started(std::size_t p, const RunPhase& phase, double start) override {
    history_.phase_started(p, phase.name, start);
  }
  void row_due(std::size_t phase, const EnergyBalance& energy) override {
    history_.record(solver_, phase, energy);
  }
  void phase_ended(std::size_t phase, double end, const std::string& why) override {
    history_.phase_ended(phase, end, why);
  }

private:
  HistoryWriter& history_;
  const ExplicitSolver& solver_;
};

/// The particles (and grid) as .vtu files with their ParaView collections.
class SnapshotObserver final : public RunObserver {
public:
  SnapshotObserver(SnapshotWriter& snapshots, const Scene& scene)
      : snapshots_(snapshots), scene_(scene) {}
  void snapshot_due(double time) override { snapshots_.write(scene_, time); }

private:
  SnapshotWriter& snapshots_;
  const Scene& scene_;
};

/// The full state at each checkpoint time (the writing is the run command's: it knows the case).
class CheckpointObserver final : public RunObserver {
public:
  explicit CheckpointObserver(std::function<void()> save) : save_(std::move(save)) {}
  void checkpoint_due() override { save_(); }

private:
  std::function<void()> save_;
};

/// The progress line on the terminal, ended with each phase.
class ProgressObserver final : public RunObserver {
public:
  explicit ProgressObserver(ProgressReporter& reporter) : reporter_(reporter) {}
  void stepped(const RunPhase& phase, long steps, const PhaseGoal& goal) override {
    reporter_.update(phase.name, steps, goal);
  }
  void phase_ended(std::size_t, double, const std::string&) override { reporter_.finish(); }

private:
  ProgressReporter& reporter_;
};

} // namespace mpile
