#include "app/run_continuation.hpp"

#include "io/hdf5_file.hpp"

#include <filesystem>
#include <stdexcept>

namespace mpile {

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
  if (resolved != resolved_case) {
    // Another case, or other --set values: its state is not this run's (a restart with changed
    // end criteria is --restart's, which says what it accepts).
    c.reason = history.string() + " holds a run of another case or other values";
    return c;
  }
  if (status.starts_with("complete")) {
    c.complete = true;
    c.reason = history.string() + " holds this case's complete run";
    return c;
  }
  const bool stopped = status.starts_with("interrupted") || status == "running";
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
