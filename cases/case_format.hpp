#pragma once

// The case format, declared once: every table a case file may hold and every key of it, with its
// type, unit, range, default and one line of meaning. The readers take defaults, ranges and choices
// from here (cases/toml_reader.hpp), `mpile describe` prints it, docs/case-format.md's key tables
// are generated from it and `mpile describe --json-schema` exports it for TOML editors. Checks that
// relate several keys (a body's material must exist, a band must lie on grid lines) stay in the
// readers, which name the key they refuse.

#include "engine/parameter_range.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <typeinfo>
#include <variant>
#include <vector>

namespace mpile {

enum class ValueKind {
  number,        // a float; integers are accepted
  integer,       // an integer
  boolean,       // true or false
  string,        // a string, possibly one of a list of choices
  numbers,       // an array of numbers, of a fixed length when `count` is set
  time_function, // a number (constant) or a table [time_function]
  table,         // a table, declared under its own path
  tables,        // an array of tables ([[path]]), declared under its own path
  named_tables,  // a table of tables named by the user ([path.<name>]), declared as path.*
  strings,       // an array of strings, each one of the choices
  any,           // a value whose forms the meaning lists (a number or a range, a string or a table)
};

/// The value a key takes when it is absent.
using DefaultValue = std::variant<std::monostate, double, long, bool, std::string>;

class TomlTable;
/// Reads a declared key into a field of its kind (cases/toml_reader.cpp), the range checked there.
void read_key(TomlTable& table, const std::string& key, double& field);
void read_key(TomlTable& table, const std::string& key, int& field);
void read_key(TomlTable& table, const std::string& key, long& field);
void read_key(TomlTable& table, const std::string& key, bool& field);
void read_key(TomlTable& table, const std::string& key, std::string& field);
void read_key(TomlTable& table, const std::string& key, std::optional<double>& field);
void read_key(TomlTable& table, const std::string& key, std::optional<int>& field);
void read_key(TomlTable& table, const std::string& key, std::optional<long>& field);
/// The index of a string key's value among its declared choices (KeySpec::choice_into).
long read_choice(TomlTable& table, const std::string& key);

/// Where a member lies in a default-constructed Spec: how a bound key is found by its member
/// (TomlTable::key_of).
template <class Spec, class T, class Owner> std::ptrdiff_t member_offset(T Owner::*member) {
  static const Spec probe{};
  return reinterpret_cast<const char*>(&(probe.*member)) - reinterpret_cast<const char*>(&probe);
}

struct KeySpec {
  std::string name;
  ValueKind kind = ValueKind::number;
  std::string unit;    // "" where no unit applies, "-" for a ratio
  std::string meaning; // one line
  bool required = false;
  DefaultValue fallback;            // std::monostate: none (required, or absent means "not set")
  std::string default_text;         // how the documentation names a default the reader computes
  ParameterRange range;             // numbers and integers
  std::vector<std::string> choices; // strings
  std::size_t count = 0;            // numbers: the exact length, 0 for any

  KeySpec needed() &&;
  KeySpec or_default(DefaultValue value) &&;
  KeySpec or_computed(std::string text) &&; // the reader derives the default from other keys
  KeySpec above(double value) &&;
  KeySpec at_least(double value) &&;
  KeySpec below(double value) &&;
  KeySpec at_most(double value) &&;
  KeySpec one_of(std::vector<std::string> values) &&;
  KeySpec length(std::size_t n) &&;
  /// Binds the key to a member of the struct its table is read into (TomlTable::read_into), whose
  /// initialiser is then its default unless the key is required or its default computed.
  /// `Target` names a struct that inherits the member (PhaseSpec's RunPhase::duration).
  template <class Target = void, class T, class Owner> KeySpec into(T Owner::*member) &&;
  /// Binds a string key of choices to a member that takes the index of the choice: an enum whose
  /// values are in the choices' order, an int, or a bool that is true for the choice `truth` (the
  /// second of two when not given).
  template <class Target = void, class T, class Owner>
  KeySpec choice_into(T Owner::*member, const std::string& truth = "") &&;

  /// The struct a bound key is read into (null: read by name), how, and the member's place in it.
  const std::type_info* bound_to = nullptr;
  std::function<void(TomlTable&, const std::string&, void*)> store;
  std::ptrdiff_t bound_offset = -1;

  /// "> 0", "in [0, 1)", "1 to 8", ... ; empty without bounds.
  std::string range_text() const { return range.text(kind == ValueKind::integer); }
  /// The default as the documentation writes it: a TOML value, the computed default's text, or
  /// "required" / "none".
  std::string default_description() const;
};

template <class Target, class T, class Owner> KeySpec KeySpec::into(T Owner::*member) && {
  using Spec = std::conditional_t<std::is_void_v<Target>, Owner, Target>;
  static_assert(std::is_base_of_v<Owner, Spec>);
  bound_to = &typeid(Spec);
  bound_offset = member_offset<Spec>(member);
  store = [member](TomlTable& table, const std::string& key, void* target) {
    read_key(table, key, static_cast<Spec*>(target)->*member);
  };
  constexpr bool optional = std::is_same_v<T, std::optional<double>> ||
                            std::is_same_v<T, std::optional<int>> ||
                            std::is_same_v<T, std::optional<long>>;
  if constexpr (!optional) {
    if (!required && default_text.empty() && std::holds_alternative<std::monostate>(fallback)) {
      const T value = Spec{}.*member;
      if constexpr (std::is_same_v<T, int>) {
        fallback = static_cast<long>(value);
      } else {
        fallback = value;
      }
    }
  }
  return std::move(*this);
}

template <class Target, class T, class Owner>
KeySpec KeySpec::choice_into(T Owner::*member, const std::string& truth) && {
  using Spec = std::conditional_t<std::is_void_v<Target>, Owner, Target>;
  static_assert(std::is_base_of_v<Owner, Spec>);
  bound_to = &typeid(Spec);
  bound_offset = member_offset<Spec>(member);
  long true_index = 1;
  if constexpr (std::is_same_v<T, bool>) {
    if (!truth.empty()) {
      true_index =
          static_cast<long>(std::find(choices.begin(), choices.end(), truth) - choices.begin());
    }
    if (choices.size() != 2 || true_index > 1) {
      throw std::logic_error("a switch between two choices, one of them " + truth);
    }
  }
  store = [member, true_index](TomlTable& table, const std::string& key, void* target) {
    const long index = read_choice(table, key);
    if constexpr (std::is_same_v<T, bool>) {
      static_cast<Spec*>(target)->*member = index == true_index;
    } else {
      static_cast<Spec*>(target)->*member = static_cast<T>(index);
    }
  };
  if (!required && default_text.empty() && std::holds_alternative<std::monostate>(fallback)) {
    const T value = Spec{}.*member;
    if constexpr (std::is_same_v<T, bool>) {
      fallback = choices.at(static_cast<std::size_t>(value ? true_index : 1 - true_index));
    } else {
      fallback = choices.at(static_cast<std::size_t>(value));
    }
  }
  return std::move(*this);
}

KeySpec number(std::string name, std::string unit, std::string meaning);
KeySpec integer(std::string name, std::string meaning);
KeySpec boolean(std::string name, std::string meaning);
KeySpec string(std::string name, std::string meaning);
KeySpec numbers(std::string name, std::string unit, std::string meaning);
KeySpec time_function(std::string name, std::string unit, std::string meaning);
KeySpec table(std::string name, std::string meaning);
KeySpec tables(std::string name, std::string meaning);
KeySpec named_tables(std::string name, std::string meaning);
KeySpec strings(std::string name, std::string meaning);
KeySpec any(std::string name, std::string unit, std::string meaning);

struct TableSpec {
  /// Dotted path without indices: "" (the top level), "solver", "phases.stop_at", "materials.*".
  std::string path;
  std::string meaning;
  std::vector<KeySpec> keys;
  /// Keys beyond `keys` come from the material registry by the table's `type`.
  bool material_parameters = false;

  const KeySpec* key(std::string_view name) const;
};

/// Every table of the case format, parents before children.
const std::vector<TableSpec>& case_format();
/// The table declared under `path`, or nullptr.
const TableSpec* find_table_spec(std::string_view path);

/// "[solver]", "[[phases]]", "[materials.<name>]", "phases.stop_at" as a reader writes the table.
std::string table_heading(const TableSpec& table);

} // namespace mpile
