#pragma once

// Particles that move from coarse cells into much finer ones would leave fine cells empty between
// them (a body's nodes losing their mass and its internal forces their path). A particle whose
// domain is longer than its cell along r or y is split in two along that direction, until every
// half fits its cell.

#include "engine/geometry_mode.hpp"
#include "engine/grid.hpp"
#include "engine/particles.hpp"

#include <cstdint>
#include <vector>

namespace mpile {

/// Whether a particle's domain (2 half_r by 2 half_y) is longer than its cell along r or y.
bool oversized(const Particles& p, const Grid& grid, std::size_t i);

/// Splits every oversized particle: the particle becomes the half at -d along the direction, a
/// new particle appended at the end of the arrays the half at +d (d a quarter of its length), each
/// with half the domain there, and again while a half is oversized. Mass and volume are shared in
/// proportion to each half's integration weight (its area, times its radius in axisymmetry), so
/// that both sums are kept exactly; velocity, stress, state and displacement are the particle's
/// (its reference position moves with it), except that in axisymmetry a split along r scales
/// v_theta by r^2 / (r^2 + d^2), which keeps the angular momentum sum m r v_theta. A half that
/// would leave the grid or reach the axis is not made. Returns, for each appended particle, the
/// index of the particle it was split from.
std::vector<std::int32_t> split_oversized_particles(Particles& p, const Grid& grid,
                                                    GeometryMode mode);

} // namespace mpile
