#include "solver/run_log.hpp"

#include <iomanip>
#include <ostream>
#include <sstream>

namespace mpile {

std::string format_time(double t) {
  std::ostringstream s;
  s << std::setprecision(6) << t;
  return s.str();
}

std::string at_step(long step, double time) {
  return "step " + std::to_string(step) + ", t = " + format_time(time) + " s: ";
}

void RunLog::write(const std::string& line) {
  if (stream_ != nullptr) {
    *stream_ << line << '\n';
  }
  if (file_ != nullptr) {
    *file_ << line << std::endl;
  }
}

void RunLog::info(const std::string& message) {
  write(message);
}

void RunLog::warn(const std::string& message) {
  warnings_.push_back(message);
  write("warning: " + message);
}

} // namespace mpile
