#include "cases/rigid_drive_reader.hpp"

#include "cases/time_function_reader.hpp"

#include <algorithm>

namespace mpile {

void check_rigid_body_name(const TomlTable& table, const std::string& key, const std::string& name,
                           const CaseSpec& spec, const RigidNames& declared_rigid,
                           const std::string& why) {
  const auto body = std::find_if(spec.bodies.begin(), spec.bodies.end(),
                                 [&](const BodySpec& b) { return b.name == name; });
  if (body == spec.bodies.end() || !(body->rigid || declared_rigid.contains(name))) {
    table.fail(key, "no rigid body named '" + name + "'" + why);
  }
}

std::array<std::optional<RigidDrive>, 3> read_drives(TomlTable& table, const CaseSpec& spec,
                                                     std::vector<CaseWarning>& warnings) {
  const bool plane = spec.mode == GeometryMode::plane_strain;
  const char* velocity_keys[] = {"velocity_r", "velocity_y", "angular_velocity"};
  const char* force_keys[] = {"force_r", "force_y", "torque"};
  std::array<std::optional<RigidDrive>, 3> drives;
  for (std::size_t d = 0; d < 3; ++d) {
    const bool velocity = table.has(velocity_keys[d]);
    const bool force = table.has(force_keys[d]);
    if (velocity && force) {
      table.fail(force_keys[d], std::string("give either ") + velocity_keys[d] + " or " +
                                    force_keys[d] + ", not both");
    }
    if (d == RIGID_X && !plane && (velocity || force)) {
      table.fail(velocity ? velocity_keys[d] : force_keys[d],
                 "an axisymmetric rigid body has no radial motion (zero by symmetry)");
    }
    if (velocity || force) {
      RigidDrive drive;
      drive.kind = velocity ? RigidDrive::Kind::velocity : RigidDrive::Kind::force;
      drive.function = read_time_function(table, velocity ? velocity_keys[d] : force_keys[d]);
      drives[d] = drive;
      if (d == RIGID_ROTATION && force) {
        warn_implausible_torque(table, force_keys[d], plane ? "N m/m" : "N m/rad", warnings);
      }
    }
  }
  return drives;
}

} // namespace mpile
