#include "engine/structures/surface_split.hpp"

#include <cassert>
#include <cmath>

namespace mpile {

bool split_over_surfaces(const std::array<double, 3>& force, std::span<const double> share,
                         std::span<const std::array<double, 2>> normal,
                         std::span<std::array<double, 3>> part) {
  assert(share.size() == normal.size() && share.size() == part.size());
  std::array<double, 2> mean{0.0, 0.0};
  for (std::size_t q = 0; q < share.size(); ++q) {
    mean[0] += share[q] * normal[q][0];
    mean[1] += share[q] * normal[q][1];
  }
  const double squared = mean[0] * mean[0] + mean[1] * mean[1];
  if (squared < opposed_surfaces_mean_normal * opposed_surfaces_mean_normal) {
    for (std::size_t q = 0; q < share.size(); ++q) {
      part[q] = {share[q] * force[0], share[q] * force[1], share[q] * force[2]};
    }
    return false;
  }
  // p mean + tau rot(mean) = f, with rot(mean) orthogonal to mean and as long.
  const double pressure = (force[0] * mean[0] + force[1] * mean[1]) / squared;
  const double shear = (-force[0] * mean[1] + force[1] * mean[0]) / squared;
  for (std::size_t q = 0; q < share.size(); ++q) {
    const auto& n = normal[q];
    part[q] = {share[q] * (pressure * n[0] - shear * n[1]),
               share[q] * (pressure * n[1] + shear * n[0]), share[q] * force[2]};
  }
  return true;
}

} // namespace mpile
