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

double ProgressReporter::eta(const PhaseGoal& start, const PhaseGoal& now, double elapsed) {
  const double infinity = std::numeric_limits<double>::infinity();
  if (!(elapsed > 0.0)) {
    return infinity;
  }
  auto remaining = [&](double from, double value, double target) {
    const double rate = (value - from) / elapsed;
    return rate > 0.0 ? std::max(target - value, 0.0) / rate : infinity;
  };
  // The goal's own rate, and simulated time to the phase's end as the bound it cannot pass.
  return std::min(remaining(start.value, now.value, now.target),
                  remaining(start.time, now.time, now.end_time));
}

void ProgressReporter::update(const std::string& phase, long steps, const PhaseGoal& goal) {
  const double now = seconds_();
  if (phase != phase_) {
    phase_ = phase;
    phase_start_ = goal;
    phase_start_seconds_ = now;
    phase_start_steps_ = steps;
  }
  if (now - last_ < (terminal_ ? 0.25 : 5.0)) {
    return;
  }
  last_ = now;
  const double elapsed = now - phase_start_seconds_;
  const double rate =
      elapsed > 0.0 ? static_cast<double>(steps - phase_start_steps_) / elapsed : 0.0;
  const double eta = ProgressReporter::eta(phase_start_, goal, elapsed);
  std::ostringstream line;
  line << goal.quantity << " = " << std::setprecision(5) << goal.value << " of " << goal.target
       << " " << goal.unit << "  [" << phase << "]  " << std::fixed << std::setprecision(0) << rate
       << " steps/s  ETA ";
  if (std::isfinite(eta)) {
    line << eta << " s";
  } else {
    line << "-";
  }
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
