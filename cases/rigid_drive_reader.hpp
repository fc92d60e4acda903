#pragma once

#include "cases/case_spec.hpp"
#include "cases/case_warnings.hpp"
#include "cases/toml_reader.hpp"
#include "engine/structures/rigid_body.hpp"

#include <array>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace mpile {

/// The names of the bodies a file declares rigid with a [bodies.rigid] table. Their drives are
/// read after the phases (a drive names its phase), while the phases' stop criteria and the moving
/// mesh name them first.
using RigidNames = std::set<std::string>;

/// `name`, read under `key`, must name a rigid body.
void check_rigid_body_name(const TomlTable& table, const std::string& key, const std::string& name,
                           const CaseSpec& spec, const RigidNames& declared_rigid,
                           const std::string& why);

/// The drive keys of a rigid body's table or a phase's `drive`: per DOF (RigidDof order) a velocity
/// or a force function, or neither (free).
std::array<std::optional<RigidDrive>, 3> read_drives(TomlTable& table, const CaseSpec& spec,
                                                     std::vector<CaseWarning>& warnings);

} // namespace mpile
