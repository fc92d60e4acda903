#pragma once

// Monitor points: single material points whose position, stress, strain and state go into
// history.h5 at every row, so that the stress path of the soil beside a pile tip can be plotted.
// A monitor named by a position follows the particle nearest it at the start of the run (by its
// id, through every re-sort), since material points move with the soil; a fixed one stays at its
// point and reads the particles around it, as a transducer in the ground does.

#include "cases/case_spec.hpp"
#include "engine/scene.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace mpile {

/// The particle id a monitor follows: the one given, or the soil particle nearest the position
/// given (rigid bodies left out); -1 for a fixed monitor whose material is named, which follows
/// none. CaseError when the id does not exist, or when no soil particle lies within reach of the
/// position (two of its half-diagonals).
std::int32_t monitored_particle(const MonitorSpec& monitor, const Scene& scene);

/// The material a monitor records: a fixed monitor's named one, else that of the particle id.
std::uint16_t monitored_material(const MonitorSpec& monitor, const Scene& scene, std::int32_t id);

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

/// The values at a point fixed in space: the particles of the material weighted by their volume
/// and by the tent of the grid cell the point lies in (1 at the point, 0 one cell size away each
/// way), as a transducer reads the soil around it; r and y are where the weights centre. NaN for
/// every value where no particle of the material lies within the tent (the point in a pile, above
/// the surface). The particles' sum is in index order: the same for any thread count.
std::vector<double> fixed_point_values(const Scene& scene, std::array<double, 2> point,
                                       std::uint16_t material);

} // namespace mpile
