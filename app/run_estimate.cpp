#include "app/run_estimate.hpp"

#include "app/progress_estimate.hpp"
#include "io/hdf5_file.hpp"
#include "io/history_writer.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

namespace mpile {

namespace {

/// The longest period among the drives of a rigid body, if any is periodic.
std::optional<double> drive_period(const CaseSpec& spec, const std::string& body) {
  std::optional<double> longest;
  for (const BodySpec& b : spec.bodies) {
    if (b.name != body || !b.rigid) {
      continue;
    }
    for (const std::optional<RigidDrive>& drive : b.rigid->drive) {
      if (drive) {
        if (const std::optional<double> period = drive->function.period()) {
          longest = std::max(longest.value_or(0.0), *period);
        }
      }
    }
  }
  return longest;
}

/// What the progress line's estimator makes of the pilot's rows up to the end of phase
/// `phase` (wall seconds left in it), given its stop at a penetration.
EtaEstimate progress_estimate(const CaseSpec& spec, const PilotRecord& pilot, std::size_t phase,
                              double phase_start_time) {
  ProgressEstimator estimator;
  const PhaseSpec& spec_phase = spec.phases[phase];
  const std::vector<double>& p = pilot.penetration.at(spec_phase.stop_at->body);
  for (std::size_t r = 0; r < pilot.time.size(); ++r) {
    const auto in = static_cast<std::size_t>(pilot.phase[r]);
    PhaseGoal goal;
    goal.time = pilot.time[r];
    if (in == phase) {
      goal.quantity = "penetration";
      goal.unit = "m";
      goal.value = p[r];
      goal.target = spec_phase.stop_at->penetration;
      goal.end_time = phase_start_time + spec_phase.duration;
    } else {
      goal.end_time = pilot.time[r]; // only its rate matters, for the phase after it
    }
    const long steps = pilot.step.empty() ? static_cast<long>(r) : static_cast<long>(pilot.step[r]);
    estimator.observe(spec.phases[in].name, steps, goal, pilot.wall[r]);
  }
  return estimator.estimate();
}

} // namespace

std::vector<PhaseEstimate> estimate_phases(const CaseSpec& spec, const PilotRecord& pilot) {
  std::vector<PhaseEstimate> estimates;
  const std::size_t rows = pilot.time.size();
  if (rows < 2) {
    return estimates;
  }
  const auto last_phase = static_cast<std::size_t>(pilot.phase.back());
  // Rows of phase i: [first, end).
  auto rows_of = [&](std::size_t i) {
    std::size_t first = rows, end = 0;
    for (std::size_t r = 0; r < rows; ++r) {
      if (static_cast<std::size_t>(pilot.phase[r]) == i) {
        first = std::min(first, r);
        end = r + 1;
      }
    }
    return std::pair{first, end};
  };
  // Wall time per simulated second, where the pilot stopped (the phase's own settings, such as
  // mass scaling, set it), else over the whole pilot.
  auto [first, end] = rows_of(last_phase);
  const auto per_second = [&](std::size_t a, std::size_t b) {
    const double dt = pilot.time[b - 1] - pilot.time[a];
    return dt > 0.0 ? (pilot.wall[b - 1] - pilot.wall[a]) / dt : 0.0;
  };
  double wall_per_second = end - first >= 2 ? per_second(first, end) : 0.0;
  if (!(wall_per_second > 0.0)) {
    wall_per_second = per_second(0, rows);
  }
  double phase_start_wall = 0.0;
  double phase_start_time = 0.0;
  for (std::size_t i = 0; i < spec.phases.size(); ++i) {
    const PhaseSpec& phase = spec.phases[i];
    PhaseEstimate e;
    e.name = phase.name;
    std::ostringstream basis;
    basis << std::setprecision(3);
    if (i < last_phase || (i == last_phase && pilot.complete)) {
      const auto [a, b] = rows_of(i);
      e.wall = pilot.wall[b - 1] - phase_start_wall;
      basis << "measured in the pilot (" << pilot.time[b - 1] - phase_start_time << " s simulated)";
      phase_start_wall = pilot.wall[b - 1];
      phase_start_time = pilot.time[b - 1];
    } else if (i == last_phase) {
      const auto [a, b] = rows_of(i);
      const double now = pilot.time[b - 1];
      const double to_end = std::max(phase_start_time + phase.duration - now, 0.0);
      double remaining = to_end; // at the pile's present speed
      double sooner = to_end;    // if it keeps gathering speed
      double later = to_end;     // at its mean speed since the phase began
      e.bound = true;
      basis << "at most its duration";
      if (phase.stop_at && pilot.penetration.count(phase.stop_at->body) > 0 && b - a >= 2) {
        const std::vector<double>& p = pilot.penetration.at(phase.stop_at->body);
        const double into_phase = now - pilot.time[a];
        // A periodic drive (a torque's cycle, the interval between blows) moves the pile in
        // spurts: its rate means something only over whole periods. Otherwise the rate over the
        // later half of the phase's rows: the pile's present speed.
        const std::optional<double> period = drive_period(spec, phase.stop_at->body);
        double window = 0.5 * into_phase;
        if (period) {
          const double periods = std::floor(0.5 * into_phase / *period);
          window = std::max(periods, into_phase >= *period ? 1.0 : 0.0) * *period;
        }
        const bool within_first_period = period && window == 0.0;
        if (within_first_period) {
          window = into_phase; // the rate so far: right if the pile gets there in this period
        }
        std::size_t m = a;
        while (m + 2 < b && pilot.time[m] < now - window) {
          ++m;
        }
        const double rate = (p[b - 1] - p[m]) / (pilot.time[b - 1] - pilot.time[m]);
        const double left = std::max(phase.stop_at->penetration - p[b - 1], 0.0);
        if (rate > 0.0) {
          remaining = std::min(left / rate, to_end);
          sooner = later = remaining;
          e.bound = false;
          basis.str("");
          basis << "from its penetration rate over the pilot's last " << window << " s, " << rate
                << " m/s to " << phase.stop_at->penetration << " m";
          // A pile that has gathered speed may keep gathering it (the progress line's estimator
          // fits its acceleration over the later half of the phase; a periodic drive's spurts
          // need a whole period in that half) or slow again as the soil's grip grows with depth
          // (gdp_quick's pile: 0.75 m/s at 0.05 s, 0.5 m/s at 0.17 s): the range runs from the
          // first to the pile at its mean speed since the phase began.
          const double whole = period && into_phase >= *period
                                   ? std::floor(into_phase / *period) * *period
                                   : into_phase; // whole periods again
          std::size_t f = a;
          while (f + 2 < b && pilot.time[f] < now - whole) {
            ++f;
          }
          const double mean = (p[b - 1] - p[f]) / (now - pilot.time[f]);
          if (mean > 0.0 && mean < rate) {
            later = std::min(left / mean, to_end);
            basis << " (" << mean << " m/s since the phase began)";
          }
          if (!period || 0.5 * into_phase >= *period) {
            const EtaEstimate eta = progress_estimate(spec, pilot, i, phase_start_time);
            if (eta.known && !eta.bound && wall_per_second > 0.0) {
              sooner = std::min(remaining, eta.low / wall_per_second);
            }
          }
        }
        if (within_first_period) {
          // How long a pilot must run to see one whole period of the drive.
          const double one_period = pilot.wall[a] + (pilot.wall[b - 1] - pilot.wall[a]) * *period /
                                                        std::max(into_phase, 1e-300);
          basis << (rate > 0.0 ? "; " : " (") << "the pilot ran " << into_phase
                << " s of its drive's period of " << *period
                << " s: longer if the pile does not get there within this period; --pilot "
                << std::ceil(1.2 * one_period) << " or more covers one period"
                << (rate > 0.0 ? "" : ")");
        }
      } else if (!phase.stop_at && !phase.equilibrium_tolerance) {
        e.bound = false;
        basis.str("");
        basis << "its duration";
      }
      const double spent = pilot.wall[b - 1] - phase_start_wall;
      e.wall = spent + std::max(remaining, later) * wall_per_second;
      e.low = spent + std::min(remaining, sooner) * wall_per_second;
      phase_start_time += phase.duration; // at the latest; only phases after it use this
    } else {
      e.wall = phase.duration * wall_per_second;
      e.bound = phase.stop_at.has_value() || phase.equilibrium_tolerance.has_value();
      basis << (e.bound ? "at most its duration" : "its duration")
            << ", at the pilot's wall time per simulated second";
    }
    e.basis = basis.str();
    if (!(e.low > 0.0) || e.low > e.wall) {
      e.low = e.wall;
    }
    estimates.push_back(e);
  }
  return estimates;
}

PilotRecord read_pilot(const std::string& history, const CaseSpec& spec) {
  Hdf5File file(history, Hdf5File::Mode::read);
  PilotRecord pilot;
  pilot.time = file.read_doubles("/time");
  pilot.phase = file.read_doubles("/phase");
  pilot.wall = file.read_doubles("/wall_time");
  pilot.step = file.read_doubles("/step");
  for (const PhaseSpec& phase : spec.phases) {
    if (phase.stop_at && pilot.penetration.count(phase.stop_at->body) == 0) {
      pilot.penetration[phase.stop_at->body] =
          file.read_doubles("/bodies/" + dataset_name(phase.stop_at->body) + "/penetration");
    }
  }
  pilot.complete = file.string_attribute("/", "status").rfind("complete", 0) == 0;
  return pilot;
}

} // namespace mpile
