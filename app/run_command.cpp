#include "app/run_command.hpp"

#include "app/progress_reporter.hpp"
#include "app/run_continuation.hpp"
#include "app/run_observers.hpp"
#include "cases/case_builder.hpp"
#include "cases/case_error.hpp"
#include "cases/case_phases.hpp"
#include "cases/case_warnings.hpp"
#include "cases/plausibility.hpp"
#include "io/checkpoint.hpp"
#include "io/history_writer.hpp"
#include "io/monitor_points.hpp"
#include "io/output_directory.hpp"
#include "io/reserve_space.hpp"
#include "io/vtk_writer.hpp"
#include "solver/phase_runner.hpp"

#include <tbb/task_arena.h>

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

/// The run's output directory and where its path came from (named in its messages): --out, else
/// the case's [output] directory, else out/<case stem>.
struct OutputDirectory {
  std::string path;
  std::string source;
};

OutputDirectory output_directory(const RunOptions& options, const CaseSpec& spec) {
  if (!options.output_directory.empty()) {
    return {options.output_directory, "--out"};
  }
  if (!spec.output.directory.empty()) {
    return {spec.output.directory, "[output] directory in " + spec.file};
  }
  return {"out/" + std::filesystem::path(spec.file).stem().string(), "the default out/<case name>"};
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

namespace {

/// A stage's outcome: std::nullopt to go on, else the exit status the command ends with.
using Stop = std::optional<int>;

/// `mpile run` in its stages: open (read the case, find what it continues, build the scene, read
/// the checkpoint), start the solver, prepare the outputs (directory, lock, log), run the phases
/// with their observers, and close (the history's status and the summary, for each way a run
/// ends). Each stage handles its own errors; nothing is written before the outputs' stage.
class RunStages {
public:
  RunStages(const RunOptions& options, std::ostream& out, std::ostream& err)
      : options_(options), out_(out), err_(err), log_(&out),
        wall_start_(std::chrono::steady_clock::now()) {}

  int run() {
    if (const Stop stop = open()) {
      return *stop;
    }
    // Before anything is written: with --strict a likely slip of units refuses the run.
    print_case_warnings(err_, spec_.warnings, options_.strict);
    if (options_.strict && refused_when_strict(spec_.warnings)) {
      return exit_bad_input;
    }
    if (const Stop stop = start_solver()) {
      return *stop;
    }
    if (stop_requested != 0) {
      err_ << "mpile: interrupted before the run started; nothing was written\n";
      return exit_interrupted;
    }
    if (!continuation_reason_.empty()) {
      out_ << "mpile: --continue: " << continuation_reason_
           << (restarting() ? "" : ": the run starts from the beginning") << '\n';
    }
    if (const Stop stop = prepare_outputs()) {
      return *stop;
    }
    try {
      return run_phases();
    } catch (const std::runtime_error& e) {
      // The outputs could not even be started (the history's header, the snapshot index).
      return stop_with(std::string("mpile: ") + e.what(), exit_failure);
    }
  }

private:
  bool restarting() const { return !restart_.empty(); }
  /// The threads the run has, as recorded in its log and history: the arena's, not the number
  /// asked for (they differed when the arena was the default one of a thread a core).
  static int threads_running() { return tbb::this_task_arena::max_concurrency(); }

  /// Open: the case read (bases, --set), what --continue continues, the scene built, a fresh
  /// run's monitors found and a continued run's checkpoint read. Bad input: exit 2.
  Stop open() {
    restart_ = options_.restart;
    try {
      spec_ = read_case_file(options_.case_path, options_.overrides);
      if (options_.continue_run && restart_.empty()) {
        const Continuation c =
            find_continuation(output_directory(options_, spec_).path, spec_.resolved);
        if (c.complete) {
          out_ << "mpile: " << c.reason << "; nothing to continue\n";
          return exit_success;
        }
        restart_ = c.checkpoint;
        continuation_reason_ = c.reason;
      }
      scene_ = build_scene(spec_);
      if (!restarting()) {
        for (const MonitorSpec& monitor : spec_.output.monitors) {
          monitored_particle(monitor, *scene_); // refused here, before anything is written
        }
        return std::nullopt;
      }
      restored_ = read_checkpoint(restart_, spec_, *scene_);
      if (restored_.progress.phase >= spec_.phases.size()) {
        // A complete run goes on only when its last phase may now end later.
        const std::string last = "phases." + std::to_string(spec_.phases.size() - 1) + ".";
        if (std::none_of(restored_.changed_keys.begin(), restored_.changed_keys.end(),
                         [&](const std::string& key) { return key.starts_with(last); })) {
          throw CaseError(restart_ +
                          ": the run in this checkpoint is complete; nothing to continue (to "
                          "extend it, change the last phase's duration or stop_at, or add a "
                          "phase)");
        }
        restored_.progress.phase = spec_.phases.size() - 1;
      }
    } catch (const std::exception&) {
      return refuse_case(err_, options_.case_path);
    }
    return std::nullopt;
  }

  /// The solver at the run's first phase, or at the checkpoint's; an implausible fresh run is
  /// refused (exit 2).
  Stop start_solver() {
    progress_ = restarting() ? restored_.progress : RunProgress{};
    phases_.emplace(spec_, *scene_);
    try {
      solver_ = restarting() ? phases_->resume(progress_, log_, restored_.solver)
                             : phases_->start(progress_, log_);
      if (!restarting()) {
        refuse_implausible_run(spec_, *scene_, solver_->stable_time_step());
      }
    } catch (const CaseError& e) {
      err_ << "mpile: " << e.what() << '\n';
      return exit_bad_input;
    } catch (const std::invalid_argument& e) {
      err_ << "mpile: " << spec_.file << ": " << e.what() << '\n';
      return exit_bad_input;
    }
    return std::nullopt;
  }

  /// The output directory made and locked (one run at a time in it), an earlier run's outputs
  /// removed for a fresh run, and the run's log opened beside them.
  Stop prepare_outputs() {
    const OutputDirectory output = output_directory(options_, spec_);
    directory_ = output.path;
    checkpoint_path_ = directory_ + "/checkpoint.h5";
    std::error_code error;
    std::filesystem::create_directories(directory_, error);
    if (error == std::errc::file_exists || error == std::errc::not_a_directory) {
      // The path, or a folder on it, is a file: the user's choice of path, not the machine's.
      err_ << "mpile: the output directory " << directory_ << " (" << output.source
           << ") cannot be made: it or a folder on its path is a file\n";
      return exit_bad_input;
    }
    if (error) {
      err_ << "mpile: cannot create the output directory " << directory_ << ": " << error.message()
           << '\n';
      return exit_failure;
    }
    try {
      lock_.emplace(directory_);
      if (!restarting()) {
        // A fresh run replaces the outputs of an earlier run in the same directory, so that no
        // stale snapshot or checkpoint is taken for part of this one.
        remove_earlier_outputs(directory_);
      }
    } catch (const OutputBusy& e) {
      err_ << "mpile: " << e.what() << '\n';
      return exit_bad_input;
    } catch (const std::runtime_error& e) {
      err_ << "mpile: " << e.what() << '\n';
      return exit_failure;
    }
    // Found now, not when the first checkpoint is due (at the end, where checkpoint_interval is
    // 0): a run of hours would be lost to a path the user can clear before it starts.
    if (std::filesystem::exists(checkpoint_path_, error) &&
        !std::filesystem::is_regular_file(checkpoint_path_, error)) {
      err_ << "mpile: " << checkpoint_path_
           << " is not a file (a directory?): the run writes its checkpoint there; remove it or "
              "choose another --out\n";
      return exit_bad_input;
    }
    // Appended to by a restart, flushed line by line.
    log_file_.open(directory_ + "/run.log", restarting() ? std::ios::app : std::ios::trunc);
    if (log_file_) {
      log_.also_to(&log_file_);
      to_log_file(std::string("mpile ") + MPILE_VERSION + ": " +
                  (restarting() ? "continuing " + spec_.file + " from " + restart_
                                : "running " + spec_.file) +
                  " on " + std::to_string(threads_running()) + " threads");
      if (!continuation_reason_.empty()) {
        to_log_file("--continue: " + continuation_reason_);
      }
      // The warnings printed as the run began, beside its outputs where they are read.
      print_case_warnings(log_file_, spec_.warnings, false);
      log_file_.flush();
    }
    return std::nullopt;
  }

  /// The history opened (created, or continued after a restart); a checkpoint whose history does
  /// not fit it is bad input.
  Stop open_history() {
    try {
      history_ = std::make_unique<HistoryWriter>(directory_ + "/history.h5", spec_, *scene_,
                                                 threads_running(),
                                                 restarting() ? progress_.history_rows : 0);
    } catch (const NoRoomForOutput&) {
      throw; // a full disk, not a checkpoint that does not fit its history
    } catch (const std::runtime_error& e) {
      if (!restarting()) {
        throw;
      }
      err_ << "mpile: " << restart_ << ": cannot continue the history in " << directory_;
      if (!std::filesystem::exists(directory_ + "/history.h5")) {
        err_ << ": it has no history.h5; restart into the output directory of the run that wrote "
                "the checkpoint (--out)\n";
      } else {
        err_ << ": " << e.what() << '\n';
      }
      return exit_bad_input;
    }
    return std::nullopt;
  }

  /// Run: the phases with their observers (history, snapshots, checkpoints, progress) until they
  /// end, are interrupted or fail; then the matching close.
  int run_phases() {
    if (const Stop stop = open_history()) {
      return *stop;
    }
    const OutputSpec& output = spec_.output;
    const OutputSchedule schedule{output.history_interval, output.snapshot_interval,
                                  output.snapshot_times,   output.snapshot_penetrations,
                                  output.penetration_body, output.checkpoint_interval};
    snapshots_.emplace(directory_, output.grid_snapshots);
    reporter_.emplace(err_, isatty(fileno(stderr)) != 0);
    runner_.emplace(*solver_, phases_->phases(), schedule, progress_, log_);
    HistoryObserver history_observer(*history_, *solver_);
    SnapshotObserver snapshot_observer(*snapshots_, *scene_);
    CheckpointObserver checkpoint_observer([this] { save_state(); });
    ProgressObserver progress_observer(*reporter_);
    for (RunObserver* observer : std::initializer_list<RunObserver*>{
             &history_observer, &snapshot_observer, &checkpoint_observer, &progress_observer}) {
      runner_->add_observer(*observer);
    }
    if (restarting()) {
      snapshots_->restore(progress_.snapshots);
      out_ << "mpile: continuing " << spec_.file << " from " << restart_
           << " at t = " << format_time(solver_->time()) << " s\n";
    } else {
      runner_->start();
    }
    const auto stop_due = [&](long steps_this_run) {
      return stop_requested != 0 ||
             (options_.stop_after_steps > 0 && steps_this_run >= options_.stop_after_steps) ||
             (options_.stop_after_seconds > 0.0 &&
              seconds_since(wall_start_) >= options_.stop_after_seconds);
    };
    try {
      try {
        if (runner_->run(phases_->set_up_on(*solver_), stop_due) ==
            PhaseRunner::Outcome::interrupted) {
          return close_interrupted();
        }
      } catch (const SimulationError& e) {
        return close_failed(e);
      }
      return close_complete();
    } catch (const std::runtime_error& e) {
      return close_cannot_write(e);
    }
  }

  /// The checkpoint, after the history's rows it counts.
  void save_state() {
    // The rows must be in the file before the checkpoint counts them, or a run killed after the
    // checkpoint restarts from rows the file never got.
    history_->flush();
    progress_.snapshots = snapshots_->entries();
    progress_.history_rows = history_->rows();
    write_checkpoint(checkpoint_path_, spec_, *scene_, solver_->state(), progress_);
  }

  HistoryWriter::ResidualSummary residual_summary() const {
    const PhaseRunner::ResidualSummary r = runner_->residual_summary();
    return {r.final, r.peak, r.peak_time};
  }

  /// Interrupted (a signal, --stop-after): a checkpoint to continue from.
  int close_interrupted() {
    const double t = solver_->time();
    reporter_->finish();
    // The checkpoint lists the snapshots an uninterrupted run has by now; the one taken at the
    // interruption is this run's alone (a restart writes its number again).
    save_state();
    runner_->snapshot_now();
    history_->close(seconds_since(wall_start_), "interrupted at t = " + format_time(t) + " s",
                    residual_summary());
    std::ostringstream line;
    line << "mpile: interrupted at t = " << format_time(t) << " s; checkpoint " << checkpoint_path_
         << " (continue with --restart " << checkpoint_path_ << ")";
    return stop_with(line.str(), exit_interrupted);
  }

  /// Unstable or out of the grid: the failure as the history's status, and a checkpoint.
  int close_failed(const SimulationError& e) {
    reporter_->finish();
    save_state();
    history_->close(seconds_since(wall_start_), std::string("failed: ") + e.what(),
                    residual_summary());
    return stop_with(std::string("mpile: ") + e.what() + " (outputs so far are in " + directory_ +
                         ")",
                     exit_failure);
  }

  /// An output that cannot be written (a full disk, a file-size limit) stops the run: what was
  /// written before stays readable, and the message names the file.
  int close_cannot_write(const std::runtime_error& e) {
    reporter_->finish();
    std::ostringstream line;
    line << "mpile: " << e.what() << "; the run stopped at t = " << format_time(solver_->time())
         << " s (outputs so far are in " << directory_;
    if (std::filesystem::exists(checkpoint_path_)) {
      line << "; once there is room, continue with --restart " << checkpoint_path_;
    }
    line << ")";
    try {
      history_->close_after_failure(seconds_since(wall_start_), std::string("failed: ") + e.what(),
                                    residual_summary());
    } catch (const std::runtime_error&) {
      // Not even the status could be written: the history keeps its whole rows so far.
    }
    return stop_with(line.str(), exit_failure);
  }

  /// Complete: the last snapshot and checkpoint, and the summary, which says so where energy went
  /// unaccounted for (the history's status and the log's last line, where it is read first).
  int close_complete() {
    const double t = solver_->time();
    runner_->snapshot_now();
    save_state();
    const double wall = seconds_since(wall_start_);
    const double warning = solver_->settings().energy_residual_warning;
    const double final_residual = runner_->residual_summary().final;
    const bool doubtful = progress_.peak_residual > warning || final_residual > warning;
    std::ostringstream residual;
    residual << std::setprecision(3) << "energy residual " << 100.0 * final_residual
             << " % at the end, peak " << 100.0 * progress_.peak_residual
             << " % at t = " << format_time(progress_.peak_residual_time) << " s";
    if (doubtful) {
      residual << " (energy_residual_warning " << 100.0 * warning << " %)";
    }
    history_->close(wall, doubtful ? "complete, but the " + residual.str() : "complete",
                    residual_summary());
    std::ostringstream done;
    done << "mpile: " << spec_.title
         << (doubtful ? " done, but its energy balance is doubtful" : " done")
         << ": t = " << format_time(t) << " s in " << solver_->step_count() << " steps, "
         << std::fixed << std::setprecision(1) << wall << " s wall; " << residual.str()
         << "; outputs in " << directory_;
    out_ << done.str() << "\n";
    to_log_file(done.str());
    return exit_success;
  }

  /// The closing line, on stderr and in the log; returns `status`.
  int stop_with(const std::string& line, int status) {
    err_ << line << '\n';
    to_log_file(line);
    return status;
  }

  void to_log_file(const std::string& line) {
    if (log_file_) {
      log_file_ << line << std::endl;
    }
  }

  const RunOptions& options_;
  std::ostream& out_;
  std::ostream& err_;
  RunLog log_;
  const std::chrono::steady_clock::time_point wall_start_;
  // Open.
  CaseSpec spec_;
  std::unique_ptr<Scene> scene_;
  Checkpoint restored_;
  std::string restart_; // the checkpoint the run continues from; empty for a fresh run
  std::string continuation_reason_;
  // The solver.
  RunProgress progress_;
  std::optional<CasePhases> phases_;
  std::unique_ptr<ExplicitSolver> solver_;
  // The outputs.
  std::string directory_;
  std::string checkpoint_path_;
  std::optional<OutputLock> lock_;
  std::ofstream log_file_;
  // The run.
  std::unique_ptr<HistoryWriter> history_;
  std::optional<SnapshotWriter> snapshots_;
  std::optional<ProgressReporter> reporter_;
  std::optional<PhaseRunner> runner_;
};

} // namespace

int run_case(const RunOptions& options, std::ostream& out, std::ostream& err) {
  // First of all, so that a SIGINT or SIGTERM while the case is read and built (seconds for a
  // large one) stops the run cleanly instead of killing it.
  StopOnSignals signals;
  RunStages stages(options, out, err);
  return stages.run();
}

} // namespace mpile
