#pragma once

// The element-test file (docs/element-tests.md): read strictly like a case file, and the CSV the
// results are written to.

#include "solver/element_test.hpp"

#include <iosfwd>
#include <string>

namespace mpile {

/// Reads an element-test file; every mistake is a CaseError "file:line: key: reason".
ElementTestSpec read_element_test_text(const std::string& text, const std::string& file);
ElementTestSpec read_element_test_file(const std::string& path);

/// The table as CSV: a header of column names, then one row per increment, each number in the
/// shortest form that reads back to the same double.
void write_csv(const ElementTestTable& table, std::ostream& out);

} // namespace mpile
