#pragma once

#include "cases/case_spec.hpp"
#include "cases/toml_reader.hpp"

namespace mpile {

/// Reads a [monopile] table (the seed's monopile model from a few parameters, cases/monopile/)
/// and fills the grid, the pile and soil bodies, the pile's contact, the boundaries and the
/// moving mesh of `spec`. The materials must have been read. Returns the pile's drive table
/// ([monopile.drive]), read like [bodies.rigid] once the phases are known.
std::optional<TomlTable> read_monopile(TomlTable& monopile, CaseSpec& spec);

} // namespace mpile
