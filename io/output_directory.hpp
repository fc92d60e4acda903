#pragma once

// The output directory of a run: one run at a time writes there, and a fresh run removes only
// what an earlier run wrote.

#include <stdexcept>
#include <string>

namespace mpile {

/// Another run holds the output directory's lock.
struct OutputBusy : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// An exclusive lock on a run's output directory (flock on `<directory>/.mpile.lock`), held while
/// the object lives and released by the system however the process ends, SIGKILL included.
class OutputLock {
public:
  /// Throws OutputBusy naming the directory when another run holds the lock, or
  /// std::runtime_error with the system's reason when the lock file cannot be made.
  explicit OutputLock(const std::string& directory);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

private:
  int descriptor_ = -1;
};

/// Removes the outputs of an earlier run from `directory`: the snapshot files its `particles.pvd`
/// and `grid.pvd` list (plain file names only), those indexes, `history.h5`, `checkpoint.h5` and
/// `run.log`.
/// Any other file, a user's `particles_notes.txt` included, stays. Throws std::runtime_error
/// naming the file and the system's reason when one cannot be removed.
void remove_earlier_outputs(const std::string& directory);

} // namespace mpile
