#pragma once

// `mpile run --continue`: what the output directory holds decides whether the run starts afresh or
// continues from its checkpoint, so that a batch job or a sweep's variant can be resubmitted
// unchanged after an interruption, a time limit or a lost machine.

#include <string>

namespace mpile {

struct Continuation {
  std::string checkpoint; ///< the checkpoint to continue from; empty: start afresh
  bool complete = false;  ///< the directory holds this case's complete run: nothing to do
  std::string reason;     ///< what was found, for the run's log
};

/// Reads DIRECTORY/history.h5: a run of the same resolved case (its file, bases and --set values)
/// whose status is "interrupted ..." (a signal or --stop-after) or "running" (the process was
/// killed: its last checkpoint is the way back) continues from DIRECTORY/checkpoint.h5; one whose
/// status is "complete ..." leaves nothing to do; no run, an unreadable history, a failed run or
/// a run of another case or other values start afresh. A stopped run whose case differs only in
/// what `--restart` accepts (restart_changes: later end criteria, phases not begun) continues.
Continuation find_continuation(const std::string& directory, const std::string& resolved_case);

} // namespace mpile
