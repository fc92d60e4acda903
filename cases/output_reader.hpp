#pragma once

#include "cases/case_spec.hpp"
#include "cases/toml_reader.hpp"
#include "engine/graded_axis.hpp"

namespace mpile {

/// [output]: the snapshots' times and penetrations, the cone penetration test's surfaces
/// ([output.cpt]) and the monitors ([[output.monitor]], each a point inside the grid or a particle
/// id, named for its dataset). Needs the bodies and contacts read.
void read_output(TomlTable& top, CaseSpec& spec, const GradedAxis& r_axis,
                 const GradedAxis& y_axis);

} // namespace mpile
