#include "io/run_command.hpp"

#include "io/case_builder.hpp"
#include "io/case_error.hpp"
#include "io/checkpoint.hpp"
#include "io/history_writer.hpp"
#include "io/monitor_points.hpp"
#include "io/output_directory.hpp"
#include "io/plausibility.hpp"
#include "io/progress_reporter.hpp"
#include "io/vtk_writer.hpp"
#include "solver/diagnostics.hpp"

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

/// Times equal to within this fraction of a step count as reached.
bool reached(double time, double target, double dt) {
  return time >= target - 1e-9 * dt;
}

const RigidBody& rigid_body_named(const Scene& scene, const std::string& name) {
  for (const RigidBody& body : scene.rigid_bodies) {
    if (body.name == name) {
      return body;
    }
  }
  throw std::logic_error("no rigid body named " + name);
}

/// A rigid body's penetration: its total downward displacement (m).
double penetration_of(const RigidBody& body) {
  return -body.displacement[RIGID_Y];
}

/// Below this vertical speed (m/s) a pile counts as at rest between blows.
constexpr double rest_speed = 1e-3;

std::string format_time(double t) {
  std::ostringstream s;
  s << std::setprecision(6) << t;
  return s.str();
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
  const bool restarting = !options.restart.empty();
  try {
    spec = read_case_file(options.case_path, options.overrides);
    scene = build_scene(spec);
    if (!restarting) {
      for (const MonitorSpec& monitor : spec.output.monitors) {
        monitored_particle(monitor, *scene); // refused here, before anything is written
      }
    }
    if (restarting) {
      restored = read_checkpoint(options.restart, spec, *scene);
      if (restored.progress.phase >= spec.phases.size()) {
        // A complete run goes on only when its last phase may now end later.
        const std::string last = "phases." + std::to_string(spec.phases.size() - 1) + ".";
        if (std::none_of(restored.changed_keys.begin(), restored.changed_keys.end(),
                         [&](const std::string& key) { return key.starts_with(last); })) {
          throw CaseError(options.restart +
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

  RunLog log(&out);
  RunProgress progress = restarting ? restored.progress : RunProgress{};
  // Where a phase's stop_at body stands as the phase begins, for a settlement stop.
  const auto begin_phase = [&](std::size_t p, double time) {
    progress.phase_starts.push_back(time);
    const auto& stop = spec.phases[p].stop_at;
    progress.phase_start_depths.resize(progress.phase_starts.size() - 1,
                                       std::numeric_limits<double>::quiet_NaN());
    progress.phase_start_depths.push_back(stop && stop->settlement > 0.0
                                              ? penetration_of(rigid_body_named(*scene, stop->body))
                                              : std::numeric_limits<double>::quiet_NaN());
  };
  if (!restarting) {
    begin_phase(0, 0.0);
    apply_k0(*scene, spec, spec.phases.front());
  }
  // A complete run continued into phases added to its case: the next phase begins now.
  const bool begins_added_phase = progress.phase == progress.phase_starts.size();
  if (begins_added_phase) {
    begin_phase(progress.phase, restored.solver.time);
  }
  for (std::size_t p = 0; p < progress.phase_starts.size(); ++p) {
    activate_phase_boundaries(*scene, spec, p, progress.phase_starts[p]);
  }

  std::unique_ptr<ExplicitSolver> solver;
  try {
    const SolverSettings settings = phase_settings(spec, spec.phases[progress.phase]);
    solver = restarting ? std::make_unique<ExplicitSolver>(*scene, settings, log, restored.solver)
                        : std::make_unique<ExplicitSolver>(*scene, settings, log);
    if (!restarting) {
      refuse_implausible_run(spec, *scene, solver->stable_time_step());
      switch_on_absorbing_faces(*solver, spec, 0);
    }
    if (begins_added_phase) {
      const double elastic_before = elastic_energy(*scene);
      apply_k0(*scene, spec, spec.phases[progress.phase]);
      if (!spec.phases[progress.phase].k0.empty()) {
        solver->account_for_stress_reset(elastic_before);
      }
      switch_on_absorbing_faces(*solver, spec, progress.phase);
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
    to_log_file(std::string("mpile ") + MPILE_VERSION + ": " +
                (restarting ? "continuing " + spec.file + " from " + options.restart
                            : "running " + spec.file) +
                " on " + std::to_string(options.threads) + " threads");
  }

  const OutputSpec& output = spec.output;
  const double never = std::numeric_limits<double>::infinity();
  std::vector<double> listed = output.snapshot_times;
  std::sort(listed.begin(), listed.end());
  const std::vector<double>& depths = output.snapshot_penetrations;
  // The next listed penetration follows from the state, so a restarted run needs no bookkeeping.
  std::size_t next_depth = 0;
  auto skip_reached_depths = [&] {
    bool passed = false;
    while (next_depth < depths.size() &&
           penetration_of(rigid_body_named(*scene, output.penetration_body)) >=
               depths[next_depth]) {
      ++next_depth;
      passed = true;
    }
    return passed;
  };
  skip_reached_depths();
  const std::string checkpoint_path = directory + "/checkpoint.h5";
  try {
    std::unique_ptr<HistoryWriter> history_file;
    try {
      history_file =
          std::make_unique<HistoryWriter>(directory + "/history.h5", spec, *scene, options.threads,
                                          restarting ? progress.history_rows : 0);
    } catch (const std::runtime_error& e) {
      if (!restarting) {
        throw;
      }
      // The checkpoint and the history it continues do not fit together: bad input.
      err << "mpile: " << options.restart << ": cannot continue the history in " << directory;
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
    if (restarting) {
      snapshots.restore(progress.snapshots);
      out << "mpile: continuing " << spec.file << " from " << options.restart
          << " at t = " << format_time(solver->time()) << " s\n";
    } else {
      history.record(*solver, 0);
      snapshots.write(*scene, 0.0);
      progress.next_history_time = output.history_interval;
      progress.next_snapshot_time =
          output.snapshot_interval > 0.0 ? output.snapshot_interval : never;
      progress.next_checkpoint_time =
          output.checkpoint_interval > 0.0 ? output.checkpoint_interval : never;
      while (progress.next_listed_snapshot < listed.size() &&
             listed[progress.next_listed_snapshot] <= 0.0) {
        ++progress.next_listed_snapshot;
      }
    }
    auto save_state = [&] {
      // The checkpoint counts the history's rows: they must be in the file before it does, or a
      // run killed after the checkpoint restarts from rows the file never got.
      history.flush();
      progress.snapshots = snapshots.entries();
      progress.history_rows = history.rows();
      write_checkpoint(checkpoint_path, spec, *scene, solver->state(), progress);
    };

    // The first row whose energy residual passes the case's warning threshold warns, once per
    // run. A residual past the limit stops the run as unstable once it has stayed past it for
    // blow_up_steps steps: the first steps of a run put so little energy in play that their
    // residual, a start-up error of order dt, can pass any fraction, and it fades; a blow-up
    // does not (the rows are already in the history).
    constexpr long blow_up_steps = 100;
    // Between history rows the guard looks every guard_steps steps, so that a run whose rows are
    // far apart (or a single row at the end) still stops within blow_up_steps + guard_steps steps
    // of a blow-up; the sums cost about a twentieth of a particle pass per step.
    constexpr long guard_steps = 20;
    long recorded_step = -1;
    bool residual_warned = false;
    long over_limit_since = -1;
    double final_residual = 0.0;
    auto residual_summary = [&] {
      return HistoryWriter::ResidualSummary{final_residual, progress.peak_residual,
                                            progress.peak_residual_time};
    };
    // recorded: the balance is a history row's (the final and peak residuals are the rows').
    auto check_energy_residual = [&](const EnergyBalance& energy, bool recorded) {
      const SolverSettings& settings = solver->settings();
      if (recorded) {
        final_residual = energy.relative_residual;
      }
      // The peak leaves out the start-up (see above), which would otherwise dominate it.
      if (recorded && solver->step_count() >= blow_up_steps &&
          !(energy.relative_residual <= progress.peak_residual)) {
        progress.peak_residual = energy.relative_residual;
        progress.peak_residual_time = solver->time();
      }
      const bool over_limit = !(energy.relative_residual <= settings.energy_residual_limit);
      if (!over_limit) {
        over_limit_since = -1;
      } else if (over_limit_since < 0) {
        over_limit_since = solver->step_count();
      }
      const bool blown_up = over_limit && solver->step_count() - over_limit_since >= blow_up_steps;
      if (!blown_up && (!recorded || residual_warned ||
                        !(energy.relative_residual > settings.energy_residual_warning))) {
        return;
      }
      if (blown_up && !recorded) {
        // The history ends on the step that stopped the run.
        final_residual = history.record(*solver, progress.phase).relative_residual;
        recorded_step = solver->step_count();
      }
      std::ostringstream s;
      s << "t = " << format_time(solver->time()) << " s: the energy residual is "
        << std::setprecision(3) << 100.0 * energy.relative_residual << " % of the energy in play ("
        << (blown_up ? "energy_residual_limit " : "energy_residual_warning ")
        << 100.0 * (blown_up ? settings.energy_residual_limit : settings.energy_residual_warning)
        << " %";
      if (blown_up) {
        s << " since step " << over_limit_since;
      }
      s << "): external work " << energy.external_work << ", kinetic " << energy.kinetic
        << ", elastic " << energy.elastic << ", plastic " << energy.plastic << ", damping "
        << energy.damping << ", contact " << energy.contact << ", transfer " << energy.transfer
        << "; " << describe_kinetic_hotspot(*scene, settings.mass_scaling);
      if (blown_up) {
        throw SimulationError("step " + std::to_string(solver->step_count()) + ", " + s.str() +
                              ": the run went unstable");
      }
      residual_warned = true;
      log.warn(s.str() + " (see /energy in history.h5)");
    };
    ProgressReporter reporter(err, isatty(fileno(stderr)) != 0);
    long steps_this_run = 0;
    auto stop_due = [&] {
      return stop_requested != 0 ||
             (options.stop_after_steps > 0 && steps_this_run >= options.stop_after_steps) ||
             (options.stop_after_seconds > 0.0 &&
              seconds_since(wall_start) >= options.stop_after_seconds);
    };
    // A snapshot of the state a run stops or a phase ends in, unless one was just written.
    auto snapshot_now = [&] {
      const double t = solver->time();
      if (snapshots.entries().empty() || snapshots.entries().back().first < t) {
        snapshots.write(*scene, t);
      }
    };
    auto interrupt = [&] {
      const double t = solver->time();
      reporter.finish();
      snapshot_now();
      save_state();
      history.close(seconds_since(wall_start), "interrupted at t = " + format_time(t) + " s",
                    residual_summary());
      std::ostringstream line;
      line << "mpile: interrupted at t = " << format_time(t) << " s; checkpoint " << checkpoint_path
           << " (continue with --restart " << checkpoint_path << ")";
      err << line.str() << '\n';
      to_log_file(line.str());
      return exit_interrupted;
    };
    try {
      while (progress.phase < spec.phases.size()) {
        const PhaseSpec& phase = spec.phases[progress.phase];
        const double phase_end = progress.phase_starts[progress.phase] + phase.duration;
        log.info("phase " + phase.name + " from t = " + format_time(solver->time()) + " s");
        history.phase_started(progress.phase, phase.name, progress.phase_starts[progress.phase]);
        std::string ended = "after its duration";
        while (!reached(solver->time(), phase_end, solver->stable_time_step())) {
          // Steps land exactly on the phase end and on snapshot times, without a sliver step.
          double limit = std::min(phase_end, progress.next_snapshot_time) - solver->time();
          if (progress.next_listed_snapshot < listed.size()) {
            limit = std::min(limit, listed[progress.next_listed_snapshot] - solver->time());
          }
          solver->step(landing_step(limit, solver->stable_time_step()));
          ++steps_this_run; // every step counts, the one that ends a phase too
          const double t = solver->time();
          const double dt = solver->last_time_step();
          if (output.history_interval == 0.0 || reached(t, progress.next_history_time, dt)) {
            recorded_step = solver->step_count();
            check_energy_residual(history.record(*solver, progress.phase), true);
            while (output.history_interval > 0.0 && reached(t, progress.next_history_time, dt)) {
              progress.next_history_time += output.history_interval;
            }
          } else if (solver->step_count() % guard_steps == 0) {
            check_energy_residual(solver->energy_balance(), false);
          }
          bool snapshot_due = reached(t, progress.next_snapshot_time, dt);
          while (reached(t, progress.next_snapshot_time, dt)) {
            progress.next_snapshot_time += output.snapshot_interval;
          }
          while (progress.next_listed_snapshot < listed.size() &&
                 reached(t, listed[progress.next_listed_snapshot], dt)) {
            snapshot_due = true;
            ++progress.next_listed_snapshot;
          }
          if (!depths.empty() && skip_reached_depths()) {
            snapshot_due = true;
          }
          if (snapshot_due) {
            snapshots.write(*scene, t);
          }
          if (reached(t, progress.next_checkpoint_time, dt)) {
            while (reached(t, progress.next_checkpoint_time, dt)) {
              progress.next_checkpoint_time += output.checkpoint_interval;
            }
            save_state();
          }
          // Equilibrium is checked on a fixed step grid, so a restarted run checks the same steps.
          // Equilibrium: out-of-balance force and kinetic energy both small (physics.md 9).
          if (phase.equilibrium_tolerance && solver->step_count() % 20 == 0) {
            const double kinetic = kinetic_energy(*scene);
            const double work = std::abs(solver->external_work());
            // A state already at rest (no work done, no motion) counts too.
            if (kinetic <= *phase.equilibrium_tolerance * work) {
              const double force_ratio = solver->unbalanced_force_ratio();
              if (force_ratio < *phase.equilibrium_tolerance) {
                std::ostringstream why;
                why << "at equilibrium (out-of-balance force ratio " << std::setprecision(3)
                    << force_ratio << ", kinetic energy / external work "
                    << (work > 0.0 ? kinetic / work : 0.0) << ")";
                ended = why.str();
                break;
              }
            }
          }
          // Progress in the phase's own terms: its stop depth, else its end time.
          PhaseGoal goal{"t", t, phase_end, "s", t, phase_end};
          if (phase.stop_at) {
            const PenetrationStop& stop = *phase.stop_at;
            const RigidBody& pile = rigid_body_named(*scene, stop.body);
            const double depth = penetration_of(pile);
            const double speed = std::abs(pile.velocity[RIGID_Y]);
            // A load test counts its settlement since the phase began, others the penetration.
            const bool settles = stop.settlement > 0.0;
            const double measured =
                settles ? depth - progress.phase_start_depths.at(progress.phase) : depth;
            const double target = settles ? stop.settlement : stop.penetration;
            goal = {settles ? "settlement" : "penetration", measured, target, "m", t, phase_end};
            std::ostringstream why;
            why << std::setprecision(4);
            if (measured >= target && (!stop.at_rest || speed < rest_speed)) {
              why << "at " << stop.body << (settles ? " settlement " : " penetration ") << measured
                  << " m";
              if (settles) {
                why << " (penetration " << depth << " m)";
              }
              ended = why.str() + (stop.at_rest ? " and at rest" : "");
              break;
            }
            // The band may not be carried past its travel: a load test ends there, short of its
            // settlement, and says so (a penetration stop beyond it is refused when read).
            const double travel = scene->moving_mesh ? scene->moving_mesh->travel : 0.0;
            if (settles && travel > 0.0 && depth + speed * solver->stable_time_step() >= travel) {
              why << "at the moving band's travel (" << travel << " m) with " << stop.body
                  << " settlement " << measured << " m of " << stop.settlement;
              ended = why.str();
              break;
            }
          }
          reporter.update(phase.name, solver->step_count(), goal);
          if (stop_due()) {
            return interrupt();
          }
        }
        reporter.finish();
        // The state a phase ends in (a target penetration, equilibrium) is always in the history.
        if (recorded_step != solver->step_count()) {
          final_residual = history.record(*solver, progress.phase).relative_residual;
          recorded_step = solver->step_count();
        }
        snapshot_now();
        history.phase_ended(progress.phase, solver->time(), ended);
        log.info("phase " + phase.name + " ended at t = " + format_time(solver->time()) + " s " +
                 ended + ", " + std::to_string(solver->step_count()) + " steps so far");
        ++progress.phase;
        if (progress.phase < spec.phases.size()) {
          begin_phase(progress.phase, solver->time());
          activate_phase_boundaries(*scene, spec, progress.phase, solver->time());
          const double elastic_before = elastic_energy(*scene);
          apply_k0(*scene, spec, spec.phases[progress.phase]);
          if (!spec.phases[progress.phase].k0.empty()) {
            solver->account_for_stress_reset(elastic_before);
          }
          solver->change_settings(phase_settings(spec, spec.phases[progress.phase]));
          switch_on_absorbing_faces(*solver, spec, progress.phase);
          // A stop due on the step that ended the phase comes here, with the next phase set up.
          if (stop_due()) {
            return interrupt();
          }
        }
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
    snapshot_now();
    save_state();
    const double wall = seconds_since(wall_start);
    // A run that completes with energy unaccounted for says so where it is read first: the
    // history's status and the last line of the log.
    const double warning = solver->settings().energy_residual_warning;
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
    if (solver->soil_moved_out() > 0) {
      // Contact acts at nodes; how often soil crossed a rigid outline between them tells whether
      // the mesh resolves the structure's corners (docs/design.md, "Contact and rigid bodies", step
      // 8).
      to_log_file("soil particles put back on a rigid outline " +
                  std::to_string(solver->soil_moved_out()) +
                  " times in this run (their centres had crossed it between the nodes)");
    }
    std::ostringstream done;
    done << "mpile: " << spec.title << (doubtful ? " done, but with a doubtful" : " done")
         << ": t = " << format_time(t) << " s in " << solver->step_count() << " steps, "
         << std::fixed << std::setprecision(1) << wall << " s wall; " << residual.str()
         << "; outputs in " << directory;
    out << done.str() << "\n";
    to_log_file(done.str());
  } catch (const std::runtime_error& e) {
    err << "mpile: " << e.what() << '\n';
    return exit_failure;
  }
  return exit_success;
}

} // namespace mpile
