#pragma once

#include "cases/toml_reader.hpp"
#include "engine/time_function.hpp"

#include <string>

namespace mpile {

/// A function of time under `key`: a number (a constant), or a table whose `type` ("constant",
/// "ramp", "table", "harmonic", "pulse_train") says which other keys it takes; another type's key
/// is refused at its line.
TimeFunction read_time_function(TomlTable& parent, const std::string& key);

} // namespace mpile
