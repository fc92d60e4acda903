#pragma once

// A body's region in a case file (a rectangle, polygon or circle) and the contact surfaces of the
// outline it gives a structure; errors name the file, line, key and reason.

#include "cases/case_spec.hpp"
#include "cases/toml_reader.hpp"
#include "engine/geometry_mode.hpp"
#include "engine/graded_axis.hpp"
#include "engine/region.hpp"

#include <string>
#include <vector>

namespace mpile {

/// Reads the key `region` of a [[bodies]] table: { r = [...], y = [...] }, { polygon = [[r, y],
/// ...] } or { circle = { centre = [r, y], radius = R } }, inside the grid and, in axisymmetric
/// mode, not behind the axis.
Region read_region(TomlTable& body, GeometryMode mode, const GradedAxis& r, const GradedAxis& y);

/// Reads the surface names of a [[contact]] entry whose structure (body `name`, region `region`)
/// takes outline normals, in the order ContactSpec::surfaces keeps them: a rectangle's by
/// `surfaces = { bottom, right, top, left }`, a convex polygon's by `surfaces = [...]` (one per
/// edge as given), a circle's by `surface` (read into `read` already).
std::vector<std::string> read_outline_surfaces(TomlTable& contact, const ContactSpec& read,
                                               const Region& region, const std::string& name);

} // namespace mpile
