#pragma once

#include <chrono>

namespace mpile {

/// Adds the wall time from its making to its end to a pass's total (PassTimings).
class PassTimer {
public:
  explicit PassTimer(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~PassTimer() {
    total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

} // namespace mpile
