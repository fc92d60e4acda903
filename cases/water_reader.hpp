#pragma once

#include "cases/case_spec.hpp"
#include "cases/toml_reader.hpp"

namespace mpile {

/// [water]: the sea above a saturated seabed and the pore water's cavitation. Sets each saturated
/// material's column pressure and cavitation stress and the case's WaterSpec; refuses, at the key's
/// line, a table without saturated soil, a level below the grid's bottom or below the seabed, and a
/// seabed that is not one surface. Needs the phases read (the K0 procedures give the seabed).
void read_water(TomlTable& top, CaseSpec& spec, double grid_bottom);

/// [boundaries] drained_pressure = "hydrostatic": the far field's water surface (the seabed, as
/// read_water finds it) and density; refused, at that key, under gravity not along -y, with
/// saturated materials of different water densities or a saturated body without a K0 procedure.
/// Needs read_water done.
void read_drained_water(TomlTable& boundaries, CaseSpec& spec);

} // namespace mpile
