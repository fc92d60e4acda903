#pragma once

// The seed paper's monopile model (its section 3, Table 1 and Figure 2) from a few parameters: an
// axisymmetric domain of sand with an open-ended pile, its walls and tip on grid lines, a grid
// that is fine at the wall and around the tip and coarse far away, and the band of y-lines that
// moves with the pile (physics.md section 7).

#include "engine/graded_axis.hpp"
#include "engine/particle_fill.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace mpile {

struct MonopileParameters {
  // Pile (Table 1); the whole pile's mass and polar inertia come from these and its density.
  double pile_length = 14.0;
  double diameter = 0.746; // outer
  double wall_thickness = 0.0159;
  double embedment = 3.0; // initial depth of the tip below the soil surface
  // Soil: r from the axis to soil_width, y from 0 (bottom) to soil_depth (the surface).
  double soil_width = 5.0;
  double soil_depth = 10.0;
  double head_room = 1.0; // grid above the surface, so the meshed pile top stays above the soil
  // Mesh.
  double fine_cell = 0.05;  // cell size at the wall, in the band around the tip
  double fine_width = 0.2;  // width of the uniform fine zone on each side of the wall
  double coarse_cell = 0.5; // the largest cell far from the pile
  double shaft_cell = 0.1;  // the largest cell along the shaft, between the band and the surface
  double growth = 1.15;     // ratio of neighbouring cell sizes where the mesh coarsens
  /// Cells across the wall. 1: the wall is one cell with fine cells right beside it (the seed's
  /// mesh); more: cells of wall_thickness / wall_cells across the wall, beside it and in y at the
  /// tip (inside the band, so they move with the pile), growing by `growth` to fine_cell; the
  /// band's ends are then rounded out to whole fine cells after that growth.
  int wall_cells = 1;
  double band_below = 0.4; // the band that moves with the pile: this far below the tip
  double band_above = 0.4; // and this far above it
  /// The deepest (m) the band may be carried down: the soil below the band is seeded for the cells
  /// it will have then (cases/case_builder.cpp), and a run that goes further stops.
  double travel = 0.7;
};

/// What the parameters give: grid zones (one cell per zone where the mesh grades), the regions of
/// the pile and the three soil bodies, and the moving band's lines.
struct MonopileGeometry {
  std::vector<AxisZone> r_zones;
  std::vector<AxisZone> y_zones;
  double inner_radius = 0.0; // r1: the internal shaft
  double outer_radius = 0.0; // r2: the external shaft
  double tip = 0.0;          // y of the tip
  double surface = 0.0;      // y of the soil surface
  Rectangle pile;            // the meshed part of the pile: from the tip to the top of the grid
  Rectangle soil_below_tip;
  Rectangle soil_plug;
  Rectangle soil_outside;
  double band_bottom = 0.0; // y of the band's lowest line
  double band_top = 0.0;    // y of its highest line

  /// Mass and polar inertia per radian of the whole pile (a thin-walled tube of the given
  /// length): M = rho L (r2^2 - r1^2) / 2, J = rho L (r2^4 - r1^4) / 4.
  double pile_mass(const MonopileParameters& p, double density) const;
  double pile_polar_inertia(const MonopileParameters& p, double density) const;
};

/// A parameter set the geometry refuses: `what()` is "parameter: reason", the parameter the check
/// is about; `with` the other parameters it compares that one with (a reader blames whichever of
/// them the case wrote, not always the first: a diameter in mm is refused by soil_width's check).
struct MonopileParameterError : std::invalid_argument {
  MonopileParameterError(std::string parameter, std::vector<std::string> compared, std::string why);
  std::string parameter;
  std::vector<std::string> with;
  std::string reason;
};

/// Builds the geometry; throws MonopileParameterError naming the parameter that is inconsistent
/// (a pile wider than the soil, an embedment deeper than the soil, a band that leaves no room).
MonopileGeometry build_monopile_geometry(const MonopileParameters& p);

/// Node coordinates from `from` to `to` (either order of size): cells of `near` next to `from`,
/// uniform for `uniform_length`, then growing by `growth` per cell up to `largest`; the sizes are
/// scaled at the end so that the last node lands exactly on `to`. Returned in increasing order.
std::vector<double> graded_nodes(double from, double to, double near, double uniform_length,
                                 double largest, double growth);

} // namespace mpile
