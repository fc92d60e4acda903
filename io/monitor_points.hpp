#pragma once

// Monitor points: single material points whose position, stress, strain and state go into
// history.h5 at every row, so that the stress path of the soil beside a pile tip can be plotted.
// A monitor named by a position follows the particle nearest it at the start of the run (by its
// id, through every re-sort), since material points move with the soil.

#include "cases/case_spec.hpp"
#include "engine/scene.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace mpile {

/// The particle id a monitor follows: the one given, or the soil particle nearest the position
/// given (rigid bodies left out). CaseError when the id does not exist, or when no soil particle
/// lies within reach of the position (two of its half-diagonals).
std::int32_t monitored_particle(const MonitorSpec& monitor, const Scene& scene);

/// The names of the quantities recorded for a particle of a material, with their units, in the
/// order monitor_values writes them.
struct MonitorQuantity {
  std::string name;
  std::string unit;
};
std::vector<MonitorQuantity> monitor_quantities(const Scene& scene, std::uint16_t material);

/// The values of the particle with this id (NaN for every one when it is no longer in the scene,
/// as a rigid body's particle that left the grid).
std::vector<double> monitor_values(const Scene& scene, std::int32_t id, std::uint16_t material);

} // namespace mpile
