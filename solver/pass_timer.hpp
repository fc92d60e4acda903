#pragma once

#include <chrono>

namespace mpile {

/// Wall time spent in each pass since the solver was made (s).
struct PassTimings {
  double binning = 0.0;
  double particle_to_grid = 0.0;
  double grid_update = 0.0;
  double grid_to_particle = 0.0;
  double momentum_remap = 0.0;
  double stress_update = 0.0;
  double contact = 0.0; // contact and rigid bodies (scenes with contact only)
};

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
