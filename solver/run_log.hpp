#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace mpile {

/// A simulated time as the run's messages give it (6 significant digits).
std::string format_time(double t);
/// "step N, t = T s: ", the prefix of every message about a step (errors and warnings).
std::string at_step(long step, double time);

/// Messages of a run for the user: information and warnings, written to a stream (or nowhere) and
/// kept, so that tests and the command line can see what was said.
class RunLog {
public:
  explicit RunLog(std::ostream* stream = nullptr) : stream_(stream) {}
  /// Every later message also goes to `file` (flushed line by line, so that a run killed keeps
  /// what it said), for a run's log in its output directory.
  void also_to(std::ostream* file) { file_ = file; }
  void info(const std::string& message);
  void warn(const std::string& message);
  const std::vector<std::string>& warnings() const { return warnings_; }

private:
  void write(const std::string& line);

  std::ostream* stream_;
  std::ostream* file_ = nullptr;
  std::vector<std::string> warnings_;
};

} // namespace mpile
