#include "cases/monopile_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>

namespace mpile {

namespace {

void require(bool ok, const std::string& parameter, const std::string& reason) {
  if (!ok) {
    throw MonopileParameterError(parameter, {}, reason);
  }
}

/// A check between parameters: `with` are the others it compares `parameter` with.
void require(bool ok, const std::string& parameter, std::vector<std::string> with,
             const std::string& reason) {
  if (!ok) {
    throw MonopileParameterError(parameter, std::move(with), reason);
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

/// Nodes from `from` towards `to` with cells of `start`, growing by `growth` while smaller than
/// `limit`: the transition from a resolved wall or tip to the fine cells. Returns `from` alone
/// when start is not below limit.
std::vector<double> transition_nodes(double from, double to, double start, double limit,
                                     double growth) {
  const double direction = to > from ? 1.0 : -1.0;
  std::vector<double> nodes{from};
  for (double h = start; h < limit * (1.0 - 1e-9); h *= growth) {
    nodes.push_back(nodes.back() + direction * h);
  }
  return nodes;
}

/// Nodes from `from` to `to`: a transition from cells of `start` to `fine` (see above), then
/// graded_nodes from fine with a uniform stretch of `uniform_length` (counted from `from`). A
/// remainder shorter than two fine cells is taken as whole fine cells with the transition, all but
/// its first cell scaled to land on `to`, so no sliver cell is left beside a grown one.
std::vector<double> resolved_nodes(double from, double to, double start, double fine,
                                   double uniform_length, double largest, double growth) {
  std::vector<double> nodes = transition_nodes(from, to, start, fine, growth);
  const double length = std::abs(to - from);
  const double covered = std::abs(nodes.back() - from);
  const double direction = to > from ? 1.0 : -1.0;
  if (nodes.size() > 1 && length - covered < 2.0 * fine) {
    std::vector<double> sizes;
    for (std::size_t i = 1; i < nodes.size(); ++i) {
      sizes.push_back(std::abs(nodes[i] - nodes[i - 1]));
    }
    const double whole = std::round((length - covered) / fine);
    sizes.insert(sizes.end(), static_cast<std::size_t>(whole), fine);
    const double scale = (length - sizes[0]) / (covered + whole * fine - sizes[0]);
    nodes.resize(2);
    for (std::size_t i = 1; i < sizes.size(); ++i) {
      nodes.push_back(i + 1 == sizes.size() ? to : nodes.back() + direction * sizes[i] * scale);
    }
    return nodes;
  }
  const std::vector<double> rest = graded_nodes(
      nodes.back(), to, fine, std::max(0.0, uniform_length - covered), largest, growth);
  // graded_nodes returns increasing order; continue from the transition's end in its direction.
  if (to > from) {
    nodes.insert(nodes.end(), rest.begin() + 1, rest.end());
  } else {
    nodes.insert(nodes.end(), rest.rbegin() + 1, rest.rend());
  }
  return nodes;
}

/// Increasing order, for append_zones.
std::vector<double> increasing(std::vector<double> nodes) {
  if (nodes.size() > 1 && nodes.front() > nodes.back()) {
    std::reverse(nodes.begin(), nodes.end());
  }
  return nodes;
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

MonopileParameterError::MonopileParameterError(std::string parameter_,
                                               std::vector<std::string> compared, std::string why)
    : std::invalid_argument(parameter_ + ": " + why), parameter(std::move(parameter_)),
      with(std::move(compared)), reason(std::move(why)) {}

MonopileGeometry build_monopile_geometry(const MonopileParameters& p) {
  require(p.diameter > 0.0, "diameter", "must be positive");
  require(p.wall_thickness > 0.0 && p.wall_thickness < p.diameter / 2.0, "wall_thickness",
          {"diameter"}, "must be positive and less than the radius");
  require(p.fine_cell > 0.0, "fine_cell", "must be positive");
  require(p.wall_cells >= 1 && p.wall_cells <= 16, "wall_cells", "must lie between 1 and 16");
  require(p.fine_width >= 0.0, "fine_width", "must not be negative");
  require(p.coarse_cell >= p.fine_cell, "coarse_cell", {"fine_cell"}, "must be at least fine_cell");
  require(p.shaft_cell >= p.fine_cell, "shaft_cell", {"fine_cell"}, "must be at least fine_cell");
  require(p.growth >= 1.0 && p.growth <= 2.0, "growth", "must lie in [1, 2]");
  require(p.head_room > 0.0, "head_room", "must be positive");
  require(p.band_below > 0.0, "band_below", "must be positive");
  require(p.band_above > 0.0, "band_above", "must be positive");
  require(std::isfinite(p.soil_width), "soil_width", "must be finite");
  require(std::isfinite(p.soil_depth), "soil_depth", "must be finite");
  // The axes' nodes are built one cell at a time: no axis may hold more cells than its extent in
  // its smallest cells, and a mistyped extent or cell (soil_width = 4e9 m) would take minutes and
  // gigabytes before the memory budget could refuse the grid. The cap is far above any mesh that
  // fits in memory with a cell that small across the other axis.
  {
    constexpr double max_cells = 1e7;
    const double smallest = std::min(p.fine_cell, p.wall_thickness / p.wall_cells);
    for (const auto& [extent, key, usual] :
         {std::tuple{p.soil_width, "soil_width", 5.0},
          std::tuple{p.soil_depth + p.head_room, "soil_depth", 11.0}}) {
      if (extent / smallest > max_cells) {
        // Blame whichever of the extent and the cell is further from its usual size.
        const bool extent_is_odd =
            std::abs(std::log(extent / usual)) > std::abs(std::log(0.05 / smallest));
        std::ostringstream why;
        why << "the grid could take up to " << extent / smallest << " cells of " << smallest
            << " m across " << extent << " m (at most " << max_cells
            << " along an axis): check soil_width, soil_depth and fine_cell";
        require(false, extent_is_odd ? key : "fine_cell", why.str());
      }
    }
  }

  MonopileGeometry g;
  g.outer_radius = p.diameter / 2.0;
  g.inner_radius = g.outer_radius - p.wall_thickness;
  g.surface = p.soil_depth;
  g.tip = p.soil_depth - p.embedment;
  require(g.outer_radius + p.fine_width + p.fine_cell < p.soil_width, "soil_width",
          {"diameter", "fine_width", "fine_cell"},
          "must exceed the pile's outer radius plus fine_width and a cell");
  require(g.inner_radius > p.fine_cell, "diameter", {"wall_thickness", "fine_cell"},
          "the pile's inner radius must exceed fine_cell (room for the soil plug)");
  require(p.embedment > 0.0, "embedment", "must be positive");
  require(p.embedment < p.pile_length, "embedment", {"pile_length"},
          "must be less than pile_length");
  if (!(p.embedment < p.soil_depth)) {
    std::ostringstream why;
    why << "must be less than soil_depth (" << p.soil_depth
        << " m): the tip would start below the soil";
    require(false, "embedment", {"soil_depth"}, why.str());
  }
  g.band_bottom = g.tip - p.band_below;
  g.band_top = g.tip + p.band_above;
  const double wall_cell = p.wall_thickness / p.wall_cells;
  const double near = p.wall_cells > 1 ? wall_cell : p.fine_cell;
  if (p.wall_cells > 1) {
    // The band holds the cells growing from the tip's size to fine_cell and then whole fine
    // cells: its ends are rounded out to the next of them.
    const double growing =
        std::abs(transition_nodes(g.tip, 0.0, near, p.fine_cell, p.growth).back() - g.tip);
    require(growing + p.fine_cell <= std::min(p.band_below, p.band_above), "wall_cells",
            {"wall_thickness", "fine_cell", "growth", "band_below", "band_above"},
            "the cells growing from the tip's to fine_cell take " + std::to_string(growing) +
                " m: band_below and band_above must exceed that by a fine cell");
    const auto rounded = [&](double extent) {
      return growing + std::ceil((extent - growing) / p.fine_cell - 1e-9) * p.fine_cell;
    };
    g.band_bottom = g.tip - rounded(p.band_below);
    g.band_top = g.tip + rounded(p.band_above);
  }
  require(g.band_bottom > 2.0 * p.fine_cell, "band_below", {"embedment", "soil_depth", "fine_cell"},
          "the moving band reaches the bottom of the soil (soil_depth - embedment - band_below "
          "must leave room for cells below it)");
  require(g.band_top < g.surface, "band_above", {"embedment"},
          "the moving band reaches the soil surface (band_above must be less than embedment)");

  // r: graded from the axis to the fine zone inside the wall, the wall in wall_cells cells, then
  // fine and graded outwards; a resolved wall's cells continue beside it and grow to fine_cell.
  const double inside_uniform = std::min(p.fine_width, g.inner_radius);
  append_zones(g.r_zones, increasing(resolved_nodes(g.inner_radius, 0.0, near, p.fine_cell,
                                                    inside_uniform, p.coarse_cell, p.growth)));
  g.r_zones.push_back({g.inner_radius, g.outer_radius, p.wall_cells});
  append_zones(g.r_zones, resolved_nodes(g.outer_radius, p.soil_width, near, p.fine_cell,
                                         p.fine_width, p.coarse_cell, p.growth));

  // y: graded from the band down to the bottom, uniform fine in the band, graded from the band up
  // to the surface (at most shaft_cell along the shaft), then uniform to the top of the grid.
  require(p.travel > 0.0, "travel", "must be positive");
  require(g.band_bottom - p.travel > 2.0 * p.fine_cell, "travel",
          {"embedment", "soil_depth", "band_below", "fine_cell"},
          "the band's travel reaches the bottom of the soil (make the soil deeper or the travel "
          "shorter)");
  append_zones(g.y_zones,
               graded_nodes(g.band_bottom, 0.0, p.fine_cell, 0.0, p.coarse_cell, p.growth));
  if (p.wall_cells > 1) {
    // The band: cells of the wall's at the tip, growing to fine_cell above and below it.
    const std::vector<double> below =
        resolved_nodes(g.tip, g.band_bottom, near, p.fine_cell, 0.0, p.fine_cell, p.growth);
    const std::vector<double> above =
        resolved_nodes(g.tip, g.band_top, near, p.fine_cell, 0.0, p.fine_cell, p.growth);
    append_zones(g.y_zones, increasing(below));
    append_zones(g.y_zones, above);
  } else {
    append_uniform(g.y_zones, g.band_bottom, g.band_top, p.fine_cell);
  }
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
