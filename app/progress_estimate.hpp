#pragma once

#include "solver/run_phase.hpp"

#include <string>
#include <vector>

namespace mpile {

/// The time a phase has left, in seconds of wall time: either one estimate (low == high), a range
/// (a pile still gathering speed: `low` if it keeps accelerating as now, `high` at its present
/// speed), or only a bound (`bound`: the phase's end time at the measured rate, which its
/// criterion may well end sooner). Nothing known: `known` false.
struct EtaEstimate {
  bool known = false;
  bool bound = false;
  double low = 0.0;
  double high = 0.0;
};

/// "ETA 12 s", "ETA 21 to 158 s", "ETA <= 464 s" or "ETA -".
std::string format_eta(const EtaEstimate& eta);

/// Estimates what is left of the phase a run is in from what is known at each moment: the rate at
/// which wall time buys simulated time, over the later half of the phase (from its first step,
/// the previous phase's wall time per step); the phase's goal (a penetration or settlement) fitted
/// over the later half of the phase in simulated time, its speed and acceleration now; and, with
/// an equilibrium criterion, the trend of its ratio over its last checks. A pure function of the
/// samples it is given: the caller passes the wall clock.
class ProgressEstimator {
public:
  void observe(const std::string& phase, long steps, const PhaseGoal& goal, double wall);
  EtaEstimate estimate() const;

private:
  struct Sample {
    double wall = 0.0;
    long steps = 0;
    double time = 0.0;
    double value = 0.0;
  };
  struct Check {
    long steps = 0;
    double log_ratio = 0.0;
  };
  /// Wall seconds per simulated second and per step over the later half of the phase, else the
  /// previous phase's; 0 where unknown.
  void rates(double& per_second, double& per_step) const;

  std::string phase_;
  PhaseGoal goal_;
  std::vector<Sample> samples_; // this phase's, thinned as they grow
  std::vector<Check> checks_;   // this phase's equilibrium checks, the last few
  double previous_per_step_ = 0.0;
  double previous_per_second_ = 0.0;
};

} // namespace mpile
