#include "solver/run_log.hpp"

#include <ostream>

namespace mpile {

void RunLog::info(const std::string& message) {
  if (stream_ != nullptr) {
    *stream_ << message << '\n';
  }
}

void RunLog::warn(const std::string& message) {
  warnings_.push_back(message);
  if (stream_ != nullptr) {
    *stream_ << "warning: " << message << '\n';
  }
}

} // namespace mpile
