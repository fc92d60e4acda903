#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace mpile {

struct RunOptions {
  std::string case_path;
  std::string output_directory; // empty: the case's [output].directory, else out/<case stem>
  std::string restart;          // checkpoint to continue from
  /// --continue: continue the run in the output directory from its checkpoint if it stopped
  /// before its end, do nothing if it is complete, else start afresh (app/run_continuation.hpp).
  bool continue_run = false;
  std::vector<std::string> overrides; // --set key.path=value, applied over the case in order
  int threads = 0;
  /// Stop after this many steps as if interrupted (writing a checkpoint); 0: run to the end.
  long stop_after_steps = 0;
  /// Stop after this many seconds of wall time as if interrupted; 0: run to the end.
  double stop_after_seconds = 0.0;
  /// check: run the case for this many seconds of wall time and estimate its run time from it.
  double pilot_seconds = 0.0;
  /// --strict: a plausibility warning of units (cases/case_warnings.hpp) refuses the case (exit
  /// status 2) instead of being printed; notes on resolution are printed either way.
  bool strict = false;
  /// check --print-resolved: print the case as it runs (bases merged, --set applied) as TOML.
  bool print_resolved = false;
};

/// Exit statuses of the command line.
enum ExitStatus : int {
  exit_success = 0,
  exit_failure = 1,      // a run that went wrong (unstable, particle out of the grid, I/O error)
  exit_bad_input = 2,    // the case file or the command line is wrong
  exit_interrupted = 130 // stopped by SIGINT or SIGTERM, after writing a checkpoint (or before
                         // writing anything, when the signal came while the case was built)
};

/// `mpile run`: reads the case, runs its phases, writes history.h5, VTK snapshots and
/// checkpoints, and reports progress. Returns an ExitStatus.
int run_case(const RunOptions& options, std::ostream& out, std::ostream& err);

/// Called from a catch block around reading and building a case: writes why the case at
/// case_path cannot be run (a CaseError as it stands, as it names file, line and key; running out
/// of memory; anything else after the case's path) and returns exit_bad_input.
int refuse_case(std::ostream& err, const std::string& case_path);

/// `mpile check`: validates the case and prints the grid, particle counts, the time step, the
/// estimated number of steps, run time and memory. Returns an ExitStatus.
int check_case(const RunOptions& options, std::ostream& out, std::ostream& err);

} // namespace mpile
