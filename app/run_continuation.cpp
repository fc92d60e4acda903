#include "app/run_continuation.hpp"

#include "cases/case_composition.hpp"
#include "io/checkpoint.hpp"
#include "io/hdf5_file.hpp"

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <vector>

namespace mpile {

namespace {

std::string joined(const std::vector<std::string>& keys) {
  std::string text;
  for (const std::string& key : keys) {
    text += (text.empty() ? "" : ", ") + key;
  }
  return text;
}

} // namespace

Continuation find_continuation(const std::string& directory, const std::string& resolved_case) {
  namespace fs = std::filesystem;
  const fs::path history = fs::path(directory) / "history.h5";
  const fs::path checkpoint = fs::path(directory) / "checkpoint.h5";
  Continuation c;
  if (!fs::is_regular_file(history)) {
    c.reason = "no earlier run in " + directory;
    return c;
  }
  std::string status, resolved;
  try {
    const Hdf5File file(history.string(), Hdf5File::Mode::read);
    status = file.string_attribute("/", "status");
    resolved = file.string_attribute("/", "case_resolved");
  } catch (const std::exception& e) {
    c.reason = history.string() + " cannot be read (" + e.what() + ")";
    return c;
  }
  const bool stopped = status.starts_with("interrupted") || status == "running";
  if (resolved != resolved_case) {
    // Another case, or other --set values. A stopped run whose case changed only in what a
    // restart may change (later end criteria, the settings of phases not begun) continues: the
    // state it reached is this case's too. Anything else is not this run's state.
    c.reason = history.string() + " holds a run of another case or other values";
    if (!stopped || !fs::is_regular_file(checkpoint)) {
      return c;
    }
    try {
      const std::optional<CheckpointCase> stored = checkpoint_case(checkpoint.string());
      if (!stored) {
        return c;
      }
      const RestartCheck check =
          check_restart(stored->resolved, resolved_case, stored->phase, checkpoint.string());
      if (!check.refused.empty()) {
        c.reason += " (" + check.refused + ")";
        return c;
      }
      c.checkpoint = checkpoint.string();
      c.reason = "the run in " + directory + " stopped before its end (" + status +
                 "); its case differs in what a restart may change: " + joined(check.changed);
    } catch (const std::exception& e) {
      c.reason += " (its checkpoint cannot be read: " + std::string(e.what()) + ")";
    }
    return c;
  }
  if (status.starts_with("complete")) {
    c.complete = true;
    c.reason = history.string() + " holds this case's complete run";
    return c;
  }
  if (stopped && fs::is_regular_file(checkpoint)) {
    c.checkpoint = checkpoint.string();
    c.reason = "the run in " + directory + " stopped before its end (" + status + ")";
    return c;
  }
  c.reason = stopped ? "the run in " + directory + " stopped before its first checkpoint"
                     : "the run in " + directory + " ended without finishing (" + status + ")";
  return c;
}

} // namespace mpile
