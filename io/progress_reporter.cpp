#include "io/progress_reporter.hpp"

#include <iomanip>
#include <ostream>
#include <sstream>

namespace mpile {

ProgressReporter::ProgressReporter(std::ostream& stream, bool terminal, double end_time)
    : stream_(stream), terminal_(terminal), end_time_(end_time),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

void ProgressReporter::update(const std::string& phase, double time, long steps) {
  const auto now = std::chrono::steady_clock::now();
  if (first_steps_ < 0) {
    first_steps_ = steps;
    first_time_ = time;
  }
  const double since_last = std::chrono::duration<double>(now - last_).count();
  if (since_last < (terminal_ ? 0.25 : 5.0)) {
    return;
  }
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = static_cast<double>(steps - first_steps_) / elapsed;
  const double simulated_rate = (time - first_time_) / elapsed;
  const double eta = simulated_rate > 0.0 ? (end_time_ - time) / simulated_rate : 0.0;
  std::ostringstream line;
  line << "t = " << std::setprecision(5) << time << " s of " << end_time_ << " s  [" << phase
       << "]  " << std::fixed << std::setprecision(0) << rate << " steps/s  ETA "
       << std::setprecision(0) << eta << " s";
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
