#pragma once

#include "cases/case_spec.hpp"
#include "cases/toml_reader.hpp"
#include "engine/graded_axis.hpp"

#include <vector>

namespace mpile {

/// The memory a case will take, from its grid and its bodies' regions before anything is
/// allocated: refused past the machine's physical memory with the key that drives it (a mistyped
/// cell size or zone took 15 GB and ended in std::bad_alloc).
void refuse_past_memory_budget(TomlTable& top, const CaseSpec& spec, const GradedAxis& r_axis,
                               const GradedAxis& y_axis, std::vector<TomlTable>& body_tables);

} // namespace mpile
