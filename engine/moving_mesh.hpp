#pragma once

#include <string>
#include <vector>

namespace mpile {

/// The moving mesh of physics.md section 7 (after Al-Kafaji 2013) on a rectilinear grid: the
/// y-lines of a band around the pile tip translate with a rigid body, so the tip stays on its grid
/// line; the lines between the band and the bottom of the grid are compressed (or stretched)
/// linearly, and those between the band and the top likewise. The bottom and top lines stay put,
/// or, with stretch limits, every line below the lower limit and above the upper one (a loaded soil
/// surface under a rod that reaches above it). The r-lines never move (the pile walls stay on
/// theirs: the pile only translates along y).
struct MovingMesh {
  int rigid_body = 0;  // index into Scene::rigid_bodies
  int band_bottom = 0; // index of the lowest y-line that moves with the body
  int band_top = 0;    // index of the highest
  /// Indices of the lines beyond which nothing moves; -1: the grid's first and last lines.
  int stretch_bottom = -1;
  int stretch_top = -1;
  std::vector<double> reference_y; // the y-lines when the body is at its initial position
  /// How far (m) the band may move either way; 0: until a zone beside it is squeezed. Particles
  /// are seeded once, from the cells at the start: a band carried into soil seeded for coarser
  /// cells leaves some of its cells without particles, and the soil above such a row of empty
  /// cells is no longer connected to the soil below it (it falls).
  double travel = 0.0;

  /// The y-lines for a body displaced by `offset` (m) from its initial position. Throws
  /// std::runtime_error when the band would move beyond its travel, or squeeze a zone between it
  /// and a stretch limit (the grid's bottom or top by default) to a tenth.
  std::vector<double> lines_at(double offset) const;

private:
  static std::size_t index(int i) { return static_cast<std::size_t>(i); }
  std::size_t lower_index() const { return stretch_bottom < 0 ? 0 : index(stretch_bottom); }
  std::size_t upper_index() const {
    return stretch_top < 0 ? reference_y.size() - 1 : index(stretch_top);
  }
  double lower_limit() const { return reference_y[lower_index()]; }
  double upper_limit() const { return reference_y[upper_index()]; }
};

} // namespace mpile
