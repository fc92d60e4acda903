#include "app/run_continuation.hpp"

#include "cases/case_composition.hpp"
#include "cases/case_error.hpp"
#include "io/hdf5_file.hpp"

#include <filesystem>
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

/// "KEY changed (was A, now B)" from restart_changes' refusal, without its advice.
std::string what_changed(const std::string& refusal) {
  const auto start = refusal.find("with this case: ");
  const auto end = refusal.find("). ");
  if (start == std::string::npos || end == std::string::npos || end < start) {
    return refusal;
  }
  return refusal.substr(start + 16, end + 1 - (start + 16));
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
      const Hdf5File file(checkpoint.string(), Hdf5File::Mode::read);
      const auto phase = static_cast<std::size_t>(file.read_doubles("/run/counters").at(0));
      const std::vector<std::string> changed = restart_changes(
          file.string_attribute("/", "case_resolved"), resolved_case, phase, checkpoint.string());
      c.checkpoint = checkpoint.string();
      c.reason = "the run in " + directory + " stopped before its end (" + status +
                 "); its case differs in what a restart may change: " + joined(changed);
    } catch (const CaseError& e) {
      c.reason += " (" + what_changed(e.what()) + ")";
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
