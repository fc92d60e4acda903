#pragma once

#include <array>
#include <cstddef>
#include <span>

namespace mpile {

/// Below this length of the share-weighted mean normal, a node's surfaces nearly face opposite
/// ways (faces of a structure thinner than a cell meeting at one node): one traction over both
/// would be ill-conditioned, and the node's force is split in proportion to the shares instead.
constexpr double opposed_surfaces_mean_normal = 0.25;

/// Splits a node's contact force f (r, y, theta) over the surfaces its outline area belongs to
/// (share[q] of the area, summing to 1, outward unit normal[q]) as one traction, a pressure p and
/// a shear tau, acting on each surface's part of the area: part q = share[q] (p normal[q] +
/// tau tangent[q]), tangent (-n_y, n_r), and share[q] of f_theta. (p, tau) is the one pair whose
/// parts add up to f; at a node whose contact normal is the share-weighted mean normal, tau / p is
/// the node's own friction ratio, so each surface reports friction within mu. (Turning each
/// share of f into its surface's frame without solving for p would lose the part of f the mean
/// normal is shorter than 1: at a square corner of equal shares, 29 % of the node's force.)
/// Returns false, with parts in proportion to the shares, where the surfaces nearly oppose.
bool split_over_surfaces(const std::array<double, 3>& force, std::span<const double> share,
                         std::span<const std::array<double, 2>> normal,
                         std::span<std::array<double, 3>> part);

} // namespace mpile
