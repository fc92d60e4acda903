#include "cases/case_composition.hpp"

#include "cases/case_spec.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace mpile {

std::string read_case_text_file(const std::string& path, std::string_view kind) {
  // Only a regular file of bounded size: a directory would read as empty, a FIFO would block and
  // /dev/zero would be read without end.
  const std::string what(kind);
  const std::string a_what = (what.find_first_of("aeiou") == 0 ? "an " : "a ") + what;
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (error) {
    throw CaseError(path + ": cannot open the " + what + ": " + error.message());
  }
  if (std::filesystem::is_directory(status)) {
    throw CaseError(path + ": is a directory, not " + a_what);
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw CaseError(path + ": is not a regular file (" + a_what + " is a TOML text file)");
  }
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (!error && size > max_case_file_bytes) {
    throw CaseError(path + ": is " + std::to_string(size) + " bytes; " + a_what + " is at most " +
                    std::to_string(max_case_file_bytes) + " bytes");
  }
  std::ifstream in(path);
  if (!in) {
    throw CaseError(path + ": cannot open the " + what + ": " + std::strerror(errno));
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

namespace {

/// A table's `type` (a material's model, a drive's time function), empty if it names none.
std::string type_of(const TomlValue& table) {
  const auto found = table.as_table().find("type");
  if (found == table.as_table().end() || !found->second.is_string()) {
    return {};
  }
  return found->second.as_string().str;
}

} // namespace

TomlValue merge_over(const TomlValue& base, const TomlValue& top) {
  if (!base.is_table() || !top.is_table()) {
    return top;
  }
  // A table of another type shares no keys with the base's: a hypoplastic sand over a Hardening
  // Soil one would otherwise inherit e50_ref and be refused for it.
  const std::string top_type = type_of(top);
  if (!top_type.empty() && top_type != type_of(base)) {
    return top;
  }
  // The top table keeps its own location (its file and line name errors about it).
  TomlValue merged = top;
  auto& table = merged.as_table();
  for (const auto& [key, value] : base.as_table()) {
    const auto found = table.find(key);
    if (found == table.end()) {
      table.emplace(key, value);
    } else {
      found->second = merge_over(value, found->second);
    }
  }
  return merged;
}

namespace {

std::vector<std::string> split_key(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    parts.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) {
      return parts;
    }
    start = dot + 1;
  }
}

bool is_index(const std::string& part) {
  return !part.empty() && part.size() < 10 && std::all_of(part.begin(), part.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
}

bool is_bare_key(const std::string& part) {
  return !part.empty() && std::all_of(part.begin(), part.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
  });
}

TomlValue read_with_bases(const std::string& path, int depth, std::vector<std::string>& ancestors,
                          std::vector<std::string>& read, std::string* own_text);

/// Reads the base file `entry` names (relative to `path`, the file that names it) with its own
/// bases. `ancestors` are the files above it in this branch (a cycle is a file among them).
TomlValue read_base(const TomlValue& entry, const std::string& path, int depth,
                    std::vector<std::string>& ancestors, std::vector<std::string>& read) {
  const auto where = path + ":" + std::to_string(entry.location().line()) + ": base: ";
  if (!entry.is_string()) {
    throw CaseError(where + "expected the path of a base case file (a string) or a list of them");
  }
  if (entry.as_string().str.find('\0') != std::string::npos) {
    // The system reads a path only up to a NUL: "x.toml\u0000junk" read x.toml.
    throw CaseError(where + "a path cannot hold a NUL character (\\u0000)");
  }
  // Relative to the file that names it, so a case and its base move together.
  std::filesystem::path base_path = static_cast<std::string>(entry.as_string());
  if (base_path.is_relative()) {
    base_path = std::filesystem::path(path).parent_path() / base_path;
  }
  const std::string base_file = base_path.lexically_normal().string();
  if (depth >= max_base_depth) {
    throw CaseError(where + "bases are nested more than " + std::to_string(max_base_depth) +
                    " deep");
  }
  const auto same_file = [&](const std::string& other) {
    std::error_code error;
    return std::filesystem::equivalent(base_file, other, error);
  };
  if (same_file(path) || std::any_of(ancestors.begin(), ancestors.end(), same_file)) {
    throw CaseError(where + base_file + " is already in this chain of bases (a cycle)");
  }
  read.push_back(base_file);
  ancestors.push_back(base_file);
  try {
    TomlValue base = read_with_bases(base_file, depth + 1, ancestors, read, nullptr);
    ancestors.pop_back();
    return base;
  } catch (const CaseError& e) {
    // The line that names the base leads, so the message starts in the file the user ran.
    throw CaseError(where + e.what());
  }
}

/// Reads one case file and the bases under it, merged: `base` names one file or a list of them,
/// each merged over the ones before it (a mesh, then a sand), and the file over them all.
TomlValue read_with_bases(const std::string& path, int depth, std::vector<std::string>& ancestors,
                          std::vector<std::string>& read, std::string* own_text) {
  std::string text = read_case_text_file(path);
  TomlValue root = parse_toml(text, path);
  if (own_text != nullptr) {
    *own_text = std::move(text);
  }
  auto& table = root.as_table();
  const auto base_key = table.find("base");
  if (base_key == table.end()) {
    return root;
  }
  TomlValue bases;
  if (base_key->second.is_array()) {
    const auto& entries = base_key->second.as_array();
    if (entries.empty()) {
      throw CaseError(path + ":" + std::to_string(base_key->second.location().line()) +
                      ": base: the list of base files is empty");
    }
    for (const TomlValue& entry : entries) {
      bases = merge_over(bases, read_base(entry, path, depth, ancestors, read));
    }
  } else {
    bases = read_base(base_key->second, path, depth, ancestors, read);
  }
  table.erase(base_key);
  return merge_over(bases, root);
}

} // namespace

namespace {

/// The `name` of an element of an array of tables, or nullptr (not a table, or no name text).
const std::string* name_of(const TomlValue& item) {
  if (!item.is_table()) {
    return nullptr;
  }
  const auto name = item.as_table().find("name");
  return name != item.as_table().end() && name->second.is_string() ? &name->second.as_string().str
                                                                   : nullptr;
}

/// The element of an array of tables a --set path names: by its index (phases.1) or by its
/// `name` (phases.installation), with the names it has and the nearest one when none matches.
TomlValue& element(TomlValue::array_type& array, const std::string& part, const std::string& origin,
                   const std::string& path) {
  if (is_index(part)) {
    if (std::stoul(part) >= array.size()) {
      throw CaseError(origin + ": " + path + ": the array has " + std::to_string(array.size()) +
                      " elements, numbered from 0");
    }
    return array[std::stoul(part)];
  }
  std::string names, nearest;
  std::size_t nearest_edits = 3; // a suggestion within two edits, as for keys
  for (TomlValue& item : array) {
    const std::string* text = name_of(item);
    if (text == nullptr) {
      continue;
    }
    if (*text == part) {
      return item;
    }
    names += (names.empty() ? "" : ", ") + *text;
    if (const std::size_t edits = edit_distance(part, *text); edits < nearest_edits) {
      nearest_edits = edits;
      nearest = *text;
    }
  }
  throw CaseError(origin + ": " + path + ": no element is named '" + part + "'" +
                  (names.empty() ? " (its elements have no names; give an index from 0)"
                                 : " (names: " + names + ")") +
                  (nearest.empty() ? "" : "; did you mean '" + nearest + "'?"));
}

} // namespace

void apply_override(TomlValue& root, const std::string& assignment) {
  const std::string origin = "--set " + assignment;
  const std::size_t equals = assignment.find('=');
  if (equals == std::string::npos) {
    throw CaseError(origin + ": expected key.path=value");
  }
  std::string key = assignment.substr(0, equals);
  key.erase(key.find_last_not_of(' ') + 1);
  key.erase(0, key.find_first_not_of(' '));
  // Bounded as in a case file, before the parts are split out: each makes a table.
  const auto dots = static_cast<std::size_t>(std::count(key.begin(), key.end(), '.'));
  if (dots + 1 > max_key_parts) {
    throw CaseError("--set " + key_excerpt(key) + ": the key has " + std::to_string(dots + 1) +
                    " parts; a dotted key has at most " + std::to_string(max_key_parts));
  }
  const std::vector<std::string> parts = split_key(key);
  if (!std::all_of(parts.begin(), parts.end(), is_bare_key)) {
    throw CaseError(origin + ": '" + key +
                    "' is not a key path (keys joined by dots, like monopile.embedment)");
  }
  if (parts.front() == "base") {
    throw CaseError(origin + ": base is the file a case builds on; name it in the case file");
  }
  TomlValue parsed;
  try {
    parsed = parse_toml("value = " + assignment.substr(equals + 1), "--set " + key);
  } catch (const CaseError& e) {
    throw CaseError(origin + ": the value is not TOML (text needs quotes: " + key +
                    "=\"text\"):\n" + e.what());
  }
  if (parsed.as_table().size() != 1) {
    // Text after a line break parses as further keys of its own, which would be dropped.
    throw CaseError("--set " + key +
                    ": the value must be one TOML value; it goes on after a line break (give each "
                    "assignment its own --set)");
  }
  TomlValue* node = &root;
  std::string path;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& part = parts[i];
    path += (path.empty() ? "" : ".") + part;
    if (node->is_array()) {
      node = &element(node->as_array(), part, origin, path);
      continue;
    }
    if (!node->is_table()) {
      throw CaseError(origin + ": " + path.substr(0, path.rfind('.')) + " is not a table");
    }
    auto& table = node->as_table();
    auto found = table.find(part);
    if (found == table.end()) {
      // Made where the --set is, so that an error about it names the --set, not the case file.
      found = table.emplace(part, parse_toml("value = {}", "--set " + key).as_table().at("value"))
                  .first;
    }
    node = &found->second;
  }
  const TomlValue& value = parsed.as_table().at("value");
  if (node->is_array()) {
    element(node->as_array(), parts.back(), origin, key) = value;
  } else if (node->is_table()) {
    node->as_table()[parts.back()] = value;
  } else {
    throw CaseError(origin + ": " + key.substr(0, key.rfind('.')) + " is not a table");
  }
}

std::string canonical_key(const TomlValue& root, const std::string& key) {
  const TomlValue* node = &root;
  std::string canonical;
  for (const std::string& part : split_key(key)) {
    std::string written = part;
    const TomlValue* next = nullptr;
    if (node != nullptr && node->is_array()) {
      const auto& array = node->as_array();
      if (is_index(part)) {
        const std::size_t index = std::stoul(part);
        written = std::to_string(index); // phases.00 is phases.0
        next = index < array.size() ? &array[index] : nullptr;
      }
      for (std::size_t i = 0; !is_index(part) && next == nullptr && i < array.size(); ++i) {
        if (const std::string* name = name_of(array[i]); name != nullptr && *name == part) {
          written = std::to_string(i);
          next = &array[i];
        }
      }
    } else if (node != nullptr && node->is_table()) {
      const auto found = node->as_table().find(part);
      next = found == node->as_table().end() ? nullptr : &found->second;
    }
    canonical += (canonical.empty() ? "" : ".") + written;
    node = next;
  }
  return canonical;
}

ComposedCase compose_case(const std::string& path, const std::vector<std::string>& overrides) {
  ComposedCase composed;
  std::vector<std::string> ancestors;
  composed.root = read_with_bases(path, 0, ancestors, composed.bases, &composed.text);
  for (const std::string& assignment : overrides) {
    apply_override(composed.root, assignment);
  }
  composed.resolved = toml::format(composed.root);
  return composed;
}

namespace {

void collect_differences(const TomlValue& before, const TomlValue& after, const std::string& path,
                         std::vector<std::string>& out) {
  const auto child = [&](const std::string& part) {
    return path.empty() ? part : path + "." + part;
  };
  if (before.is_table() && after.is_table()) {
    const auto& a = before.as_table();
    const auto& b = after.as_table();
    for (const auto& [key, value] : a) {
      const auto found = b.find(key);
      if (found == b.end()) {
        out.push_back(child(key));
      } else {
        collect_differences(value, found->second, child(key), out);
      }
    }
    for (const auto& [key, value] : b) {
      if (a.count(key) == 0) {
        out.push_back(child(key));
      }
    }
    return;
  }
  if (before.is_array() && after.is_array()) {
    const auto& a = before.as_array();
    const auto& b = after.as_array();
    const bool of_tables =
        std::all_of(a.begin(), a.end(), [](const TomlValue& v) { return v.is_table(); }) &&
        std::all_of(b.begin(), b.end(), [](const TomlValue& v) { return v.is_table(); });
    if (of_tables && !a.empty() && !b.empty()) {
      // Arrays of tables ([[phases]]) element by element, so a change names its phase.
      for (std::size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
        if (i >= a.size() || i >= b.size()) {
          out.push_back(child(std::to_string(i)));
        } else {
          collect_differences(a[i], b[i], child(std::to_string(i)), out);
        }
      }
      return;
    }
  }
  if (!(before == after)) {
    out.push_back(path);
  }
}

} // namespace

std::vector<std::string> differing_keys(const TomlValue& before, const TomlValue& after) {
  std::vector<std::string> out;
  collect_differences(before, after, "", out);
  return out;
}

namespace {

const TomlValue* find_path(const TomlValue& root, const std::string& path) {
  const TomlValue* node = &root;
  for (const std::string& part : split_key(path)) {
    if (node->is_table() && node->as_table().count(part) > 0) {
      node = &node->as_table().at(part);
    } else if (node->is_array() && is_index(part) && std::stoul(part) < node->as_array().size()) {
      node = &node->as_array()[std::stoul(part)];
    } else {
      return nullptr;
    }
  }
  return node;
}

std::string shown(const TomlValue* value) {
  if (value == nullptr) {
    return "absent";
  }
  if (value->is_table()) {
    return "a table";
  }
  if (value->is_floating()) {
    // Shortest form that reads back: 0.15, not 0.14999999999999999.
    std::ostringstream number;
    number << std::setprecision(15) << value->as_floating();
    std::string text = number.str();
    if (text.find_first_of(".eni") == std::string::npos) {
      text += ".0"; // as TOML writes a float
    }
    return text;
  }
  std::string text = toml::format(*value, 0);
  text.erase(text.find_last_not_of('\n') + 1);
  return text.size() > 60 ? text.substr(0, 57) + "..." : text;
}

} // namespace

RestartCheck check_restart(const std::string& stored_resolved, const std::string& resolved,
                           std::size_t phase, const std::string& source) {
  const TomlValue before = parse_toml(stored_resolved, source + " (its case)");
  const TomlValue after = parse_toml(resolved, "the case");
  std::size_t stored_phases = 0;
  if (const TomlValue* phases = find_path(before, "phases"); phases && phases->is_array()) {
    stored_phases = phases->as_array().size();
  }
  std::size_t phases_now = 0;
  if (const TomlValue* phases = find_path(after, "phases"); phases && phases->is_array()) {
    phases_now = phases->as_array().size();
  }
  // The first phase whose end criteria may change: the one the run stopped in; for a complete
  // run its last phase, which it re-enters, unless phases were added after it.
  std::size_t first_open = phase;
  if (phase >= stored_phases) {
    first_open =
        phases_now > stored_phases || stored_phases == 0 ? stored_phases : stored_phases - 1;
  }
  RestartCheck check;
  check.changed = differing_keys(before, after);
  for (const std::string& key : check.changed) {
    const std::vector<std::string> parts = split_key(key);
    bool allowed = parts[0] == "title" || parts[0] == "output";
    if (parts[0] == "phases" && parts.size() >= 2 && is_index(parts[1])) {
      const std::size_t index = std::stoul(parts[1]);
      const bool end_criterion =
          parts.size() >= 3 &&
          (parts[2] == "duration" || parts[2] == "equilibrium_tolerance" || parts[2] == "stop_at");
      // A phase the run has not begun has left nothing in its state: the settings its runner
      // applies when it begins may change too. Not its name (drives, loads and absorbing faces
      // name their phase) nor its K0 procedure (the first one a saturated body gets is the
      // seabed, which the run has used from its start).
      const bool not_begun = phase < stored_phases && index > phase && index < stored_phases;
      const bool setting =
          parts.size() >= 3 &&
          (parts[2] == "local_damping" || parts[2] == "gravity" || parts[2] == "flip_fraction" ||
           parts[2] == "xpic_order" || parts[2] == "mass_scaling" || parts[2] == "courant_number" ||
           parts[2] == "drive");
      allowed = (parts.size() == 2 && index >= stored_phases) ||
                (end_criterion && index >= first_open) || (setting && not_begun);
    }
    if (!allowed) {
      check.refused = key + " changed (was " + shown(find_path(before, key)) + ", now " +
                      shown(find_path(after, key)) + ")";
      break;
    }
  }
  return check;
}

std::vector<std::string> restart_changes(const std::string& stored_resolved,
                                         const std::string& resolved, std::size_t phase,
                                         const std::string& source) {
  RestartCheck check = check_restart(stored_resolved, resolved, phase, source);
  if (!check.refused.empty()) {
    throw CaseError(source + ": cannot continue with this case: " + check.refused +
                    ". A restart may change the title, [output], the duration, "
                    "equilibrium_tolerance and stop_at of the phase it continues and of later "
                    "phases, the settings and drive of phases not begun, and add phases at the "
                    "end; start a new run for anything else");
  }
  return std::move(check.changed);
}

} // namespace mpile
