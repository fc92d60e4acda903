#pragma once

// A case as it runs: its file, the files its `base` key names underneath it (and their bases, and
// so on), and the command line's --set values on top. Values keep the file and line they came
// from, so the reader's errors point into whichever file (or --set) gave the value.

#include "cases/case_spec.hpp"
#include "cases/toml_reader.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace mpile {

struct ComposedCase {
  TomlValue root;                 // the merged tree, without `base` keys
  std::string text;               // the case file's own text
  std::string resolved;           // the merged tree as TOML text: the case that ran
  std::vector<std::string> bases; // the base files read, in the order they were opened
};

/// The deepest chain of bases followed; a longer one is almost surely a mistake.
constexpr int max_base_depth = 8;

/// Reads a case file of bounded size (a regular file, at most max_case_file_bytes); CaseError with
/// the operating system's reason otherwise. `kind` names the file in the errors: the sweep and
/// element-test files are read here too.
std::string read_case_text_file(const std::string& path, std::string_view kind = "case file");

/// Merges `top` over `base`: a table merges key by key (recursively), unless `top` names a `type`
/// other than the base's (a material of another model), which replaces the base's table; any
/// other value of `top`, arrays and arrays of tables included, replaces the base's.
TomlValue merge_over(const TomlValue& base, const TomlValue& top);

/// Sets one value from `key.path=value` (value in TOML syntax: numbers, "strings", booleans,
/// arrays, inline tables). A path element that is a number indexes an array ([[phases]]: phases.1).
/// Tables on the path are made when absent; the strict reader then refuses an unknown key.
void apply_override(TomlValue& root, const std::string& assignment);

/// A --set key path as it lands in `root`: an element of an array of tables by its index without
/// leading zeros, whether written by index or by name (phases.installation.duration and
/// phases.01.duration are both phases.1.duration where phase 1 is "installation"). Parts that
/// name nothing in `root` are kept as written.
std::string canonical_key(const TomlValue& root, const std::string& key);

/// Reads a case file with its bases and applies the overrides, in the order given.
ComposedCase compose_case(const std::string& path, const std::vector<std::string>& overrides);

/// Reads and validates a parsed (and composed) case tree; `text` is the case file's own text.
CaseSpec read_case_tree(const TomlValue& root, const std::string& text, const std::string& file);

/// The dotted key paths at which two case trees differ (array elements as numbers: phases.1.name);
/// a table or array present on one side only is one path.
std::vector<std::string> differing_keys(const TomlValue& before, const TomlValue& after);

/// The keys at which a stored case and this one differ, and the first of them a restart may not
/// change ("KEY changed (was A, now B)"; empty when there is none): restart_changes' judgement
/// without the throw, for `run --continue`, which starts afresh instead.
struct RestartCheck {
  std::vector<std::string> changed;
  std::string refused;
};
RestartCheck check_restart(const std::string& stored_resolved, const std::string& resolved,
                           std::size_t phase, const std::string& source);

/// What a restart may change in its case, so that a finished or stopped run can be extended
/// without running anything it already ran under other physics: the title, [output], the end
/// criteria (duration, equilibrium_tolerance, stop_at) of the phase it continues and of later
/// phases, the settings and drive of phases not begun (not their names or K0), and phases added
/// at the end. `phase` is the index of the phase the run stopped in (the
/// number of phases when it was complete, whose last phase may then be extended). Returns the keys
/// that changed; throws CaseError naming the first key that may not change, with both values.
std::vector<std::string> restart_changes(const std::string& stored_resolved,
                                         const std::string& resolved, std::size_t phase,
                                         const std::string& source);

} // namespace mpile
