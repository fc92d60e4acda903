// TOML text parsed within bounds, and TomlTable: a table read key by key against its declaration
// (cases/case_format.cpp), every error naming the file, line and key.
//
// Outline:
//   value helpers: type names for messages, edit_distance (suggestions), numbers
//   check_toml_bounds: nesting depth, line length and dotted-key parts bounded before parsing
//   key_excerpt, format_number, parse_toml
//   TomlTable: the declaration's keys and child tables (declared, child_spec), range and choice
//     checks, where a key was written and the errors that say so (line_of, fail, type_error,
//     missing), typed reads with and without a default (number, integer, string, path, boolean,
//     numbers), child tables (table, optional_table, tables, named_tables), finish (unknown keys
//     refused with the table's known keys), positive
#include "cases/toml_reader.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace mpile {

namespace {

std::string type_name(const TomlValue& v) {
  switch (v.type()) {
  case toml::value_t::boolean:
    return "a boolean";
  case toml::value_t::integer:
    return "an integer";
  case toml::value_t::floating:
    return "a number";
  case toml::value_t::string:
    return "a string";
  case toml::value_t::array:
    return "an array";
  case toml::value_t::table:
    return "a table";
  default:
    return "a date or time";
  }
}

bool is_number(const TomlValue& v) {
  return v.is_floating() || v.is_integer();
}

} // namespace

double as_number(const TomlValue& v) {
  return v.is_floating() ? v.as_floating() : static_cast<double>(v.as_integer());
}

/// Levenshtein distance (insertions, deletions, substitutions).
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) {
    row[j] = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

namespace {

/// The TOML parser recurses once per level of nested arrays and inline tables (a few thousand
/// levels overflow the stack), takes time quadratic in a line's length (a 435 kB line took 11 s)
/// and cubic in the parts of a dotted key (4 000 parts took 35 s and 600 MB): all three are bounded
/// here, in one pass before parsing, with the line that breaks the bound.
void check_toml_bounds(const std::string& text, const std::string& file) {
  constexpr std::size_t max_line = 16384;
  enum class In { code, comment, basic, literal, multiline_basic, multiline_literal };
  In in = In::code;
  // The open arrays and inline tables ('[' or '{'; a table header's brackets too), innermost last.
  std::string open;
  // A key is read at the start of a line outside any array, in a table header, and at the start
  // of an inline table or after its commas; it ends at '=' (or the header's ']').
  bool in_key = true;
  bool line_start = true; // nothing but blanks on this line so far
  std::size_t key_start = 0;
  std::size_t key_parts = 1;
  int line = 1;
  std::size_t line_start_at = 0;
  auto refuse = [&](const std::string& why) {
    throw CaseError(file + ":" + std::to_string(line) + ": " + why);
  };
  auto begin_key = [&](std::size_t at) {
    in_key = true;
    key_start = at;
    key_parts = 1;
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      if (i - line_start_at > max_line) {
        refuse("the line is " + std::to_string(i - line_start_at) + " characters long (at most " +
               std::to_string(max_line) + "): break long arrays over several lines");
      }
      ++line;
      line_start_at = i + 1;
      if (in == In::comment || in == In::basic || in == In::literal) {
        in = In::code; // a single-line string cannot span lines; the parser reports it
      }
      if (in == In::code && open.empty()) {
        begin_key(i + 1);
        line_start = true;
      }
      continue;
    }
    const bool triple = i + 2 < text.size() && text[i + 1] == c && text[i + 2] == c;
    switch (in) {
    case In::comment:
      break;
    case In::basic:
    case In::multiline_basic:
      if (c == '\\' && i + 1 < text.size() && text[i + 1] != '\n') {
        ++i; // an escaped character, possibly a quote (a line-ending backslash is counted above)
      } else if (c == '"' && (in == In::basic || triple)) {
        i += in == In::basic ? 0 : 2;
        in = In::code;
      }
      break;
    case In::literal:
    case In::multiline_literal:
      if (c == '\'' && (in == In::literal || triple)) {
        i += in == In::literal ? 0 : 2;
        in = In::code;
      }
      break;
    case In::code:
      if (c == '#') {
        in = In::comment;
      } else if (c == '"') {
        in = triple ? In::multiline_basic : In::basic;
        i += triple ? 2 : 0;
      } else if (c == '\'') {
        in = triple ? In::multiline_literal : In::literal;
        i += triple ? 2 : 0;
      } else if (c == '[' || c == '{') {
        const bool header = c == '[' && in_key && (line_start || open == "[");
        open += c;
        if (static_cast<int>(open.size()) > max_toml_depth) {
          refuse("arrays and inline tables are nested more than " + std::to_string(max_toml_depth) +
                 " deep");
        }
        if (c == '{') {
          begin_key(i + 1);
        } else if (header) {
          begin_key(i + 1);
        } else {
          in_key = false;
        }
      } else if (c == ']' || c == '}') {
        if (!open.empty()) {
          open.pop_back();
        }
        in_key = false;
      } else if (c == '=') {
        in_key = false;
      } else if (c == ',' && !open.empty() && open.back() == '{') {
        begin_key(i + 1);
      } else if (c == '.' && in_key && ++key_parts > max_key_parts) {
        refuse(key_excerpt(text.substr(key_start, 80)) + ": a dotted key has more than " +
               std::to_string(max_key_parts) + " parts");
      }
      break;
    }
    if (c != ' ' && c != '\t') {
      line_start = false;
    }
  }
  if (text.size() - line_start_at > max_line) {
    refuse("the line is " + std::to_string(text.size() - line_start_at) +
           " characters long (at most " + std::to_string(max_line) +
           "): break long arrays over several lines");
  }
}

} // namespace

std::string key_excerpt(const std::string& key) {
  std::string start = key.substr(std::min(key.size(), key.find_first_not_of(" \t")), 40);
  start.erase(start.find_last_not_of(". \t") + 1);
  return start + "...";
}

std::string format_number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

TomlValue parse_toml(const std::string& text, const std::string& file) {
  check_toml_bounds(text, file);
  std::istringstream stream(text);
  try {
    return toml::parse<toml::discard_comments, std::map, std::vector>(stream, file);
  } catch (const toml::syntax_error& e) {
    throw CaseError(file + ": not valid TOML:\n" + e.what());
  }
}

TomlTable::TomlTable(const TomlValue& table, std::string path, std::string file,
                     const TableSpec* spec)
    : table_(&table), path_(std::move(path)), file_(std::move(file)), spec_(spec) {}

const KeySpec* TomlTable::declared(const std::string& key) const {
  if (spec_ == nullptr) {
    return nullptr;
  }
  const KeySpec* k = spec_->key(key);
  if (k == nullptr && !spec_->material_parameters) {
    throw std::logic_error("the reader of " + table_heading(*spec_) + " reads '" + key +
                           "', which cases/case_format.cpp does not declare");
  }
  return k;
}

const TableSpec* TomlTable::child_spec(const std::string& key, bool star) const {
  const KeySpec* k = declared(key);
  if (k == nullptr) {
    return nullptr;
  }
  if (k->kind == ValueKind::time_function) {
    return find_table_spec("time_function");
  }
  const std::string path =
      (spec_->path.empty() ? key : spec_->path + "." + key) + (star ? ".*" : "");
  const TableSpec* child = find_table_spec(path);
  if (child == nullptr) {
    throw std::logic_error("the reader reads the table " + path +
                           ", which cases/case_format.cpp does not declare");
  }
  return child;
}

void TomlTable::refuse_second_default(const std::string& key) const {
  const KeySpec* k = declared(key);
  if (k != nullptr && !std::holds_alternative<std::monostate>(k->fallback)) {
    throw std::logic_error("the reader gives '" + key_path(key) +
                           "' a default, which cases/case_format.cpp declares already");
  }
}

void TomlTable::check_range(const std::string& key, double x, bool integer) const {
  const KeySpec* k = declared(key);
  if (k == nullptr || k->range.contains(x)) {
    return;
  }
  fail(key, k->range.requirement(integer) +
                (k->unit.empty() || k->unit == "-" ? "" : " " + k->unit) + ", got " +
                format_bound(x));
}

void TomlTable::check_choice(const std::string& key, const std::string& x) const {
  const KeySpec* k = declared(key);
  if (k == nullptr || k->choices.empty() ||
      std::find(k->choices.begin(), k->choices.end(), x) != k->choices.end()) {
    return;
  }
  std::string list;
  for (std::size_t i = 0; i < k->choices.size(); ++i) {
    list += (i == 0                       ? ""
             : i + 1 == k->choices.size() ? " or "
                                          : ", ") +
            ("\"" + k->choices[i] + "\"");
  }
  fail(key, "must be " + list + ", got \"" + x + "\"");
}

bool TomlTable::has(const std::string& key) const {
  return table_->as_table().count(key) > 0;
}

std::string TomlTable::key_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

int TomlTable::line_of(const std::string& key) const {
  const auto& table = table_->as_table();
  const auto found = table.find(key);
  const auto location = found != table.end() ? found->second.location() : table_->location();
  return static_cast<int>(location.line());
}

std::string TomlTable::file_of(const std::string& key) const {
  // A composed case holds values from its base files and from --set: each names its own source.
  const auto& table = table_->as_table();
  const auto found = table.find(key);
  const toml::source_location location =
      found != table.end() ? found->second.location() : table_->location();
  const std::string& name = location.file_name();
  return name.empty() || name == "unknown file" ? file_ : name;
}

namespace {

/// How near the user a key's value was written: 0 on the command line (--set), 1 in the case file
/// read, 2 in one of its bases, 3 not at all (a default).
int source_rank(const TomlTable& table, const std::string& key) {
  if (!table.has(key)) {
    return 3;
  }
  const std::string file = table.file_of(key);
  if (file.rfind("--set", 0) == 0) {
    return 0;
  }
  return file == table.file() ? 1 : 2;
}

} // namespace

std::string TomlTable::nearest_key(const std::string& key,
                                   const std::vector<std::string>& with) const {
  std::string nearest = key;
  for (const std::string& other : with) {
    if (source_rank(*this, other) < source_rank(*this, nearest)) {
      nearest = other;
    }
  }
  return nearest;
}

std::string TomlTable::location(const std::string& key) const {
  return file_of(key) + ":" + std::to_string(line_of(key));
}

std::string TomlTable::value_and_place(const std::string& key) const {
  if (!has(key)) {
    const KeySpec* k = spec_ != nullptr ? spec_->key(key) : nullptr;
    const bool given = k != nullptr && !std::holds_alternative<std::monostate>(k->fallback);
    return given ? k->default_description() + ", its default" : "its default";
  }
  return toml::format(table_->as_table().at(key)) + " at " + location(key);
}

void TomlTable::fail(const std::string& key, const std::string& message) const {
  throw CaseError(location(key) + ": " + key_path(key) + ": " + message);
}

void TomlTable::type_error(const std::string& key, const std::string& expected) const {
  fail(key, "expected " + expected + ", got " + type_name(table_->as_table().at(key)));
}

void TomlTable::missing(const std::string& key, const std::string& what) const {
  constexpr std::size_t max_edits = 2;
  for (const auto& [present, v] : table_->as_table()) {
    // A key the table declares is no typo, however close ([grid] y is not a misspelt r).
    const bool known = spec_ != nullptr && spec_->key(present) != nullptr;
    if (!known && read_.count(present) == 0 && edit_distance(present, key) <= max_edits) {
      fail(present, "unknown key; did you mean '" + key + "'?");
    }
  }
  fail(key, what.empty() ? "missing (required)" : "missing (required): " + what);
}

const TomlValue& TomlTable::value(const std::string& key) {
  if (!has(key)) {
    missing(key);
  }
  read_.insert(key);
  return table_->as_table().at(key);
}

std::optional<std::vector<std::vector<double>>> TomlTable::number_rows(const std::string& key,
                                                                       std::size_t columns) {
  const TomlValue& value = raw(key);
  if (!value.is_array() || value.as_array().empty()) {
    return std::nullopt;
  }
  std::vector<std::vector<double>> rows;
  for (const TomlValue& row : value.as_array()) {
    if (!row.is_array() || row.as_array().size() != columns) {
      return std::nullopt;
    }
    std::vector<double>& numbers = rows.emplace_back();
    for (const TomlValue& v : row.as_array()) {
      if (v.is_integer()) {
        numbers.push_back(static_cast<double>(v.as_integer()));
      } else if (v.is_floating()) {
        numbers.push_back(v.as_floating());
      } else {
        return std::nullopt;
      }
    }
  }
  return rows;
}

const TomlValue& TomlTable::raw(const std::string& key) {
  declared(key);
  return value(key);
}

double TomlTable::number(const std::string& key) {
  if (const KeySpec* k = declared(key); k != nullptr && !has(key)) {
    if (const double* x = std::get_if<double>(&k->fallback)) {
      return *x;
    }
  }
  const TomlValue& v = value(key);
  if (!is_number(v)) {
    type_error(key, "a number");
  }
  const double x = as_number(v);
  if (!std::isfinite(x)) {
    fail(key, "must be a finite number");
  }
  check_range(key, x, false);
  return x;
}

std::optional<double> TomlTable::optional_number(const std::string& key) {
  return has(key) ? std::optional<double>(number(key)) : std::nullopt;
}

double TomlTable::number_or(const std::string& key, double fallback) {
  refuse_second_default(key);
  return has(key) ? number(key) : fallback;
}

long TomlTable::integer(const std::string& key) {
  if (const KeySpec* k = declared(key); k != nullptr && !has(key)) {
    if (const long* x = std::get_if<long>(&k->fallback)) {
      return *x;
    }
  }
  const TomlValue& v = value(key);
  if (!v.is_integer()) {
    type_error(key, "an integer");
  }
  const auto x = static_cast<long>(v.as_integer());
  check_range(key, static_cast<double>(x), true);
  return x;
}

long TomlTable::integer_or(const std::string& key, long fallback) {
  refuse_second_default(key);
  return has(key) ? integer(key) : fallback;
}

std::string TomlTable::string(const std::string& key) {
  if (const KeySpec* k = declared(key); k != nullptr && !has(key)) {
    if (const std::string* x = std::get_if<std::string>(&k->fallback)) {
      return *x;
    }
  }
  const TomlValue& v = value(key);
  if (!v.is_string()) {
    type_error(key, "a string");
  }
  std::string x = v.as_string().str;
  check_choice(key, x);
  return x;
}

std::string TomlTable::string_or(const std::string& key, const std::string& fallback) {
  refuse_second_default(key);
  return has(key) ? string(key) : fallback;
}

std::string TomlTable::path(const std::string& key) {
  std::string x = string(key);
  check_path(key, x);
  return x;
}

void TomlTable::check_path(const std::string& key, const std::string& x) const {
  if (x.find('\0') != std::string::npos) {
    fail(key, "a path cannot hold a NUL character (\\u0000)");
  }
}

std::string TomlTable::path_or(const std::string& key, const std::string& fallback) {
  return has(key) ? path(key) : string_or(key, fallback);
}

bool TomlTable::boolean(const std::string& key) {
  if (const KeySpec* k = declared(key); k != nullptr && !has(key)) {
    if (const bool* x = std::get_if<bool>(&k->fallback)) {
      return *x;
    }
  }
  const TomlValue& v = value(key);
  if (!v.is_boolean()) {
    type_error(key, "true or false");
  }
  return v.as_boolean();
}

bool TomlTable::boolean_or(const std::string& key, bool fallback) {
  refuse_second_default(key);
  return has(key) ? boolean(key) : fallback;
}

std::vector<double> TomlTable::numbers(const std::string& key, std::size_t expected_size) {
  if (const KeySpec* k = declared(key); k != nullptr && expected_size == 0) {
    expected_size = k->count;
  }
  const TomlValue& v = value(key);
  if (!v.is_array()) {
    type_error(key, "an array of numbers");
  }
  std::vector<double> out;
  for (const TomlValue& item : v.as_array()) {
    if (!is_number(item)) {
      fail(key, "expected an array of numbers, found " + type_name(item) + " in it");
    }
    out.push_back(as_number(item));
    if (!std::isfinite(out.back())) {
      fail(key, "must hold finite numbers, got " + toml::format(item) + " at index " +
                    std::to_string(out.size() - 1));
    }
  }
  if (expected_size > 0 && out.size() != expected_size) {
    fail(key, "expected " + std::to_string(expected_size) + " numbers, got " +
                  std::to_string(out.size()));
  }
  return out;
}

std::vector<double> TomlTable::numbers_or(const std::string& key, std::vector<double> fallback) {
  refuse_second_default(key);
  return has(key) ? numbers(key) : fallback;
}

TomlTable TomlTable::table(const std::string& key) {
  const TomlValue& v = value(key);
  if (!v.is_table()) {
    type_error(key, "a table");
  }
  return TomlTable(v, key_path(key), file_, child_spec(key));
}

std::optional<TomlTable> TomlTable::optional_table(const std::string& key) {
  return has(key) ? std::optional<TomlTable>(table(key)) : std::nullopt;
}

std::vector<TomlTable> TomlTable::tables(const std::string& key) {
  std::vector<TomlTable> out;
  if (!has(key)) {
    return out;
  }
  const TomlValue& v = value(key);
  if (!v.is_array()) {
    type_error(key, "an array of tables ([[" + key_path(key) + "]])");
  }
  const auto& items = v.as_array();
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (!items[i].is_table()) {
      // At the element's own place: one a --set replaced names the --set, not the case's array.
      const toml::source_location at = items[i].location();
      const bool placed = !at.file_name().empty() && at.file_name() != "unknown file";
      throw CaseError((placed ? at.file_name() : file_of(key)) + ":" +
                      std::to_string(placed ? static_cast<int>(at.line()) : line_of(key)) + ": " +
                      key_path(key) + "[" + std::to_string(i) + "]: expected a table, found " +
                      type_name(items[i]));
    }
    out.emplace_back(items[i], key_path(key) + "[" + std::to_string(i) + "]", file_,
                     child_spec(key));
  }
  return out;
}

std::vector<std::pair<std::string, TomlTable>> TomlTable::named_tables(const std::string& key) {
  std::vector<std::pair<std::string, TomlTable>> out;
  if (!has(key)) {
    return out;
  }
  const TomlValue& v = value(key);
  if (!v.is_table()) {
    type_error(key, "a table of named tables");
  }
  for (const auto& [name, item] : v.as_table()) {
    if (!item.is_table()) {
      TomlTable(v, key_path(key), file_).fail(name, "expected a table, got " + type_name(item));
    }
    out.emplace_back(name,
                     TomlTable(item, key_path(key) + "." + name, file_, child_spec(key, true)));
  }
  return out;
}

std::span<const KeySpec> TomlTable::declared_keys() const {
  return spec_ == nullptr ? std::span<const KeySpec>{} : std::span<const KeySpec>(spec_->keys);
}

void read_key(TomlTable& table, const std::string& key, double& field) {
  field = table.number(key);
}
void read_key(TomlTable& table, const std::string& key, int& field) {
  // The declaration's range keeps the value within an int.
  field = static_cast<int>(table.integer(key));
}
void read_key(TomlTable& table, const std::string& key, long& field) {
  field = table.integer(key);
}
void read_key(TomlTable& table, const std::string& key, bool& field) {
  field = table.boolean(key);
}
void read_key(TomlTable& table, const std::string& key, std::string& field) {
  field = table.string(key);
}
void read_key(TomlTable& table, const std::string& key, std::optional<double>& field) {
  field = table.number(key);
}
void read_key(TomlTable& table, const std::string& key, std::optional<int>& field) {
  field = static_cast<int>(table.integer(key));
}
void read_key(TomlTable& table, const std::string& key, std::optional<long>& field) {
  field = table.integer(key);
}

long read_choice(TomlTable& table, const std::string& key) {
  const std::string x = table.string(key); // refused unless one of the choices
  const std::vector<std::string>& choices = table.spec()->key(key)->choices;
  return std::find(choices.begin(), choices.end(), x) - choices.begin();
}

const std::string& TomlTable::bound_key(const std::type_info& spec, std::ptrdiff_t offset) const {
  for (const KeySpec& k : declared_keys()) {
    if (k.bound_to != nullptr && *k.bound_to == spec && k.bound_offset == offset) {
      return k.name;
    }
  }
  throw std::logic_error("no key of " + (spec_ != nullptr ? table_heading(*spec_) : path_) +
                         " is bound to that member of " + spec.name());
}

void TomlTable::finish() const {
  for (const auto& [key, v] : table_->as_table()) {
    if (read_.count(key) == 0) {
      if (spec_ == nullptr || spec_->material_parameters) {
        fail(key, "unknown key (check its spelling in docs/case-format.md)");
      }
      std::string known;
      for (const KeySpec& k : spec_->keys) {
        known += (known.empty() ? "" : ", ") + k.name;
      }
      fail(key, "unknown key (" + table_heading(*spec_) + " has " + known + ")");
    }
  }
}

double TomlTable::positive(const std::string& key) {
  const double x = number(key);
  if (!(x > 0.0)) {
    fail(key, "must be positive, got " + toml::format(table_->as_table().at(key)));
  }
  return x;
}

} // namespace mpile
