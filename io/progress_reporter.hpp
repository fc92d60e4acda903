#pragma once

#include <chrono>
#include <iosfwd>
#include <string>

namespace mpile {

/// The run's progress for the user: on a terminal, one line rewritten in place (simulated time,
/// phase, steps per second, ETA); otherwise a log line every few seconds.
class ProgressReporter {
public:
  ProgressReporter(std::ostream& stream, bool terminal, double end_time);
  void update(const std::string& phase, double time, long steps);
  void finish();

private:
  std::ostream& stream_;
  bool terminal_;
  double end_time_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_;
  long first_steps_ = -1;
  double first_time_ = 0.0;
  bool shown_ = false;
};

} // namespace mpile
