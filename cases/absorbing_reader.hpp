#pragma once

#include "cases/case_spec.hpp"
#include "cases/toml_reader.hpp"

namespace mpile {

/// Reads `absorbing` (a list of grid faces: "r_min", "r_max", "y_min", "y_max") and
/// `absorbing_phase` of a [boundaries] or [monopile] table into spec.absorbing. The phase is
/// checked against [[phases]] later (check_absorbing_phase), once they are read.
void read_absorbing_faces(TomlTable& table, CaseSpec& spec, bool grid_starts_on_axis);

/// Refuses an absorbing_phase that names no phase; `table` is the one it was read from.
void check_absorbing_phase(const TomlTable& table, const CaseSpec& spec);

} // namespace mpile
