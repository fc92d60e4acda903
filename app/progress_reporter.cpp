#include "app/progress_reporter.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>

namespace mpile {

double ProgressReporter::steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

ProgressReporter::ProgressReporter(std::ostream& stream, bool terminal,
                                   std::function<double()> seconds)
    : stream_(stream), terminal_(terminal), seconds_(std::move(seconds)), last_(seconds_()) {}

void ProgressReporter::update(const std::string& phase, long steps, const PhaseGoal& goal) {
  const double now = seconds_();
  estimator_.observe(phase, steps, goal, now);
  if (phase != phase_) {
    phase_ = phase;
    phase_start_seconds_ = now;
    phase_start_steps_ = steps;
    equilibrium_ = std::numeric_limits<double>::quiet_NaN();
  }
  if (!std::isnan(goal.equilibrium)) {
    equilibrium_ = goal.equilibrium;
  }
  if (now - last_ < (terminal_ ? 0.25 : 5.0)) {
    return;
  }
  last_ = now;
  const double elapsed = now - phase_start_seconds_;
  const double rate =
      elapsed > 0.0 ? static_cast<double>(steps - phase_start_steps_) / elapsed : 0.0;
  std::ostringstream line;
  if (goal.ends_at_equilibrium && !std::isnan(equilibrium_)) {
    // What ends the phase is the criterion, not its time limit: how far from it the state is.
    line << "out of balance = " << std::setprecision(3) << equilibrium_
         << " x tolerance (1 ends the phase)";
  } else {
    line << goal.quantity << " = " << std::setprecision(5) << goal.value << " of " << goal.target
         << " " << goal.unit;
  }
  line << "  [" << phase << "]  " << std::fixed << std::setprecision(0) << rate << " steps/s  "
       << format_eta(estimator_.estimate());
  if (terminal_) {
    stream_ << '\r' << line.str() << "\x1b[K" << std::flush;
    shown_ = true;
  } else {
    stream_ << line.str() << '\n' << std::flush;
  }
}

void ProgressReporter::finish() {
  if (terminal_ && shown_) {
    stream_ << '\r' << "\x1b[K" << std::flush;
  }
}

} // namespace mpile
