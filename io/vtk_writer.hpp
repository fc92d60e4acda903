#pragma once

#include "engine/scene.hpp"

#include <string>
#include <utility>
#include <vector>

namespace mpile {

/// A time series of snapshots for ParaView: one binary, zlib-compressed .vtu file of the particles
/// per snapshot, and one .pvd collection listing them with their times, rewritten (atomically)
/// after every snapshot so that ParaView can open the run while it goes on. With grid snapshots
/// on, a second series of .vtr files holds the nodal mass and velocity, and the contact force,
/// traction, surface and state of the last step.
class SnapshotWriter {
public:
  SnapshotWriter(std::string directory, bool grid_snapshots);

  /// Writes the particles (and grid) at `time`; returns the particle file's name.
  std::string write(const Scene& scene, double time);

  /// Snapshots written so far (time, particle file), for a checkpoint; restore() takes them back.
  const std::vector<std::pair<double, std::string>>& entries() const { return particles_; }
  void restore(std::vector<std::pair<double, std::string>> entries);

private:
  void write_collection(const std::string& name,
                        const std::vector<std::pair<double, std::string>>& entries) const;

  std::string directory_;
  bool grid_snapshots_;
  std::vector<std::pair<double, std::string>> particles_;
  std::vector<std::pair<double, std::string>> grids_;
};

/// Writes the particles of a scene to one .vtu file (the fields listed in docs/case-format.md).
void write_particles_vtu(const Scene& scene, const std::string& path);

} // namespace mpile
