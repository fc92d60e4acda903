#pragma once

// A strict reader over one TOML table: every key must be read (unknown keys are errors), every
// value must have the expected type, and every error names the file, line and dotted key.

#include "io/case_error.hpp"

#include <toml.hpp>

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace mpile {

using TomlValue = toml::basic_value<toml::discard_comments, std::map, std::vector>;

class TomlTable {
public:
  TomlTable(const TomlValue& table, std::string path, std::string file);

  bool has(const std::string& key) const;
  const TomlValue& raw(const std::string& key); // marks the key as read

  double number(const std::string& key); // integers are accepted as numbers
  std::optional<double> optional_number(const std::string& key);
  double number_or(const std::string& key, double fallback);
  long integer(const std::string& key);
  long integer_or(const std::string& key, long fallback);
  std::string string(const std::string& key);
  std::string string_or(const std::string& key, const std::string& fallback);
  bool boolean_or(const std::string& key, bool fallback);
  std::vector<double> numbers(const std::string& key, std::size_t expected_size = 0);
  std::vector<double> numbers_or(const std::string& key, std::vector<double> fallback);
  TomlTable table(const std::string& key);
  std::optional<TomlTable> optional_table(const std::string& key);
  std::vector<TomlTable> tables(const std::string& key); // array of tables; empty when absent
  /// Names and tables of a table of tables ([materials.soil], [materials.steel], ...).
  std::vector<std::pair<std::string, TomlTable>> named_tables(const std::string& key);

  /// Throws for any key that was not read.
  void finish() const;

  /// "file:line: key: message" for a key of this table (the table's line when the key is absent).
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  /// A required key is absent: when the table holds an unread key spelled within two edits of it,
  /// that key is the error (a typo reported as the key it was meant to be would point at the wrong
  /// line); otherwise "missing (required)", followed by `what` when given.
  [[noreturn]] void missing(const std::string& key, const std::string& what = "") const;
  std::string key_path(const std::string& key) const;
  int line_of(const std::string& key) const;
  /// The file a key's value came from (a base case file, or "--set ..."), else this table's file.
  std::string file_of(const std::string& key) const;
  const std::string& file() const { return file_; }

  /// Checks of a number just read; fail with the reason otherwise.
  double positive(const std::string& key);
  double non_negative(const std::string& key);

private:
  const TomlValue& value(const std::string& key);
  [[noreturn]] void type_error(const std::string& key, const std::string& expected) const;

  const TomlValue* table_;
  std::string path_;
  std::string file_;
  std::set<std::string> read_;
};

/// Parses TOML text; syntax errors become CaseError with the parser's own location.
TomlValue parse_toml(const std::string& text, const std::string& file);

} // namespace mpile
