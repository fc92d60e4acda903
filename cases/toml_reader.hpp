#pragma once

// A strict reader over one TOML table: every key must be read (unknown keys are errors), every
// value must have the expected type, and every error names the file, line and dotted key.
// A table of the case format carries its declaration (cases/case_format.hpp): an absent key then
// takes its declared default, a value outside its declared range or choices is refused, and
// reading a key the declaration lacks is a programming error (std::logic_error).

#include "cases/case_error.hpp"
#include "cases/case_format.hpp"

#include <toml.hpp>

#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

namespace mpile {

using TomlValue = toml::basic_value<toml::discard_comments, std::map, std::vector>;

class TomlTable {
public:
  TomlTable(const TomlValue& table, std::string path, std::string file,
            const TableSpec* spec = nullptr);

  bool has(const std::string& key) const;
  const TomlValue& raw(const std::string& key); // marks the key as read

  double number(const std::string& key); // integers are accepted as numbers
  std::optional<double> optional_number(const std::string& key);
  double number_or(const std::string& key, double fallback);
  long integer(const std::string& key);
  long integer_or(const std::string& key, long fallback);
  std::string string(const std::string& key);
  std::string string_or(const std::string& key, const std::string& fallback);
  /// A file or directory name: a string without a NUL character (the system reads a path only up
  /// to it: "x.toml\u0000junk" named x.toml).
  std::string path(const std::string& key);
  std::string path_or(const std::string& key, const std::string& fallback);
  /// The check path() makes, for a path a bound key has read.
  void check_path(const std::string& key, const std::string& x) const;
  template <class Target = void, class T, class Owner>
  void check_path(T Owner::*member, const std::string& x) const {
    check_path(key_of<Target>(member), x);
  }
  bool boolean(const std::string& key);
  bool boolean_or(const std::string& key, bool fallback);
  std::vector<double> numbers(const std::string& key, std::size_t expected_size = 0);
  std::vector<double> numbers_or(const std::string& key, std::vector<double> fallback);
  /// A non-empty array of rows of `columns` numbers each ([[t0, v0], [t1, v1]]), integers read as
  /// doubles; nullopt for any other value, for the caller to refuse with the form it expects.
  std::optional<std::vector<std::vector<double>>> number_rows(const std::string& key,
                                                              std::size_t columns);
  TomlTable table(const std::string& key);
  std::optional<TomlTable> optional_table(const std::string& key);
  std::vector<TomlTable> tables(const std::string& key); // array of tables; empty when absent
  /// Names and tables of a table of tables ([materials.soil], [materials.steel], ...).
  std::vector<std::pair<std::string, TomlTable>> named_tables(const std::string& key);

  /// Reads every key of this table bound to a member of Spec (KeySpec::into) that the table
  /// holds; an absent one keeps the member's initialiser, its declared default, and an absent
  /// required one is refused.
  template <class Spec> void read_into(Spec& target);
  /// Reads the keys bound to these members of Spec alone, as a table whose keys depend on another
  /// key's value does (a time function's on its type): the others stay unread, for finish() to
  /// refuse; a listed key that is absent and has no declared default is missing.
  template <class Spec, class T>
  void read_members(Spec& target, std::initializer_list<T Spec::*> members);
  /// The key bound to a member of Spec (KeySpec::into), as the declaration names it: a check
  /// between keys names it so, not by a second spelling. `Target` as for KeySpec::into.
  template <class Target = void, class T, class Owner>
  const std::string& key_of(T Owner::*member) const;
  template <class Target = void, class T, class Owner> bool has(T Owner::*member) const {
    return has(key_of<Target>(member));
  }
  template <class Target = void, class T, class Owner>
  [[noreturn]] void fail(T Owner::*member, const std::string& message) const {
    fail(key_of<Target>(member), message);
  }

  /// Throws for any key that was not read.
  void finish() const;
  /// The keys this table's declaration holds (none for an undeclared table).
  std::span<const KeySpec> declared_keys() const;

  /// "file:line: key: message" for a key of this table (the table's line when the key is absent).
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  /// A required key is absent: when the table holds an unread key it does not declare, spelled
  /// within two edits of it, that key is the error (a typo reported as the key it was meant to be
  /// would point at the wrong line); otherwise "missing (required)", followed by `what` when given.
  [[noreturn]] void missing(const std::string& key, const std::string& what = "") const;
  /// Of a key a check between keys refuses and the keys it compares it with, the one to blame: the
  /// one written nearest the user (a --set, then this case file, then a base file, then a default
  /// left unwritten), `key` on a tie. A value in a base is rarely the slip: `diameter = 746` over a
  /// base's soil_width is refused by soil_width's check, and is the key to name.
  std::string nearest_key(const std::string& key, const std::vector<std::string>& with) const;
  /// A key's value as a message quotes the other side of a check: "5.0 at base.toml:32", or
  /// "0.2, its default" when the table does not hold it.
  std::string value_and_place(const std::string& key) const;
  std::string key_path(const std::string& key) const;
  int line_of(const std::string& key) const;
  /// The file a key's value came from (a base case file, or "--set ..."), else this table's file.
  std::string file_of(const std::string& key) const;
  /// Where a key's value was written, as a message quotes it: "case.toml:12".
  std::string location(const std::string& key) const;
  const std::string& file() const { return file_; }
  /// The declaration this table is read against, or nullptr.
  const TableSpec* spec() const { return spec_; }

  /// Checks of a number just read; fail with the reason otherwise.
  double positive(const std::string& key);

private:
  const std::string& bound_key(const std::type_info& spec, std::ptrdiff_t offset) const;
  const TomlValue& value(const std::string& key);
  [[noreturn]] void type_error(const std::string& key, const std::string& expected) const;
  /// The key's declaration (nullptr for a table without one, or a material's parameter); throws
  /// std::logic_error for a key the declaration lacks.
  const KeySpec* declared(const std::string& key) const;
  /// The declaration of the table held under `key` (`star`: the tables are named by the user).
  const TableSpec* child_spec(const std::string& key, bool star = false) const;
  /// A caller's fallback for a key whose default is declared would be a second declaration.
  void refuse_second_default(const std::string& key) const;
  void check_range(const std::string& key, double x, bool integer) const;
  void check_choice(const std::string& key, const std::string& x) const;

  const TomlValue* table_;
  std::string path_;
  std::string file_;
  const TableSpec* spec_ = nullptr;
  std::set<std::string> read_;
};

template <class Spec> void TomlTable::read_into(Spec& target) {
  for (const KeySpec& key : declared_keys()) {
    // A required key is read absent too, to be refused as missing; an absent key with a declared
    // default takes it.
    if (key.bound_to != nullptr && *key.bound_to == typeid(Spec) &&
        (has(key.name) || key.required || !std::holds_alternative<std::monostate>(key.fallback))) {
      key.store(*this, key.name, &target);
    }
  }
}

template <class Spec, class T>
void TomlTable::read_members(Spec& target, std::initializer_list<T Spec::*> members) {
  for (T Spec::*member : members) {
    const KeySpec& k = *spec_->key(key_of<Spec>(member));
    if (!has(k.name) && std::holds_alternative<std::monostate>(k.fallback)) {
      missing(k.name);
    }
    k.store(*this, k.name, &target);
  }
}

template <class Target, class T, class Owner>
const std::string& TomlTable::key_of(T Owner::*member) const {
  using Spec = std::conditional_t<std::is_void_v<Target>, Owner, Target>;
  return bound_key(typeid(Spec), member_offset<Spec>(member));
}

/// A TOML float or integer as a double (the caller has checked it is one of them).
double as_number(const TomlValue& v);

/// A number as a message quotes it (six significant digits).
std::string format_number(double x);

/// The deepest nesting of arrays and inline tables, and the most parts of a dotted key (a.b.c has
/// three), that a case may hold: beyond them the parser overflows its stack or takes minutes.
constexpr int max_toml_depth = 64;
constexpr std::size_t max_key_parts = 64;

/// The start of an overlong dotted key for a message: its first 40 characters, cut after a part,
/// then "...".
std::string key_excerpt(const std::string& key);

/// Parses TOML text; syntax errors become CaseError with the parser's own location, and text past
/// the bounds above (or with lines over 16 384 characters) is refused before the parser sees it.
TomlValue parse_toml(const std::string& text, const std::string& file);

/// Levenshtein distance (insertions, deletions, substitutions): how near a misspelt name is.
std::size_t edit_distance(const std::string& a, const std::string& b);

} // namespace mpile
