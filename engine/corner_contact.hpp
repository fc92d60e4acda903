#pragma once

#include <array>

namespace mpile {

/// Which of a corner's two contact surfaces hold the soil at a node where they meet.
enum class CornerActive { none, first, second, both };

/// The soil's in-plane (r-y) relative velocity at a node where two contact surfaces meet, such as
/// a pile tip's corner, made admissible: it may not approach either surface, n1 . u >= 0 and
/// n2 . u >= 0 (n1, n2 the surfaces' outward unit normals). The result is the admissible velocity
/// nearest to u (its projection on that cone): u itself, u with its approach along one normal
/// removed (contact on that surface alone, which may then slide along it), or zero (held by both).
/// `active` names the surfaces in contact: those approached, or for an admissible u those it does
/// not move away from (none only when it leaves both).
/// A mean normal instead removes the approach along the mean only: under a pile tip's corner it
/// leaves half the soil's lag behind the tip, and the tip overtakes the soil under it.
struct CornerProjection {
  CornerActive active = CornerActive::none;
  std::array<double, 2> velocity{}; // the admissible relative velocity
};
CornerProjection project_on_corner(const std::array<double, 2>& u, const std::array<double, 2>& n1,
                                   const std::array<double, 2>& n2);

/// The coefficients (a, b) with f = a n1 + b n2, for normals that are not parallel: how a corner
/// node's in-plane force divides between its two surfaces.
std::array<double, 2> split_on_normals(const std::array<double, 2>& f,
                                       const std::array<double, 2>& n1,
                                       const std::array<double, 2>& n2);

} // namespace mpile
