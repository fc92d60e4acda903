#pragma once

// `mpile element-test FILE`: reads the file, runs the path, writes the CSV and a summary.

#include <iosfwd>
#include <string>

namespace mpile {

struct ElementTestOptions {
  std::string file;
  std::string csv; // empty: out/<file stem>.csv
};

/// `mpile element-test`: reads the file, runs the path, writes the CSV. Returns an ExitStatus:
/// 2 for a bad file (with file:line: key: reason), 1 when the path cannot be followed.
int element_test_command(const ElementTestOptions& options, std::ostream& out, std::ostream& err);

} // namespace mpile
