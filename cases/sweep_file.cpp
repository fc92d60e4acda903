#include "cases/sweep_file.hpp"

#include "cases/case_composition.hpp"
#include "cases/case_spec.hpp"
#include "cases/toml_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>

namespace mpile {

std::string toml_text(const TomlValue& value) {
  if (value.is_floating()) {
    const double x = value.as_floating();
    if (std::isnan(x)) {
      return "nan";
    }
    if (std::isinf(x)) {
      return x > 0 ? "inf" : "-inf";
    }
    char buffer[64];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
    std::string text(buffer, end);
    if (text.find_first_of(".e") == std::string::npos) {
      text += ".0";
    }
    return text;
  }
  if (value.is_array()) {
    std::string text = "[";
    for (const TomlValue& element : value.as_array()) {
      text += (text.size() > 1 ? ", " : "") + toml_text(element);
    }
    return text + "]";
  }
  if (value.is_table()) {
    std::string text = "{";
    for (const auto& [key, element] : value.as_table()) {
      text += (text.size() > 1 ? ", " : " ") + toml::format_key(key) + " = " + toml_text(element);
    }
    return text + " }";
  }
  std::string text = toml::format(value, 0);
  text.erase(text.find_last_not_of('\n') + 1);
  return text;
}

namespace {

/// `{ from, to, count, scale }`: count values from `from` to `to`, both included.
std::vector<std::string> range_values(TomlTable range) {
  const double from = range.number("from");
  const double to = range.number("to");
  const long count = range.integer("count");
  const std::string scale = range.string_or("scale", "linear");
  range.finish();
  if (count < 2 || static_cast<std::size_t>(count) > max_sweep_variants) {
    range.fail("count", "must be from 2 to " + std::to_string(max_sweep_variants));
  }
  if (scale != "linear" && scale != "log") {
    range.fail("scale", "must be \"linear\" or \"log\", got \"" + scale + "\"");
  }
  if (scale == "log" && (from <= 0.0 || to <= 0.0)) {
    range.fail("from", "a log range needs from and to above zero");
  }
  std::vector<std::string> values;
  for (long i = 0; i < count; ++i) {
    const double s = static_cast<double>(i) / static_cast<double>(count - 1);
    const double x = scale == "log" ? from * std::pow(to / from, s) : from + s * (to - from);
    if (!std::isfinite(x)) {
      // to / from or to - from past the largest double (1e-300 to 1e300 on a log scale)
      range.fail("to", "the range from " + toml_text(TomlValue(from)) + " to " +
                           toml_text(TomlValue(to)) + " overflows between its ends");
    }
    values.push_back(toml_text(TomlValue(i == count - 1 ? to : x)));
  }
  return values;
}

std::vector<GatherSpec> read_gather(TomlTable& top) {
  std::vector<GatherSpec> gather;
  std::set<std::string> names;
  for (TomlTable& g : top.tables("gather")) {
    GatherSpec spec;
    spec.name = g.string("name");
    spec.line = g.line_of("name");
    // A column of results.csv and a variable of results.nc (HDF5, where '/' separates groups and
    // netCDF wants a letter, digit or '_' first): a name that breaks either was found only after
    // every variant had run, when the gathering failed.
    const bool printable = std::all_of(spec.name.begin(), spec.name.end(), [](char c) {
      return static_cast<unsigned char>(c) >= 0x80 || std::isgraph(static_cast<unsigned char>(c));
    });
    const unsigned char first = spec.name.empty() ? 0 : static_cast<unsigned char>(spec.name[0]);
    if (spec.name.empty() || !printable || spec.name.find_first_of(",\"/") != std::string::npos ||
        (first < 0x80 && !std::isalnum(first) && first != '_')) {
      g.fail("name", "\"" + spec.name +
                         "\" cannot name a column of results.csv and results.nc: use letters, "
                         "digits and _ (no spaces, commas, quotes or '/'), starting with a letter, "
                         "digit or _");
    }
    if (spec.name == "variant" || spec.name == "status") {
      g.fail("name", "\"" + spec.name + "\" is a column of every sweep's table already");
    }
    if (!names.insert(spec.name).second) {
      g.fail("name", "\"" + spec.name + "\" is gathered twice");
    }
    spec.series = g.string("series");
    if (spec.series.empty() || spec.series.front() == '/' || spec.series.back() == '/') {
      g.fail("series", "a path in history.h5 such as \"bodies/pile/penetration\"");
    }
    spec.at_penetration = g.optional_number("at_penetration");
    spec.at_time = g.optional_number("at_time");
    spec.body = g.string_or("body", "");
    spec.reduce = g.string_or("reduce", "");
    spec.phase = g.string_or("phase", "");
    const int ways =
        (spec.at_penetration ? 1 : 0) + (spec.at_time ? 1 : 0) + (g.has("reduce") ? 1 : 0);
    if (ways != 1) {
      g.fail("series", "give exactly one of at_penetration, at_time or reduce");
    }
    if (spec.at_penetration &&
        !(std::isfinite(*spec.at_penetration) && *spec.at_penetration > 0.0)) {
      g.fail("at_penetration", "must be a penetration above zero, m");
    }
    if (spec.at_time && !(std::isfinite(*spec.at_time) && *spec.at_time >= 0.0)) {
      g.fail("at_time", "must be a time from zero on, s");
    }
    if (spec.at_penetration && spec.body.empty()) {
      g.missing("body", "(the rigid body whose penetration at_penetration means)");
    }
    if (!spec.at_penetration && g.has("body")) {
      g.fail("body", "only at_penetration takes a body");
    }
    if (g.has("reduce") && spec.reduce != "last" && spec.reduce != "max" && spec.reduce != "min" &&
        spec.reduce != "mean" && spec.reduce != "max_abs") {
      g.fail("reduce", "must be last, max, min, mean or max_abs, got \"" + spec.reduce + "\"");
    }
    if (g.has("phase") && !g.has("reduce")) {
      g.fail("phase", "only reduce takes a phase");
    }
    g.finish();
    gather.push_back(spec);
  }
  return gather;
}

/// Whether two TOML values are one value written two ways: 1 and 1.0, 0.0 and -0.0, and arrays
/// of such; any other pair by its text.
bool same_value(const TomlValue& a, const TomlValue& b) {
  const auto number = [](const TomlValue& v) -> std::optional<double> {
    if (v.is_integer()) {
      return static_cast<double>(v.as_integer());
    }
    if (v.is_floating()) {
      return v.as_floating();
    }
    return std::nullopt;
  };
  if (const auto x = number(a), y = number(b); x && y) {
    return *x == *y;
  }
  if (a.is_array() && b.is_array()) {
    const auto& x = a.as_array();
    const auto& y = b.as_array();
    return x.size() == y.size() &&
           std::equal(x.begin(), x.end(), y.begin(),
                      [](const TomlValue& u, const TomlValue& v) { return same_value(u, v); });
  }
  return toml_text(a) == toml_text(b);
}

/// Whether two key paths set one value: equal, or one a table holding the other.
bool keys_overlap(const std::string& a, const std::string& b) {
  const auto inside = [](const std::string& outer, const std::string& inner) {
    return outer == inner ||
           (inner.size() > outer.size() && inner.compare(0, outer.size(), outer) == 0 &&
            inner[outer.size()] == '.');
  };
  return inside(a, b) || inside(b, a);
}

/// Refuses a parameter `key` (its message prefix `where`) whose key, as `canonical` maps it,
/// overlaps an earlier parameter's or a fixed `set`'s: which value a variant ran with would depend
/// on the order they were applied in.
template <typename Canonical>
void refuse_overlaps(const std::string& where, const std::string& key,
                     const std::vector<SweepParameter>& earlier,
                     const std::vector<std::string>& sets, const Canonical& canonical) {
  const std::string mine = canonical(key);
  for (const SweepParameter& other : earlier) {
    if (other.key != key && keys_overlap(mine, canonical(other.key))) {
      throw CaseError(where + "overlaps the parameter \"" + other.key +
                      "\": a key is swept by one entry only");
    }
  }
  for (const std::string& assignment : sets) {
    if (keys_overlap(mine, canonical(assignment.substr(0, assignment.find('='))))) {
      throw CaseError(where + "overlaps set's \"" + assignment +
                      "\": a swept key is not also set for every variant");
    }
  }
}

} // namespace

SweepSpec read_sweep_file(const std::string& path) {
  const std::string text = read_case_text_file(path, "sweep file");
  const TomlValue root = parse_toml(text, path);
  TomlTable top(root, "", path);
  SweepSpec sweep;
  sweep.file = path;
  sweep.title = top.string_or("title", std::filesystem::path(path).stem().string());
  sweep.case_path = top.path("case");
  if (sweep.case_path.empty()) {
    top.fail("case", "the case file every variant runs, relative to this file");
  }
  const long threads = top.integer_or("threads", 1);
  if (threads < 1 || threads > 1024) {
    top.fail("threads", "threads per run must be from 1 to 1024");
  }
  sweep.threads = static_cast<int>(threads);
  if (top.has("set")) {
    const TomlValue& sets = top.raw("set");
    if (!sets.is_array()) {
      top.fail("set", "expected an array of \"key.path=value\" strings");
    }
    for (const TomlValue& s : sets.as_array()) {
      if (!s.is_string() || s.as_string().str.find('=') == std::string::npos) {
        top.fail("set", "expected an array of \"key.path=value\" strings");
      }
      sweep.sets.push_back(s.as_string().str);
    }
  }

  if (!top.has("parameters")) {
    top.missing("parameters", "(a table of key paths, each with a list of values or a range)");
  }
  const TomlValue& parameters = top.raw("parameters");
  if (!parameters.is_table() || parameters.as_table().empty()) {
    top.fail("parameters", "expected a table of key paths, each with a list of values or a range");
  }
  TomlTable table(parameters, "parameters", path);
  for (const auto& [key, value] : parameters.as_table()) {
    const std::string where =
        path + ":" + std::to_string(table.line_of(key)) + ": parameters.\"" + key + "\": ";
    SweepParameter parameter{key, {}, table.line_of(key)};
    if (key.empty() || key.find('=') != std::string::npos || key.front() == '.' ||
        key.back() == '.' || key.find("..") != std::string::npos) {
      throw CaseError(where + "not a key path such as \"monopile.friction\"");
    }
    if (value.is_array()) {
      for (const TomlValue& v : value.as_array()) {
        parameter.values.push_back(toml_text(v));
      }
    } else if (value.is_table()) {
      parameter.values = range_values(TomlTable(value, "parameters." + key, path));
    } else {
      throw CaseError(where + "expected a list of values or a range { from, to, count }");
    }
    if (parameter.values.empty()) {
      throw CaseError(where + "the list of values is empty");
    }
    std::vector<TomlValue> parsed;
    for (const std::string& written : parameter.values) {
      parsed.push_back(parse_toml("value = " + written, path).as_table().at("value"));
    }
    for (std::size_t i = 0; i < parameter.values.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (same_value(parsed[i], parsed[j])) {
          const std::string as =
              parameter.values[i] == parameter.values[j] ? "" : " (as " + parameter.values[j] + ")";
          throw CaseError(where + "the value " + parameter.values[i] + " is listed twice" + as +
                          ": its variants would run twice");
        }
      }
    }
    refuse_overlaps(where, key, sweep.parameters, sweep.sets,
                    [](const std::string& k) { return k; });
    sweep.parameters.push_back(parameter);
    table.raw(key);
  }
  // The order of the file, so that the first parameter varies slowest.
  std::sort(sweep.parameters.begin(), sweep.parameters.end(),
            [](const SweepParameter& a, const SweepParameter& b) { return a.line < b.line; });
  sweep.gather = read_gather(top);
  top.finish();

  std::size_t count = 1;
  for (const SweepParameter& parameter : sweep.parameters) {
    count *= parameter.values.size();
    if (count > max_sweep_variants) {
      top.fail("parameters",
               "the values make more than " + std::to_string(max_sweep_variants) + " variants");
    }
  }
  const std::size_t digits = std::to_string(count).size();
  for (std::size_t v = 0; v < count; ++v) {
    SweepVariant variant;
    std::string number = std::to_string(v + 1);
    number.insert(0, std::max<std::size_t>(digits, 2) - number.size(), '0');
    variant.id = 'v';
    variant.id += number;
    variant.sets = sweep.sets;
    std::size_t rest = v;
    std::vector<std::size_t> index(sweep.parameters.size());
    for (std::size_t p = sweep.parameters.size(); p-- > 0;) {
      index[p] = rest % sweep.parameters[p].values.size();
      rest /= sweep.parameters[p].values.size();
    }
    for (std::size_t p = 0; p < sweep.parameters.size(); ++p) {
      const std::string& value = sweep.parameters[p].values[index[p]];
      variant.values.push_back(value);
      variant.sets.push_back(sweep.parameters[p].key + "=" + value);
    }
    sweep.variants.push_back(variant);
  }
  return sweep;
}

std::vector<CaseWarning> validate_sweep(const SweepSpec& sweep) {
  const std::string case_path = (std::filesystem::path(sweep.file).parent_path() / sweep.case_path)
                                    .lexically_normal()
                                    .string();
  // Keys written two ways (a phase by name and by index, an index with a leading zero) set one
  // value: compared as they land in the case's tree, which read_sweep_file does not open. A case
  // that cannot be read is named by the variants' reading below.
  TomlValue root;
  try {
    root = compose_case(case_path, sweep.sets).root;
  } catch (const CaseError&) {
  }
  const auto canonical = [&](const std::string& key) { return canonical_key(root, key); };
  for (std::size_t p = 0; p < sweep.parameters.size(); ++p) {
    const SweepParameter& parameter = sweep.parameters[p];
    refuse_overlaps(sweep.file + ":" + std::to_string(parameter.line) + ": parameters.\"" +
                        parameter.key + "\": ",
                    parameter.key, {sweep.parameters.begin(), sweep.parameters.begin() + p},
                    sweep.sets, canonical);
  }
  // Each warning's text once, in the order first met, with the variants that have it.
  std::vector<std::pair<CaseWarning, std::vector<std::string>>> seen;
  for (const SweepVariant& variant : sweep.variants) {
    CaseSpec spec;
    try {
      spec = read_case_file(case_path, variant.sets);
    } catch (const CaseError& e) {
      // The parameter whose value the case refused, else the first one: the line to look at.
      const SweepParameter* culprit = &sweep.parameters.front();
      for (const SweepParameter& parameter : sweep.parameters) {
        if (std::string(e.what()).find(parameter.key) != std::string::npos) {
          culprit = &parameter;
        }
      }
      std::string values;
      for (std::size_t p = 0; p < sweep.parameters.size(); ++p) {
        values += (p > 0 ? ", " : "") + sweep.parameters[p].key + " = " + variant.values[p];
      }
      throw CaseError(sweep.file + ":" + std::to_string(culprit->line) + ": parameters.\"" +
                      culprit->key + "\": variant " + variant.id + " (" + values +
                      ") cannot run: " + e.what());
    }
    for (const CaseWarning& w : spec.warnings) {
      const auto same = std::find_if(seen.begin(), seen.end(),
                                     [&](const auto& f) { return f.first.text == w.text; });
      if (same == seen.end()) {
        seen.push_back({w, {variant.id}});
      } else {
        same->second.push_back(variant.id);
      }
    }
    for (std::size_t i = 0; i < sweep.gather.size(); ++i) {
      const GatherSpec& g = sweep.gather[i];
      const std::string where =
          sweep.file + ":" + std::to_string(g.line) + ": gather[" + std::to_string(i) + "].";
      if (!g.phase.empty() &&
          std::none_of(spec.phases.begin(), spec.phases.end(),
                       [&](const PhaseSpec& phase) { return phase.name == g.phase; })) {
        throw CaseError(where + "phase: the case " + case_path + " has no phase named \"" +
                        g.phase + "\"");
      }
      if (!g.at_penetration) {
        continue;
      }
      const bool found =
          std::any_of(spec.bodies.begin(), spec.bodies.end(),
                      [&](const BodySpec& b) { return b.name == g.body && b.rigid; });
      if (!found) {
        throw CaseError(where + "body: the case " + case_path + " has no rigid body named \"" +
                        g.body + "\"");
      }
    }
  }
  std::vector<CaseWarning> warnings;
  for (auto& [warning, ids] : seen) {
    std::string which;
    for (const std::string& id : ids) {
      which += (which.empty() ? "" : ", ") + id;
    }
    warning.text += ids.size() == sweep.variants.size()
                        ? " [every variant]"
                        : " [variant" + std::string(ids.size() > 1 ? "s " : " ") + which + "]";
    warnings.push_back(warning);
  }
  return warnings;
}

} // namespace mpile
