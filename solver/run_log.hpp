#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace mpile {

/// Messages of a run for the user: information and warnings, written to a stream (or nowhere) and
/// kept, so that tests and the command line can see what was said.
class RunLog {
public:
  explicit RunLog(std::ostream* stream = nullptr) : stream_(stream) {}
  void info(const std::string& message);
  void warn(const std::string& message);
  const std::vector<std::string>& warnings() const { return warnings_; }

private:
  std::ostream* stream_;
  std::vector<std::string> warnings_;
};

} // namespace mpile
