#include "cases/monopile/monopile_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mpile {

namespace {

void require(bool ok, const std::string& parameter, const std::string& reason) {
  if (!ok) {
    throw std::invalid_argument(parameter + ": " + reason);
  }
}

/// Appends the cells between consecutive nodes as one-cell zones (the graded parts of an axis).
void append_zones(std::vector<AxisZone>& zones, const std::vector<double>& nodes) {
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
    zones.push_back({nodes[i], nodes[i + 1], 1});
  }
}

/// A uniform stretch split into cells of at most `size`.
void append_uniform(std::vector<AxisZone>& zones, double start, double end, double size) {
  const int cells = std::max(1, static_cast<int>(std::ceil((end - start) / size - 1e-9)));
  zones.push_back({start, end, cells});
}

} // namespace

std::vector<double> graded_nodes(double from, double to, double near, double uniform_length,
                                 double largest, double growth) {
  const double length = std::abs(to - from);
  std::vector<double> sizes;
  double covered = 0.0;
  double h = near;
  while (covered < length * (1.0 - 1e-9)) {
    if (covered >= uniform_length) {
      h = std::min(h * growth, largest);
    }
    sizes.push_back(h);
    covered += h;
  }
  // The last cell overshoots: scale every cell so the stretch ends exactly at `to`. The graded
  // cells shrink by less than one cell's share; the uniform ones keep their size when the
  // overshoot can be taken by the graded part alone.
  const double excess = covered - length;
  const std::size_t uniform_cells =
      std::min(sizes.size(), static_cast<std::size_t>(std::ceil(uniform_length / near - 1e-9)));
  double graded = 0.0;
  for (std::size_t i = uniform_cells; i < sizes.size(); ++i) {
    graded += sizes[i];
  }
  if (graded > 2.0 * excess) {
    const double scale = (graded - excess) / graded;
    for (std::size_t i = uniform_cells; i < sizes.size(); ++i) {
      sizes[i] *= scale;
    }
  } else {
    for (double& s : sizes) {
      s *= length / covered;
    }
  }
  std::vector<double> nodes{from};
  const double direction = to > from ? 1.0 : -1.0;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    nodes.push_back(i + 1 == sizes.size() ? to : nodes.back() + direction * sizes[i]);
  }
  if (direction < 0.0) {
    std::reverse(nodes.begin(), nodes.end());
  }
  return nodes;
}

MonopileGeometry build_monopile_geometry(const MonopileParameters& p) {
  require(p.diameter > 0.0, "diameter", "must be positive");
  require(p.wall_thickness > 0.0 && p.wall_thickness < p.diameter / 2.0, "wall_thickness",
          "must be positive and less than the radius");
  require(p.fine_cell > 0.0, "fine_cell", "must be positive");
  require(p.fine_width >= 0.0, "fine_width", "must not be negative");
  require(p.coarse_cell >= p.fine_cell, "coarse_cell", "must be at least fine_cell");
  require(p.shaft_cell >= p.fine_cell, "shaft_cell", "must be at least fine_cell");
  require(p.growth >= 1.0 && p.growth <= 2.0, "growth", "must lie in [1, 2]");
  require(p.head_room > 0.0, "head_room", "must be positive");
  require(p.band_below > 0.0, "band_below", "must be positive");
  require(p.band_above > 0.0, "band_above", "must be positive");

  MonopileGeometry g;
  g.outer_radius = p.diameter / 2.0;
  g.inner_radius = g.outer_radius - p.wall_thickness;
  g.surface = p.soil_depth;
  g.tip = p.soil_depth - p.embedment;
  require(g.outer_radius + p.fine_width + p.fine_cell < p.soil_width, "soil_width",
          "must exceed the pile's outer radius plus fine_width and a cell");
  require(g.inner_radius > p.fine_cell, "diameter",
          "the pile's inner radius must exceed fine_cell (room for the soil plug)");
  require(p.embedment > 0.0, "embedment", "must be positive");
  require(p.embedment < p.pile_length, "embedment", "must be less than pile_length");
  g.band_bottom = g.tip - p.band_below;
  g.band_top = g.tip + p.band_above;
  require(g.band_bottom > 2.0 * p.fine_cell, "band_below",
          "the moving band reaches the bottom of the soil (soil_depth - embedment - band_below "
          "must leave room for cells below it)");
  require(g.band_top < g.surface, "band_above",
          "the moving band reaches the soil surface (band_above must be less than embedment)");

  // r: graded from the axis to the fine zone inside the wall, the wall as one cell, then fine
  // and graded outwards.
  const double inside_uniform = std::min(p.fine_width, g.inner_radius);
  append_zones(g.r_zones, graded_nodes(g.inner_radius, 0.0, p.fine_cell, inside_uniform,
                                       p.coarse_cell, p.growth));
  g.r_zones.push_back({g.inner_radius, g.outer_radius, 1});
  append_zones(g.r_zones, graded_nodes(g.outer_radius, p.soil_width, p.fine_cell, p.fine_width,
                                       p.coarse_cell, p.growth));

  // y: graded from the band down to the bottom, uniform fine in the band, graded from the band up
  // to the surface (at most shaft_cell along the shaft), then uniform to the top of the grid.
  require(p.travel > 0.0, "travel", "must be positive");
  require(g.band_bottom - p.travel > 2.0 * p.fine_cell, "travel",
          "the band's travel reaches the bottom of the soil (make the soil deeper or the travel "
          "shorter)");
  append_zones(g.y_zones,
               graded_nodes(g.band_bottom, 0.0, p.fine_cell, 0.0, p.coarse_cell, p.growth));
  append_uniform(g.y_zones, g.band_bottom, g.band_top, p.fine_cell);
  const std::vector<double> shaft =
      graded_nodes(g.band_top, g.surface, p.fine_cell, 0.0, p.shaft_cell, p.growth);
  append_zones(g.y_zones, shaft);
  const double top = g.surface + p.head_room;
  append_uniform(g.y_zones, g.surface, top, shaft[shaft.size() - 1] - shaft[shaft.size() - 2]);

  g.pile = {g.inner_radius, g.outer_radius, g.tip, top};
  g.soil_below_tip = {0.0, p.soil_width, 0.0, g.tip};
  g.soil_plug = {0.0, g.inner_radius, g.tip, g.surface};
  g.soil_outside = {g.outer_radius, p.soil_width, g.tip, g.surface};
  return g;
}

double MonopileGeometry::pile_mass(const MonopileParameters& p, double density) const {
  return density * p.pile_length * (outer_radius * outer_radius - inner_radius * inner_radius) /
         2.0;
}

double MonopileGeometry::pile_polar_inertia(const MonopileParameters& p, double density) const {
  const double r1 = inner_radius * inner_radius;
  const double r2 = outer_radius * outer_radius;
  return density * p.pile_length * (r2 * r2 - r1 * r1) / 4.0;
}

} // namespace mpile
