#pragma once

// A parameter study: one case run at every combination of listed values of some of its keys, and
// the quantities to gather from each run's history into one table. The sweep file is read as
// strictly as a case file, and every variant is composed (base, --set) and read before anything
// runs, so a wrong key path or value is refused naming the sweep file's line.

#include "cases/case_spec.hpp"
#include "cases/toml_reader.hpp"

#include <optional>
#include <string>
#include <vector>

namespace mpile {

/// One key of the case varied: its dotted path (as --set takes it) and its values as TOML text.
struct SweepParameter {
  std::string key;
  std::vector<std::string> values; // TOML text: 414500.0, "log", true
  int line = 0;
};

/// A number gathered from each run's history.h5.
struct GatherSpec {
  std::string name;
  std::string series; // path in history.h5: time, wall_time, bodies/pile/tip/force_y, ...
  std::string body;   // with at_penetration: the rigid body whose penetration is meant
  std::optional<double> at_penetration; // the series' value where the body first reaches this, m
  std::optional<double> at_time;        // the series' value at this time, s
  std::string reduce;                   // else: last, max, min, mean, max_abs
  std::string phase;                    // reduce over this phase only (empty: the whole run)
  int line = 0;                         // of its name, for messages
};

struct SweepVariant {
  std::string id;                  // v01, v02, ...: the run's directory under variants/
  std::vector<std::string> values; // one per parameter, TOML text
  std::vector<std::string> sets;   // key=value, as mpile run --set takes them
};

struct SweepSpec {
  std::string file; // the sweep file as given
  std::string title;
  std::string case_path;         // the case every variant runs, relative to the sweep file's folder
  int threads = 1;               // per run: a sweep fills the cores with runs rather than threads
  std::vector<std::string> sets; // applied to every variant, before the parameters
  std::vector<SweepParameter> parameters;
  std::vector<GatherSpec> gather;
  std::vector<SweepVariant> variants; // the product of the parameters' values, first key slowest
};

/// The most variants a sweep may expand to; more is almost surely a mistyped range.
inline constexpr std::size_t max_sweep_variants = 10000;

/// A TOML value as text that reads back exactly (floats in their shortest round-trip form,
/// strings quoted and escaped): what --set and the expanded sweep.toml are given.
std::string toml_text(const TomlValue& value);

/// Reads a sweep file and expands its variants; CaseError naming file, line and key otherwise.
SweepSpec read_sweep_file(const std::string& path);

/// Composes and reads the case of every variant (CaseError naming the parameter's line and the
/// values of the variant that cannot run), and checks that the gathered bodies exist. Returns the
/// variants' plausibility warnings, each once, with the variants that have it ("[variants v02,
/// v05]", "[every variant]").
std::vector<CaseWarning> validate_sweep(const SweepSpec& sweep);

} // namespace mpile
