#include "app/run_command.hpp"

#include "app/progress_reporter.hpp"
#include "app/run_continuation.hpp"
#include "app/run_observers.hpp"
#include "io/case_builder.hpp"
#include "io/case_error.hpp"
#include "io/case_phases.hpp"
#include "io/case_warnings.hpp"
#include "io/checkpoint.hpp"
#include "io/history_writer.hpp"
#include "io/monitor_points.hpp"
#include "io/output_directory.hpp"
#include "io/plausibility.hpp"
#include "io/reserve_space.hpp"
#include "io/vtk_writer.hpp"
#include "solver/phase_runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>

namespace mpile {

namespace {

volatile std::sig_atomic_t stop_requested = 0;

extern "C" void request_stop(int) {
  stop_requested = 1;
}

/// SIGINT and SIGTERM ask the run to stop at the end of the current step.
class StopOnSignals {
public:
  StopOnSignals() {
    stop_requested = 0;
    previous_interrupt_ = std::signal(SIGINT, request_stop);
    previous_terminate_ = std::signal(SIGTERM, request_stop);
  }
  ~StopOnSignals() {
    std::signal(SIGINT, previous_interrupt_);
    std::signal(SIGTERM, previous_terminate_);
  }
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

private:
  void (*previous_interrupt_)(int) = SIG_DFL;
  void (*previous_terminate_)(int) = SIG_DFL;
};

std::string output_directory(const RunOptions& options, const CaseSpec& spec) {
  if (!options.output_directory.empty()) {
    return options.output_directory;
  }
  if (!spec.output.directory.empty()) {
    return spec.output.directory;
  }
  return "out/" + std::filesystem::path(spec.file).stem().string();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

int refuse_case(std::ostream& err, const std::string& case_path) {
  try {
    throw;
  } catch (const CaseError& e) {
    err << "mpile: " << e.what() << '\n';
  } catch (const std::bad_alloc&) {
    err << "mpile: " << case_path
        << ": out of memory while building the case: it needs more than this process may use\n";
  } catch (const std::exception& e) {
    err << "mpile: " << case_path << ": " << e.what() << '\n';
  }
  return exit_bad_input;
}

int run_case(const RunOptions& options, std::ostream& out, std::ostream& err) {
  // First of all, so that a SIGINT or SIGTERM while the case is read and built (seconds for a
  // large one) stops the run cleanly instead of killing it.
  StopOnSignals signals;
  const auto wall_start = std::chrono::steady_clock::now();
  CaseSpec spec;
  std::unique_ptr<Scene> scene;
  Checkpoint restored;
  std::string restart = options.restart;
  std::string continuation_reason;
  try {
    spec = read_case_file(options.case_path, options.overrides);
    if (options.continue_run && restart.empty()) {
      const Continuation c = find_continuation(output_directory(options, spec), spec.resolved);
      if (c.complete) {
        out << "mpile: " << c.reason << "; nothing to continue\n";
        return exit_success;
      }
      restart = c.checkpoint;
      continuation_reason = c.reason;
    }
    scene = build_scene(spec);
    if (restart.empty()) {
      for (const MonitorSpec& monitor : spec.output.monitors) {
        monitored_particle(monitor, *scene); // refused here, before anything is written
      }
    }
    if (!restart.empty()) {
      restored = read_checkpoint(restart, spec, *scene);
      if (restored.progress.phase >= spec.phases.size()) {
        // A complete run goes on only when its last phase may now end later.
        const std::string last = "phases." + std::to_string(spec.phases.size() - 1) + ".";
        if (std::none_of(restored.changed_keys.begin(), restored.changed_keys.end(),
                         [&](const std::string& key) { return key.starts_with(last); })) {
          throw CaseError(restart +
                          ": the run in this checkpoint is complete; nothing to continue (to "
                          "extend it, change the last phase's duration or stop_at, or add a "
                          "phase)");
        }
        restored.progress.phase = spec.phases.size() - 1;
      }
    }
  } catch (const std::exception&) {
    return refuse_case(err, options.case_path);
  }
  const bool restarting = !restart.empty();
  // Before anything is written: with --strict a likely slip of units refuses the run.
  print_case_warnings(err, spec.warnings, options.strict);
  if (options.strict && refused_when_strict(spec.warnings)) {
    return exit_bad_input;
  }

  RunLog log(&out);
  RunProgress progress = restarting ? restored.progress : RunProgress{};
  const CasePhases phases(spec, *scene);
  std::unique_ptr<ExplicitSolver> solver;
  try {
    solver =
        restarting ? phases.resume(progress, log, restored.solver) : phases.start(progress, log);
    if (!restarting) {
      refuse_implausible_run(spec, *scene, solver->stable_time_step());
    }
  } catch (const CaseError& e) {
    err << "mpile: " << e.what() << '\n';
    return exit_bad_input;
  } catch (const std::invalid_argument& e) {
    err << "mpile: " << spec.file << ": " << e.what() << '\n';
    return exit_bad_input;
  }

  if (stop_requested != 0) {
    err << "mpile: interrupted before the run started; nothing was written\n";
    return exit_interrupted;
  }

  if (!continuation_reason.empty()) {
    out << "mpile: --continue: " << continuation_reason
        << (restarting ? "" : ": the run starts from the beginning") << '\n';
  }

  // Nothing is written before the case has been read, built and judged runnable.
  const std::string directory = output_directory(options, spec);
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    err << "mpile: cannot create the output directory " << directory << ": " << error.message()
        << '\n';
    return exit_failure;
  }

  // One run at a time in a directory; the lock lasts as long as this run.
  std::optional<OutputLock> lock;
  try {
    lock.emplace(directory);
    if (!restarting) {
      // A fresh run replaces the outputs of an earlier run in the same directory, so that no
      // stale snapshot or checkpoint is taken for part of this one.
      remove_earlier_outputs(directory);
    }
  } catch (const OutputBusy& e) {
    err << "mpile: " << e.what() << '\n';
    return exit_bad_input;
  } catch (const std::runtime_error& e) {
    err << "mpile: " << e.what() << '\n';
    return exit_failure;
  }

  // The run's log beside its outputs (appended to by a restart), flushed line by line.
  std::ofstream log_file(directory + "/run.log", restarting ? std::ios::app : std::ios::trunc);
  auto to_log_file = [&](const std::string& line) {
    if (log_file) {
      log_file << line << std::endl;
    }
  };
  if (log_file) {
    log.also_to(&log_file);
    to_log_file(
        std::string("mpile ") + MPILE_VERSION + ": " +
        (restarting ? "continuing " + spec.file + " from " + restart : "running " + spec.file) +
        " on " + std::to_string(options.threads) + " threads");
    if (!continuation_reason.empty()) {
      to_log_file("--continue: " + continuation_reason);
    }
    // The warnings printed as the run began, beside its outputs where they are read.
    print_case_warnings(log_file, spec.warnings, false);
    log_file.flush();
  }

  const OutputSpec& output = spec.output;
  const OutputSchedule schedule{output.history_interval, output.snapshot_interval,
                                output.snapshot_times,   output.snapshot_penetrations,
                                output.penetration_body, output.checkpoint_interval};
  const std::string checkpoint_path = directory + "/checkpoint.h5";
  try {
    std::unique_ptr<HistoryWriter> history_file;
    try {
      history_file =
          std::make_unique<HistoryWriter>(directory + "/history.h5", spec, *scene, options.threads,
                                          restarting ? progress.history_rows : 0);
    } catch (const NoRoomForOutput&) {
      throw; // a full disk, not a checkpoint that does not fit its history
    } catch (const std::runtime_error& e) {
      if (!restarting) {
        throw;
      }
      // The checkpoint and the history it continues do not fit together: bad input.
      err << "mpile: " << restart << ": cannot continue the history in " << directory;
      if (!std::filesystem::exists(directory + "/history.h5")) {
        err << ": it has no history.h5; restart into the output directory of the run that wrote "
               "the checkpoint (--out)\n";
      } else {
        err << ": " << e.what() << '\n';
      }
      return exit_bad_input;
    }
    HistoryWriter& history = *history_file;
    SnapshotWriter snapshots(directory, output.grid_snapshots);
    auto save_state = [&] {
      // The checkpoint counts the history's rows: they must be in the file before it does, or a
      // run killed after the checkpoint restarts from rows the file never got.
      history.flush();
      progress.snapshots = snapshots.entries();
      progress.history_rows = history.rows();
      write_checkpoint(checkpoint_path, spec, *scene, solver->state(), progress);
    };
    ProgressReporter reporter(err, isatty(fileno(stderr)) != 0);
    PhaseRunner runner(*solver, phases.phases(), schedule, progress, log);
    HistoryObserver history_observer(history, *solver);
    SnapshotObserver snapshot_observer(snapshots, *scene);
    CheckpointObserver checkpoint_observer(save_state);
    ProgressObserver progress_observer(reporter);
    for (RunObserver* observer : std::initializer_list<RunObserver*>{
             &history_observer, &snapshot_observer, &checkpoint_observer, &progress_observer}) {
      runner.add_observer(*observer);
    }
    auto residual_summary = [&] {
      const PhaseRunner::ResidualSummary r = runner.residual_summary();
      return HistoryWriter::ResidualSummary{r.final, r.peak, r.peak_time};
    };
    if (restarting) {
      snapshots.restore(progress.snapshots);
      out << "mpile: continuing " << spec.file << " from " << restart
          << " at t = " << format_time(solver->time()) << " s\n";
    } else {
      runner.start();
    }
    const auto stop_due = [&](long steps_this_run) {
      return stop_requested != 0 ||
             (options.stop_after_steps > 0 && steps_this_run >= options.stop_after_steps) ||
             (options.stop_after_seconds > 0.0 &&
              seconds_since(wall_start) >= options.stop_after_seconds);
    };
    // An output that cannot be written (a full disk, a file-size limit) stops the run: what was
    // written before stays readable, and the message names the file.
    const auto cannot_write = [&](const std::runtime_error& e) {
      reporter.finish();
      std::ostringstream line;
      line << "mpile: " << e.what() << "; the run stopped at t = " << format_time(solver->time())
           << " s (outputs so far are in " << directory;
      if (std::filesystem::exists(checkpoint_path)) {
        line << "; once there is room, continue with --restart " << checkpoint_path;
      }
      line << ")";
      try {
        history.close_after_failure(seconds_since(wall_start), std::string("failed: ") + e.what(),
                                    residual_summary());
      } catch (const std::runtime_error&) {
        // Not even the status could be written: the history keeps its whole rows so far.
      }
      err << line.str() << '\n';
      to_log_file(line.str());
      return exit_failure;
    };
    try {
      try {
        if (runner.run(phases.set_up_on(*solver), stop_due) == PhaseRunner::Outcome::interrupted) {
          const double t = solver->time();
          reporter.finish();
          // The checkpoint lists the snapshots an uninterrupted run has by now; the one taken at
          // the interruption is this run's alone (a restart writes its number again).
          save_state();
          runner.snapshot_now();
          history.close(seconds_since(wall_start), "interrupted at t = " + format_time(t) + " s",
                        residual_summary());
          std::ostringstream line;
          line << "mpile: interrupted at t = " << format_time(t) << " s; checkpoint "
               << checkpoint_path << " (continue with --restart " << checkpoint_path << ")";
          err << line.str() << '\n';
          to_log_file(line.str());
          return exit_interrupted;
        }
      } catch (const SimulationError& e) {
        reporter.finish();
        save_state();
        history.close(seconds_since(wall_start), std::string("failed: ") + e.what(),
                      residual_summary());
        const std::string line =
            std::string("mpile: ") + e.what() + " (outputs so far are in " + directory + ")";
        err << line << '\n';
        to_log_file(line);
        return exit_failure;
      }
      const double t = solver->time();
      runner.snapshot_now();
      save_state();
      const double wall = seconds_since(wall_start);
      // A run that completes with energy unaccounted for says so where it is read first: the
      // history's status and the last line of the log.
      const double warning = solver->settings().energy_residual_warning;
      const double final_residual = runner.residual_summary().final;
      const bool doubtful = progress.peak_residual > warning || final_residual > warning;
      std::ostringstream residual;
      residual << std::setprecision(3) << "energy residual " << 100.0 * final_residual
               << " % at the end, peak " << 100.0 * progress.peak_residual
               << " % at t = " << format_time(progress.peak_residual_time) << " s";
      if (doubtful) {
        residual << " (energy_residual_warning " << 100.0 * warning << " %)";
      }
      history.close(wall, doubtful ? "complete, but the " + residual.str() : "complete",
                    residual_summary());
      std::ostringstream done;
      done << "mpile: " << spec.title
           << (doubtful ? " done, but its energy balance is doubtful" : " done")
           << ": t = " << format_time(t) << " s in " << solver->step_count() << " steps, "
           << std::fixed << std::setprecision(1) << wall << " s wall; " << residual.str()
           << "; outputs in " << directory;
      out << done.str() << "\n";
      to_log_file(done.str());
    } catch (const std::runtime_error& e) {
      return cannot_write(e);
    }
  } catch (const std::runtime_error& e) {
    // The outputs could not even be started (the history's header, the snapshot index).
    const std::string line = std::string("mpile: ") + e.what();
    err << line << '\n';
    to_log_file(line);
    return exit_failure;
  }
  return exit_success;
}

} // namespace mpile
