#include "solver/phase_runner.hpp"

#include "solver/diagnostics.hpp"
#include "solver/equilibrium.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace mpile {

namespace {

/// Times equal to within this fraction of a step count as reached.
bool reached(double time, double target, double dt) {
  return time >= target - 1e-9 * dt;
}

/// A schedule's next time once `next` is reached at t: one interval on, as long as that is past t
/// (an interval longer than the step, the usual case); else the first whole interval past t,
/// counted at once. Adding a short interval one at a time would take dt / interval additions a
/// step, and for ever where the interval is below the rounding of t (1e-300 s).
double next_due(double next, double interval, double t, double dt) {
  next += interval;
  if (reached(t, next, dt)) {
    const double past = t + 1e-9 * dt;
    next += std::ceil((past - next) / interval) * interval;
    if (reached(t, next, dt)) {
      next = std::nextafter(past, std::numeric_limits<double>::infinity());
    }
  }
  return next;
}

/// Below this vertical speed (m/s) a pile counts as at rest between blows.
constexpr double rest_speed = 1e-3;

/// A residual past the limit stops the run as unstable once it has stayed past it for
/// blow_up_steps steps: the first steps of a run put so little energy in play that their
/// residual, a start-up error of order dt, can pass any fraction, and it fades; a blow-up does not.
constexpr long blow_up_steps = 100;
/// Between history rows the guard looks every guard_steps steps, so that a run whose rows are far
/// apart (or a single row at the end) still stops within blow_up_steps + guard_steps steps of a
/// blow-up; the sums cost about a twentieth of a particle pass per step.
constexpr long guard_steps = 20;
/// Equilibrium is checked on a fixed step grid, so that a restarted run checks the same steps.
constexpr long equilibrium_steps = 20;

} // namespace

double penetration_of(const RigidBody& body) {
  return -body.displacement[RIGID_Y];
}

const RigidBody& rigid_body_named(const Scene& scene, const std::string& name) {
  for (const RigidBody& body : scene.rigid_bodies) {
    if (body.name == name) {
      return body;
    }
  }
  throw std::logic_error("no rigid body named " + name);
}

void begin_phase(RunProgress& progress, const std::vector<RunPhase>& phases, const Scene& scene,
                 std::size_t p, double time) {
  progress.phase_starts.push_back(time);
  const auto& stop = phases.at(p).stop_at;
  progress.phase_start_depths.resize(progress.phase_starts.size() - 1,
                                     std::numeric_limits<double>::quiet_NaN());
  progress.phase_start_depths.push_back(stop && stop->settlement > 0.0
                                            ? penetration_of(rigid_body_named(scene, stop->body))
                                            : std::numeric_limits<double>::quiet_NaN());
}

PhaseRunner::PhaseRunner(ExplicitSolver& solver, std::vector<RunPhase> phases,
                         OutputSchedule schedule, RunProgress& progress, RunLog& log)
    : solver_(solver), phases_(std::move(phases)), schedule_(std::move(schedule)),
      progress_(progress), log_(log),
      last_snapshot_time_(progress.snapshots.empty() ? -std::numeric_limits<double>::infinity()
                                                     : progress.snapshots.back().first) {
  std::sort(schedule_.snapshot_times.begin(), schedule_.snapshot_times.end());
  // The next listed penetration follows from the state, so a restarted run needs no bookkeeping.
  skip_reached_depths();
  // A run continued under a case whose intervals changed: an interval now 0 ("first and last
  // only", "only when stopped") has no next time, whatever the checkpoint had scheduled (left
  // there, it would be due at every step); one newly set starts from the current time.
  const double t = solver_.time();
  const auto reschedule = [t](double interval, double& next) {
    if (!(interval > 0.0)) {
      next = std::numeric_limits<double>::infinity();
    } else if (!std::isfinite(next)) {
      next = (std::floor(t / interval) + 1.0) * interval;
    }
  };
  reschedule(schedule_.snapshot_interval, progress_.next_snapshot_time);
  reschedule(schedule_.checkpoint_interval, progress_.next_checkpoint_time);
}

bool PhaseRunner::skip_reached_depths() {
  const auto& depths = schedule_.snapshot_penetrations;
  bool passed = false;
  while (next_depth_ < depths.size() &&
         penetration_of(rigid_body_named(solver_.scene(), schedule_.penetration_body)) >=
             depths[next_depth_]) {
    ++next_depth_;
    passed = true;
  }
  return passed;
}

void PhaseRunner::take_snapshot(double time) {
  for (RunObserver* observer : observers_) {
    observer->snapshot_due(time);
  }
  last_snapshot_time_ = time;
}

void PhaseRunner::snapshot_now() {
  const double t = solver_.time();
  if (last_snapshot_time_ < t) {
    take_snapshot(t);
  }
}

void PhaseRunner::start() {
  const EnergyBalance energy = solver_.energy_balance();
  for (RunObserver* observer : observers_) {
    observer->row_due(0, energy);
  }
  take_snapshot(0.0);
  const double never = std::numeric_limits<double>::infinity();
  progress_.next_history_time = schedule_.history_interval;
  progress_.next_snapshot_time =
      schedule_.snapshot_interval > 0.0 ? schedule_.snapshot_interval : never;
  progress_.next_checkpoint_time =
      schedule_.checkpoint_interval > 0.0 ? schedule_.checkpoint_interval : never;
  const auto& listed = schedule_.snapshot_times;
  while (progress_.next_listed_snapshot < listed.size() &&
         listed[progress_.next_listed_snapshot] <= 0.0) {
    ++progress_.next_listed_snapshot;
  }
}

EnergyBalance PhaseRunner::record_row() {
  const EnergyBalance energy = solver_.energy_balance();
  for (RunObserver* observer : observers_) {
    observer->row_due(progress_.phase, energy);
  }
  recorded_step_ = solver_.step_count();
  final_residual_ = energy.relative_residual;
  return energy;
}

// The first row whose energy residual passes the case's warning threshold warns, once per run;
// a residual past the limit for blow_up_steps steps stops the run as unstable.
void PhaseRunner::check_energy_residual(const EnergyBalance& energy, bool recorded) {
  const SolverSettings& settings = solver_.settings();
  // The peak leaves out the start-up (see blow_up_steps), which would otherwise dominate it.
  if (recorded && solver_.step_count() >= blow_up_steps &&
      !(energy.relative_residual <= progress_.peak_residual)) {
    progress_.peak_residual = energy.relative_residual;
    progress_.peak_residual_time = solver_.time();
  }
  const bool over_limit = !(energy.relative_residual <= settings.energy_residual_limit);
  if (!over_limit) {
    over_limit_since_ = -1;
  } else if (over_limit_since_ < 0) {
    over_limit_since_ = solver_.step_count();
  }
  const bool blown_up = over_limit && solver_.step_count() - over_limit_since_ >= blow_up_steps;
  if (!blown_up && (!recorded || residual_warned_ ||
                    !(energy.relative_residual > settings.energy_residual_warning))) {
    return;
  }
  if (blown_up && !recorded) {
    record_row(); // the history ends on the step that stopped the run
  }
  std::ostringstream s;
  s << at_step(solver_.step_count(), solver_.time()) << "the energy residual is "
    << std::setprecision(3) << 100.0 * energy.relative_residual << " % of the energy in play ("
    << (blown_up ? "energy_residual_limit " : "energy_residual_warning ")
    << 100.0 * (blown_up ? settings.energy_residual_limit : settings.energy_residual_warning)
    << " %";
  if (blown_up) {
    s << " since step " << over_limit_since_;
  }
  s << "): external work " << energy.external_work << ", kinetic " << energy.kinetic << ", elastic "
    << energy.elastic << ", plastic " << energy.plastic << ", damping " << energy.damping
    << ", contact " << energy.contact << ", transfer " << energy.transfer << "; "
    << describe_kinetic_hotspot(solver_.scene(), settings.mass_scaling);
  if (blown_up) {
    throw SimulationError(s.str() + ": the run went unstable");
  }
  residual_warned_ = true;
  log_.warn(s.str() + " (see /energy in history.h5)");
}

// The outputs due after a step, in the order rows, snapshots, checkpoints.
void PhaseRunner::outputs_after_step() {
  const double t = solver_.time();
  const double dt = solver_.last_time_step();
  if (schedule_.history_interval == 0.0 || reached(t, progress_.next_history_time, dt)) {
    check_energy_residual(record_row(), true);
    if (schedule_.history_interval > 0.0) {
      progress_.next_history_time =
          next_due(progress_.next_history_time, schedule_.history_interval, t, dt);
    }
  } else if (solver_.step_count() % guard_steps == 0) {
    check_energy_residual(solver_.energy_balance(), false);
  }
  bool snapshot_due = reached(t, progress_.next_snapshot_time, dt);
  if (snapshot_due && schedule_.snapshot_interval > 0.0) {
    progress_.next_snapshot_time =
        next_due(progress_.next_snapshot_time, schedule_.snapshot_interval, t, dt);
  }
  const auto& listed = schedule_.snapshot_times;
  while (progress_.next_listed_snapshot < listed.size() &&
         reached(t, listed[progress_.next_listed_snapshot], dt)) {
    snapshot_due = true;
    ++progress_.next_listed_snapshot;
  }
  if (!schedule_.snapshot_penetrations.empty() && skip_reached_depths()) {
    snapshot_due = true;
  }
  if (snapshot_due) {
    take_snapshot(t);
  }
  if (reached(t, progress_.next_checkpoint_time, dt)) {
    if (schedule_.checkpoint_interval > 0.0) {
      progress_.next_checkpoint_time =
          next_due(progress_.next_checkpoint_time, schedule_.checkpoint_interval, t, dt);
    }
    for (RunObserver* observer : observers_) {
      observer->checkpoint_due();
    }
  }
}

PhaseGoal PhaseRunner::goal(const RunPhase& phase, double phase_end) const {
  PhaseGoal result = goal_of(phase, phase_end);
  result.ends_at_equilibrium = phase.equilibrium_tolerance.has_value();
  return result;
}

PhaseGoal PhaseRunner::goal_of(const RunPhase& phase, double phase_end) const {
  const double t = solver_.time();
  if (!phase.stop_at) {
    return {"t", t, phase_end, "s", t, phase_end};
  }
  const PenetrationStop& stop = *phase.stop_at;
  const double depth = penetration_of(rigid_body_named(solver_.scene(), stop.body));
  // A load test counts its settlement since the phase began, others the penetration.
  if (stop.settlement > 0.0) {
    return {"settlement",
            depth - progress_.phase_start_depths.at(progress_.phase),
            stop.settlement,
            "m",
            t,
            phase_end};
  }
  return {"penetration", depth, stop.penetration, "m", t, phase_end};
}

// Whether the phase ends after this step before its duration, and why.
bool PhaseRunner::ends_phase(const RunPhase& phase, const PhaseGoal& now,
                             const std::optional<EquilibriumMeasure>& equilibrium,
                             std::string& why) {
  if (equilibrium) {
    const EquilibriumMeasure& measure = *equilibrium;
    if (measure.reached) {
      std::ostringstream s;
      s << "at equilibrium (out-of-balance force ratio " << std::setprecision(3)
        << measure.force_ratio << ", kinetic energy / external work " << measure.kinetic_ratio
        << ")";
      why = s.str();
      return true;
    }
  }
  if (!phase.stop_at) {
    return false;
  }
  // The goal measures the stop: the penetration, or a load test's settlement since its start.
  const PenetrationStop& stop = *phase.stop_at;
  const RigidBody& pile = rigid_body_named(solver_.scene(), stop.body);
  const double depth = penetration_of(pile);
  const double speed = std::abs(pile.velocity[RIGID_Y]);
  const bool settles = stop.settlement > 0.0;
  const double measured = now.value;
  const double target = now.target;
  std::ostringstream s;
  s << std::setprecision(4);
  if (measured >= target && (!stop.at_rest || speed < rest_speed)) {
    s << "at " << stop.body << (settles ? " settlement " : " penetration ") << measured << " m";
    if (settles) {
      s << " (penetration " << depth << " m)";
    }
    why = s.str() + (stop.at_rest ? " and at rest" : "");
    return true;
  }
  // The band may not be carried past its travel: a load test ends there, short of its
  // settlement, and says so (a penetration stop beyond it is refused when read).
  const auto& moving_mesh = solver_.scene().moving_mesh;
  const double travel = moving_mesh ? moving_mesh->travel : 0.0;
  if (settles && travel > 0.0 && depth + speed * solver_.stable_time_step() >= travel) {
    s << "at the moving band's travel (" << travel << " m) with " << stop.body << " settlement "
      << measured << " m of " << stop.settlement;
    why = s.str();
    return true;
  }
  return false;
}

PhaseRunner::Outcome PhaseRunner::run(const PhaseSetUp& set_up, const StopRequest& stop) {
  long steps = 0;
  while (progress_.phase < phases_.size()) {
    const RunPhase& phase = phases_[progress_.phase];
    const double phase_end = progress_.phase_starts[progress_.phase] + phase.duration;
    const double start = progress_.phase_starts[progress_.phase];
    // A restarted run goes on with a phase that began earlier; a log read alone must not make it
    // look begun at the restart.
    log_.info("phase " + phase.name +
              (solver_.time() > start ? " resumed at t = " + format_time(solver_.time()) +
                                            " s (it began at t = " + format_time(start) + " s)"
                                      : " from t = " + format_time(solver_.time()) + " s"));
    for (RunObserver* observer : observers_) {
      observer->phase_started(progress_.phase, phase, progress_.phase_starts[progress_.phase]);
    }
    std::string ended = "after its duration";
    while (!reached(solver_.time(), phase_end, solver_.stable_time_step())) {
      // Steps land exactly on the phase end and on snapshot times, without a sliver step.
      double limit = std::min(phase_end, progress_.next_snapshot_time) - solver_.time();
      if (progress_.next_listed_snapshot < schedule_.snapshot_times.size()) {
        limit = std::min(limit,
                         schedule_.snapshot_times[progress_.next_listed_snapshot] - solver_.time());
      }
      solver_.step(landing_step(limit, solver_.stable_time_step()));
      ++steps; // every step counts, the one that ends a phase too
      outputs_after_step();
      PhaseGoal now = goal(phase, phase_end);
      // Equilibrium is measured before the observers are told of the step, so that the
      // progress line sees the criterion's trend.
      std::optional<EquilibriumMeasure> equilibrium;
      if (phase.equilibrium_tolerance && solver_.step_count() % equilibrium_steps == 0) {
        equilibrium = measure_equilibrium(solver_, *phase.equilibrium_tolerance);
        const double force = std::isnan(equilibrium->force_ratio) ? 0.0 : equilibrium->force_ratio;
        now.equilibrium =
            std::max(equilibrium->kinetic_ratio, force) / *phase.equilibrium_tolerance;
      }
      for (RunObserver* observer : observers_) {
        observer->stepped(phase, solver_.step_count(), now);
      }
      if (ends_phase(phase, now, equilibrium, ended)) {
        break;
      }
      if (stop(steps)) {
        return Outcome::interrupted;
      }
    }
    // The state a phase ends in (a target penetration, equilibrium) is always in the history.
    if (recorded_step_ != solver_.step_count()) {
      record_row();
    }
    snapshot_now();
    for (RunObserver* observer : observers_) {
      observer->phase_ended(progress_.phase, solver_.time(), ended);
    }
    log_.info("phase " + phase.name + " ended at t = " + format_time(solver_.time()) + " s " +
              ended + ", " + std::to_string(solver_.step_count()) + " steps so far");
    ++progress_.phase;
    if (progress_.phase < phases_.size()) {
      begin_phase(progress_, phases_, solver_.scene(), progress_.phase, solver_.time());
      set_up(progress_.phase, solver_.time());
      // A stop due on the step that ended the phase comes here, with the next phase set up.
      if (stop(steps)) {
        return Outcome::interrupted;
      }
    }
  }
  return Outcome::complete;
}

} // namespace mpile
