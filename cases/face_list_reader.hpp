#pragma once

#include "cases/toml_reader.hpp"
#include "engine/grid.hpp"

#include <string>
#include <vector>

namespace mpile {

/// A list of grid faces under `key` ("r_min", "r_max", "y_min", "y_max", each once), refused at
/// its line otherwise; `axis_refusal`, when not empty, refuses "r_min" (the axis) with that reason.
std::vector<GridFace> read_face_list(TomlTable& table, const std::string& key,
                                     const std::string& axis_refusal = "");

} // namespace mpile
