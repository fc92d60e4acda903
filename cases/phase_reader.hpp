#pragma once

#include "cases/case_spec.hpp"
#include "cases/rigid_drive_reader.hpp"
#include "cases/toml_reader.hpp"

namespace mpile {

/// The [[phases]] tables, in order: each one's name (unique), its K0 procedures (by body or by
/// material), its stop (a penetration or a settlement, short of the moving band's travel) and its
/// drive of a rigid body. Needs the bodies, the solver and the moving mesh read.
void read_phases(TomlTable& top, CaseSpec& spec, const RigidNames& declared_rigid);

} // namespace mpile
