#pragma once

#include "app/progress_estimate.hpp"
#include "solver/run_phase.hpp"

#include <chrono>
#include <functional>
#include <iosfwd>
#include <limits>
#include <string>
#include <string_view>

namespace mpile {

/// The run's progress for the user: on a terminal, one line rewritten in place (the phase's goal
/// and how far it is, steps per second, ETA); otherwise a log line every few seconds. The ETA is
/// the phase's, from what is known at the moment (ProgressEstimator): an estimate, a range while a
/// pile gathers speed, or, where nothing yet says when the phase's criterion ends it, the bound
/// its end time sets ("ETA <= 464 s").
class ProgressReporter {
public:
  /// seconds: the wall clock (steady, in seconds); a test passes its own.
  ProgressReporter(std::ostream& stream, bool terminal,
                   std::function<double()> seconds = steady_seconds);
  void update(const std::string& phase, long steps, const PhaseGoal& goal);
  void finish();

private:
  static double steady_seconds();

  std::ostream& stream_;
  bool terminal_;
  std::function<double()> seconds_;
  double last_ = 0.0;
  std::string phase_;
  ProgressEstimator estimator_;
  double phase_start_seconds_ = 0.0;
  long phase_start_steps_ = 0;
  bool shown_ = false;
  double equilibrium_ = std::numeric_limits<double>::quiet_NaN(); // the last ratio checked
};

} // namespace mpile
