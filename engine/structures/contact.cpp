#include "engine/structures/contact.hpp"

#include "engine/shape_functions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace mpile {

StructureOutline StructureOutline::rectangle(double r0, double r1, double y0, double y1, int bottom,
                                             int right, int top, int left) {
  StructureOutline outline;
  outline.vertices = {{r0, y0}, {r1, y0}, {r1, y1}, {r0, y1}};
  outline.edge_surface = {bottom, right, top, left};
  return outline;
}

StructureOutline region_outline(const Region& region, GeometryMode mode,
                                const std::vector<int>& surface) {
  StructureOutline outline;
  if (region.shape() != Region::Shape::circle) {
    outline.vertices = region.vertices();
    outline.edge_surface = surface;
    return outline;
  }
  const Point c = region.centre();
  const double radius = region.radius();
  const bool sphere = mode == GeometryMode::axisymmetric && c[0] == 0.0;
  // From the bottom, counter-clockwise: all the way round, or for a sphere up the right half to
  // the top.
  const int edges = sphere ? circle_outline_edges / 2 : circle_outline_edges;
  const double step = 2.0 * std::numbers::pi / circle_outline_edges;
  for (int k = 0; k < (sphere ? edges + 1 : edges); ++k) {
    const double angle = -0.5 * std::numbers::pi + k * step;
    outline.vertices.push_back({c[0] + radius * std::cos(angle), c[1] + radius * std::sin(angle)});
    outline.edge_surface.push_back(surface.at(0));
  }
  if (sphere) {
    // The bottom and the top on the axis exactly; the closing edge runs down the axis.
    outline.vertices.front()[0] = 0.0;
    outline.vertices.back()[0] = 0.0;
    outline.edge_surface.back() = -1;
  }
  return outline;
}

void StructureOutline::translate(double dr, double dy) {
  for (auto& v : vertices) {
    v[0] += dr;
    v[1] += dy;
  }
}

void StructureOutline::rotate(double angle, double r, double y) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  for (auto& v : vertices) {
    const double dr = v[0] - r;
    const double dy = v[1] - y;
    v[0] = r + c * dr - s * dy;
    v[1] = y + s * dr + c * dy;
  }
}

bool StructureOutline::contains(double r, double y) const {
  bool inside = false;
  const std::size_t n = vertices.size();
  for (std::size_t e = 0, previous = n - 1; e < n; previous = e++) {
    const auto& a = vertices[previous];
    const auto& b = vertices[e];
    // Edges whose y-range holds y (half-open, so a vertex is counted once) and that pass to the
    // right of the point.
    if ((a[1] > y) != (b[1] > y) && r < a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0])) {
      inside = !inside;
    }
  }
  return inside;
}

std::array<double, 4> StructureOutline::bounds() const {
  std::array<double, 4> box{
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const auto& v : vertices) {
    box[0] = std::min(box[0], v[0]);
    box[1] = std::max(box[1], v[0]);
    box[2] = std::min(box[2], v[1]);
    box[3] = std::max(box[3], v[1]);
  }
  return box;
}

std::vector<SurfaceAreas> surface_areas(const StructureOutline& outline, std::size_t surfaces,
                                        GeometryMode mode) {
  std::vector<SurfaceAreas> areas(surfaces);
  const bool axisymmetric = mode == GeometryMode::axisymmetric;
  const std::size_t edges = outline.vertices.size();
  for (std::size_t e = 0; e < edges; ++e) {
    const int surface = outline.edge_surface[e];
    if (surface < 0 || static_cast<std::size_t>(surface) >= surfaces) {
      continue;
    }
    const auto& a = outline.vertices[e];
    const auto& b = outline.vertices[(e + 1) % edges];
    // r is linear along the edge: the integral of r |dy| is |dy| times the mean radius, and that
    // of r |dr| is |r_b^2 - r_a^2| / 2.
    const double dr = std::abs(b[0] - a[0]);
    const double dy = std::abs(b[1] - a[1]);
    areas[surface].plan += axisymmetric ? 0.5 * std::abs(b[0] * b[0] - a[0] * a[0]) : dr;
    areas[surface].side += axisymmetric ? dy * 0.5 * (a[0] + b[0]) : dy;
  }
  return areas;
}

OutlineDistance::OutlineDistance(const StructureOutline& outline) {
  const std::size_t edges = outline.vertices.size();
  for (std::size_t e = 0; e < edges; ++e) {
    const auto& a = outline.vertices[e];
    const auto& b = outline.vertices[(e + 1) % edges];
    const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
    if (length > 0.0) {
      const double n_r = (b[1] - a[1]) / length;
      const double n_y = -(b[0] - a[0]) / length;
      lines_.push_back({n_r, n_y, n_r * a[0] + n_y * a[1]});
    }
  }
}

void ContactPair::allocate(std::size_t node_count) {
  area.assign(node_count, 0.0);
  surface_area.assign(node_count * surfaces.size(), 0.0);
  normal.assign(node_count, {0.0, 0.0});
  node_force.assign(node_count, {0.0, 0.0, 0.0});
  node_dissipation.assign(node_count, 0.0);
  state.assign(node_count, 0);
  contact_normal.assign(node_count, {0.0, 0.0});
  written = {};
  gap.assign(outline ? node_count : 0, 0.0);
  surface_gap.assign(outline && surface_gap_at_node ? node_count : 0, SurfaceGap{});
  // Sums of the last step survive (a restart restores them before the solver sizes the rest).
  surface_force.resize(surfaces.size(), {0.0, 0.0, 0.0});
  surface_torque.resize(surfaces.size(), 0.0);
  surface_pore_force.resize(surfaces.size(), {0.0, 0.0});
  outlined_nodes.clear();
}

namespace {

/// Parameters in (0, 1) where the segment a + s (b - a) crosses the grid lines of one axis.
void add_crossings(const GradedAxis& axis, double a, double b, std::vector<double>& s) {
  if (a == b) {
    return;
  }
  const double lo = std::min(a, b);
  const double hi = std::max(a, b);
  for (int i = 0; i < axis.node_count(); ++i) {
    const double x = axis.node(i);
    if (x > lo && x < hi) {
      s.push_back((x - a) / (b - a));
    }
  }
}

/// The cell holding a point, taking the last cell for a point on the far grid boundary.
int cell_of(const GradedAxis& axis, double x) {
  const int c = axis.locate(x);
  if (c < 0 && x == axis.end()) {
    return axis.cell_count() - 1;
  }
  return c;
}

/// A coordinate within rounding of one of its cell's lines, put on that line. A structure moved
/// along with its grid line (a pile's tip on the moving mesh's band) is translated step by step
/// while the line is set from the total displacement, so the two drift apart by rounding, either
/// way. Off by 1e-15 of a cell, the edge would give the nodes one cell away a share of 1e-15 of a
/// cell's area: enough to make them outline nodes, with the edge's normal and surface, inside the
/// wall or in the soil below the tip. A billionth of a cell is far beyond rounding and far below
/// any geometry a case can mean.
double on_cell_line(const GradedAxis& axis, int cell, double x) {
  const double a = axis.node(cell);
  const double b = axis.node(cell + 1);
  const double tolerance = 1e-9 * (b - a);
  if (std::abs(x - a) <= tolerance) {
    return a;
  }
  if (std::abs(x - b) <= tolerance) {
    return b;
  }
  return x;
}

} // namespace

void integrate_outline(const Grid& grid, GeometryMode mode, ContactPair& pair) {
  const std::size_t surfaces = pair.surface_count();
  for (const int node : pair.outlined_nodes) {
    const auto i = static_cast<std::size_t>(node);
    pair.area[i] = 0.0;
    pair.normal[i] = {0.0, 0.0};
    std::fill_n(pair.surface_area.begin() + static_cast<std::ptrdiff_t>(i * surfaces), surfaces,
                0.0);
  }
  pair.outlined_nodes.clear();
  const StructureOutline& outline = *pair.outline;
  const std::size_t edges = outline.vertices.size();
  // Two-point Gauss on [0, 1].
  const double g = 0.5 / std::sqrt(3.0);
  const double gauss[2] = {0.5 - g, 0.5 + g};
  std::vector<double> cuts;
  for (std::size_t e = 0; e < edges; ++e) {
    const auto& a = outline.vertices[e];
    const auto& b = outline.vertices[(e + 1) % edges];
    const double dr = b[0] - a[0];
    const double dy = b[1] - a[1];
    const double length = std::hypot(dr, dy);
    if (length == 0.0 || outline.edge_surface[e] < 0) {
      continue; // a degenerate edge, or one that is not a contact surface
    }
    const std::array<double, 2> n{dy / length, -dr / length};
    const auto surface = static_cast<std::size_t>(outline.edge_surface[e]);
    cuts.assign({0.0, 1.0});
    add_crossings(grid.r_axis(), a[0], b[0], cuts);
    add_crossings(grid.y_axis(), a[1], b[1], cuts);
    std::sort(cuts.begin(), cuts.end());
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      const double s0 = cuts[k];
      const double s1 = cuts[k + 1];
      if (s1 <= s0) {
        continue;
      }
      const double s_mid = 0.5 * (s0 + s1);
      const int cr = cell_of(grid.r_axis(), a[0] + s_mid * dr);
      const int cy = cell_of(grid.y_axis(), a[1] + s_mid * dy);
      if (cr < 0 || cy < 0) {
        continue; // this piece of the outline lies outside the grid
      }
      for (const double t : gauss) {
        const double s = s0 + t * (s1 - s0);
        const double r = on_cell_line(grid.r_axis(), cr, a[0] + s * dr);
        const double y = on_cell_line(grid.y_axis(), cy, a[1] + s * dy);
        const double weight =
            0.5 * (s1 - s0) * length * (mode == GeometryMode::axisymmetric ? r : 1.0);
        const CellWeights w = bilinear_weights(grid, cr, cy, r, y);
        for (int q = 0; q < 4; ++q) {
          const double share = weight * w.N[q];
          if (share == 0.0) {
            continue;
          }
          const auto i = static_cast<std::size_t>(w.node[q]);
          if (pair.area[i] == 0.0) {
            pair.outlined_nodes.push_back(w.node[q]);
          }
          pair.area[i] += share;
          pair.surface_area[i * surfaces + surface] += share;
          pair.normal[i][0] += share * n[0];
          pair.normal[i][1] += share * n[1];
        }
      }
    }
  }
  for (const int node : pair.outlined_nodes) {
    auto& n = pair.normal[static_cast<std::size_t>(node)];
    const double length = std::hypot(n[0], n[1]);
    if (length > 0.0) {
      n[0] /= length;
      n[1] /= length;
    }
  }
}

namespace {

/// Calls visit(distance, normal, surface) for each edge of the outline that bounds a surface (of
/// surface `only_surface` when it is not negative), with the distance from (r, y) to the edge and
/// the edge's outward normal.
template <class Visit>
void visit_edges(const StructureOutline& outline, double r, double y, int only_surface,
                 Visit&& visit) {
  const std::size_t edges = outline.vertices.size();
  for (std::size_t e = 0; e < edges; ++e) {
    const auto& a = outline.vertices[e];
    const auto& b = outline.vertices[(e + 1) % edges];
    const double dr = b[0] - a[0];
    const double dy = b[1] - a[1];
    const double length2 = dr * dr + dy * dy;
    if (length2 == 0.0 || outline.edge_surface[e] < 0 ||
        (only_surface >= 0 && outline.edge_surface[e] != only_surface)) {
      continue;
    }
    const double s = std::clamp(((r - a[0]) * dr + (y - a[1]) * dy) / length2, 0.0, 1.0);
    const double distance = std::hypot(r - (a[0] + s * dr), y - (a[1] + s * dy));
    const double length = std::sqrt(length2);
    visit(distance, std::array<double, 2>{dy / length, -dr / length}, outline.edge_surface[e]);
  }
}

} // namespace

std::array<double, 2> nearest_edge_normal(const StructureOutline& outline, double r, double y,
                                          int surface) {
  double best = std::numeric_limits<double>::infinity();
  std::array<double, 2> normal{0.0, 0.0};
  visit_edges(outline, r, y, surface, [&](double distance, const std::array<double, 2>& n, int) {
    if (distance < best) {
      best = distance;
      normal = n;
    }
  });
  return normal;
}

EdgeNormal facing_edge_normal(const StructureOutline& outline, double r, double y,
                              const std::array<double, 2>& direction) {
  double best = std::numeric_limits<double>::infinity();
  visit_edges(outline, r, y, -1, [&](double distance, const std::array<double, 2>&, int) {
    best = std::min(best, distance);
  });
  // A node on a line of symmetry of the outline (midway between a wall's faces, or as far from
  // the tip as from a face) is as near, to rounding, to several edges: rounding must not choose.
  const double tie = best * (1.0 + 1e-9) + 1e-12;
  EdgeNormal chosen;
  double most = -std::numeric_limits<double>::infinity();
  visit_edges(outline, r, y, -1,
              [&](double distance, const std::array<double, 2>& n, int edge_surface) {
                const double along = direction[0] * n[0] + direction[1] * n[1];
                if (distance <= tie && along > most) {
                  most = along;
                  chosen = {n, edge_surface};
                }
              });
  return chosen;
}

} // namespace mpile
