#pragma once

// The run time of a case estimated from a short pilot run of it: each phase the pilot finished is
// measured; the phase it stopped in is extrapolated in its own terms (the rate its penetration
// moved, or simulated time to its end) at the wall time per simulated second it ran at, as a range
// where the pile gathers speed (the progress line's estimator, fed the pilot's rows); later
// phases are bounded by their durations at that rate.

#include "cases/case_spec.hpp"

#include <map>
#include <string>
#include <vector>

namespace mpile {

/// The history rows of a pilot run.
struct PilotRecord {
  std::vector<double> time;                               // s
  std::vector<double> phase;                              // index
  std::vector<double> wall;                               // s of wall time since the pilot began
  std::vector<double> step;                               // the solver's step count
  std::map<std::string, std::vector<double>> penetration; // m, per rigid body
  bool complete = false;                                  // the pilot ran the whole case
};

struct PhaseEstimate {
  std::string name;
  double wall = 0.0;  // s; with a range, its upper end (the pile at its present speed)
  double low = 0.0;   // s; below `wall` where the pile gathers speed (if it keeps accelerating)
  bool bound = false; // the phase's duration at the measured rate: it may well end sooner
  std::string basis;  // how the figure was found, for the user
};

std::vector<PhaseEstimate> estimate_phases(const CaseSpec& spec, const PilotRecord& pilot);

/// Reads a pilot's history.h5 (the penetration of every rigid body the phases stop on).
PilotRecord read_pilot(const std::string& history, const CaseSpec& spec);

} // namespace mpile
