#pragma once

#include <numbers>

namespace mpile {

/// An angle given in degrees (as case files give friction and dilatancy angles) in radians.
inline double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

} // namespace mpile
