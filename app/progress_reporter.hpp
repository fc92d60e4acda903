#pragma once

#include "solver/run_phase.hpp"

#include <chrono>
#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>

namespace mpile {

/// The run's progress for the user: on a terminal, one line rewritten in place (the phase's goal
/// and how far it is, steps per second, ETA); otherwise a log line every few seconds. The ETA is
/// the phase's: the remaining distance to its goal over the rate at which the goal's quantity has
/// moved since the phase began, and no later than its end time at the rate simulated time moves.
class ProgressReporter {
public:
  /// seconds: the wall clock (steady, in seconds); a test passes its own.
  ProgressReporter(std::ostream& stream, bool terminal,
                   std::function<double()> seconds = steady_seconds);
  void update(const std::string& phase, long steps, const PhaseGoal& goal);
  void finish();

  /// The ETA of a phase in seconds of wall time, from the goal's values at the phase's start and
  /// now and the wall time between them; infinity while nothing has moved.
  static double eta(const PhaseGoal& start, const PhaseGoal& now, double elapsed);

private:
  static double steady_seconds();

  std::ostream& stream_;
  bool terminal_;
  std::function<double()> seconds_;
  double last_ = 0.0;
  std::string phase_;
  PhaseGoal phase_start_;
  double phase_start_seconds_ = 0.0;
  long phase_start_steps_ = 0;
  bool shown_ = false;
};

} // namespace mpile
