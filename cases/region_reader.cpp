#include "cases/region_reader.hpp"

#include "cases/case_spec.hpp"
#include "engine/structures/contact.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

namespace mpile {

namespace {

std::string grid_extent(const GradedAxis& r, const GradedAxis& y) {
  std::ostringstream s;
  s << "r from " << r.start() << " to " << r.end() << ", y from " << y.start() << " to " << y.end();
  return s.str();
}

std::string point_text(const Point& p) {
  std::ostringstream s;
  s << "(" << p[0] << ", " << p[1] << ")";
  return s.str();
}

Region read_rectangle(TomlTable& body, TomlTable& region, GeometryMode mode, const GradedAxis& r,
                      const GradedAxis& y) {
  const auto rs = region.numbers("r", 2);
  const auto ys = region.numbers("y", 2);
  if (!(rs[1] > rs[0])) {
    region.fail("r", "must be [r_min, r_max] with r_max > r_min");
  }
  if (!(ys[1] > ys[0])) {
    region.fail("y", "must be [y_min, y_max] with y_max > y_min");
  }
  region.finish();
  if (mode == GeometryMode::axisymmetric && rs[0] < 0.0) {
    body.fail("region", "reaches r < 0, behind the axis");
  }
  if (rs[0] < r.start() || rs[1] > r.end() || ys[0] < y.start() || ys[1] > y.end()) {
    body.fail("region", "lies outside the grid (" + grid_extent(r, y) + ")");
  }
  return Rectangle{rs[0], rs[1], ys[0], ys[1]};
}

Region read_polygon(TomlTable& region, GeometryMode mode, const GradedAxis& r,
                    const GradedAxis& y) {
  const TomlValue& raw = region.raw("polygon");
  if (!raw.is_array()) {
    region.fail("polygon", "expected an array of vertices [[r0, y0], [r1, y1], ...]");
  }
  std::vector<Point> vertices;
  for (const TomlValue& item : raw.as_array()) {
    const bool pair =
        item.is_array() && item.as_array().size() == 2 &&
        std::all_of(item.as_array().begin(), item.as_array().end(),
                    [](const TomlValue& x) { return x.is_floating() || x.is_integer(); });
    if (!pair) {
      region.fail("polygon", "expected [[r0, y0], [r1, y1], ...]: vertex " +
                                 std::to_string(vertices.size()) + " is not a pair of numbers");
    }
    const Point p{as_number(item.as_array()[0]), as_number(item.as_array()[1])};
    if (!std::isfinite(p[0]) || !std::isfinite(p[1])) {
      region.fail("polygon", "vertex " + std::to_string(vertices.size()) +
                                 " has a coordinate that is not "
                                 "finite");
    }
    vertices.push_back(p);
  }
  region.finish();
  std::optional<Region> polygon;
  try {
    polygon = Region::polygon(vertices);
  } catch (const std::invalid_argument& e) {
    region.fail("polygon", e.what());
  }
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const Point& p = vertices[k];
    const std::string vertex = "vertex " + std::to_string(k) + " " + point_text(p);
    if (mode == GeometryMode::axisymmetric && p[0] < 0.0) {
      region.fail("polygon", vertex + " lies behind the axis (r < 0)");
    }
    if (p[0] < r.start() || p[0] > r.end() || p[1] < y.start() || p[1] > y.end()) {
      region.fail("polygon", vertex + " lies outside the grid (" + grid_extent(r, y) + ")");
    }
  }
  return *polygon;
}

Region read_circle(TomlTable& region, GeometryMode mode, const GradedAxis& r, const GradedAxis& y) {
  TomlTable circle = region.table("circle");
  const auto centre = circle.numbers("centre", 2);
  CircleSpec read;
  circle.read_into(read);
  const double radius = read.radius;
  circle.finish();
  region.finish();
  double r_min = centre[0] - radius;
  if (mode == GeometryMode::axisymmetric) {
    if (centre[0] < 0.0) {
      circle.fail("centre", "lies behind the axis (r < 0)");
    }
    if (centre[0] > 0.0 && r_min < 0.0) {
      circle.fail(&CircleSpec::radius,
                  "reaches behind the axis: centre the circle on the axis (a sphere) or "
                  "keep the radius within the centre's r (a torus)");
    }
    r_min = std::max(r_min, 0.0); // a sphere: the half at r >= 0
  }
  // Centre plus radius need not round to a grid line the user meant it to touch.
  const double tolerance = 1e-9 * std::max({1.0, r.end() - r.start(), y.end() - y.start()});
  if (r_min < r.start() - tolerance || centre[0] + radius > r.end() + tolerance ||
      centre[1] - radius < y.start() - tolerance || centre[1] + radius > y.end() + tolerance) {
    region.fail("circle", "reaches outside the grid (" + grid_extent(r, y) + ")");
  }
  return Region::circle({centre[0], centre[1]}, radius);
}

} // namespace

Region read_region(TomlTable& body, GeometryMode mode, const GradedAxis& r, const GradedAxis& y) {
  TomlTable region = body.table("region");
  const bool rectangle = region.has("r") || region.has("y");
  const bool polygon = region.has("polygon");
  const bool circle = region.has("circle");
  const char* shapes = "{ r = [r_min, r_max], y = [y_min, y_max] }, { polygon = [[r0, y0], [r1, "
                       "y1], ...] } or { circle = { centre = [r, y], radius = R } }";
  if (rectangle + polygon + circle > 1) {
    region.fail(circle ? "circle" : "polygon",
                std::string("give one shape, not several: ") + shapes);
  }
  if (polygon) {
    return read_polygon(region, mode, r, y);
  }
  if (circle) {
    return read_circle(region, mode, r, y);
  }
  if (!rectangle) {
    region.finish(); // a misspelt shape is reported as such
    body.fail("region", std::string("needs a shape: ") + shapes);
  }
  return read_rectangle(body, region, mode, r, y);
}

std::vector<std::string> read_outline_surfaces(TomlTable& contact, const ContactSpec& read,
                                               const Region& region, const std::string& name) {
  const std::string& surface_key = contact.key_of(&ContactSpec::surface);
  switch (region.shape()) {
  case Region::Shape::rectangle: {
    if (contact.has(surface_key)) {
      contact.fail(surface_key, "an outline has four edges: name them in surfaces = { bottom = "
                                "..., right = ..., top = ..., left = ... }");
    }
    std::vector<std::string> surfaces{"bottom", "right", "top", "left"};
    if (contact.has("surfaces") && !contact.raw("surfaces").is_table()) {
      contact.fail("surfaces", "body '" + name +
                                   "' is a rectangle: name its edges in a table { "
                                   "bottom = ..., right = ..., top = ..., left = "
                                   "... }");
    }
    if (std::optional<TomlTable> table = contact.optional_table("surfaces")) {
      // Given a table, edges it does not name are not contact surfaces.
      RectangleSurfaces named;
      table->read_into(named);
      for (std::size_t e = 0; e < rectangle_edges.size(); ++e) {
        surfaces[e] = named.*rectangle_edges[e];
        if (table->has(table->key_of(rectangle_edges[e])) && surfaces[e].empty()) {
          table->fail(rectangle_edges[e],
                      "a surface name must not be empty (leave the edge out instead)");
        }
      }
      table->finish();
      if (std::all_of(surfaces.begin(), surfaces.end(),
                      [](const std::string& s) { return s.empty(); })) {
        contact.fail("surfaces", "names no edge: give at least one of bottom, right, top, left");
      }
    }
    return surfaces;
  }
  case Region::Shape::circle: {
    if (contact.has("surfaces")) {
      contact.fail("surfaces", "body '" + name +
                                   "' is a circle, outlined as one surface: name "
                                   "it with surface = \"...\"");
    }
    const std::string surface = contact.has(surface_key) ? read.surface : "surface";
    if (surface.empty()) {
      contact.fail(surface_key, "a surface name must not be empty");
    }
    return {surface};
  }
  case Region::Shape::polygon:
    break;
  }
  const std::size_t n = region.vertices().size();
  if (!region.convex()) {
    const std::size_t vertex = region.given_vertex(region.first_reflex_vertex());
    contact.fail(&ContactSpec::structure,
                 "body '" + name +
                     "' is a polygon that is not convex (it turns inwards at vertex " +
                     std::to_string(vertex) +
                     "), and outline normals (the default) need a convex outline: use normals = "
                     "\"mass_gradient\", or split the structure into convex bodies");
  }
  if (contact.has(surface_key)) {
    contact.fail(surface_key, "body '" + name +
                                  "' is a polygon: name each edge in surfaces = "
                                  "[\"...\", ...]");
  }
  const std::string expected = "an array of " + std::to_string(n) +
                               " surface names, one per edge of body '" + name +
                               "' (edge k from vertex k to the next, the last closing the "
                               "polygon; \"\" for an edge that is no contact surface)";
  const TomlValue& raw = contact.raw("surfaces");
  if (!raw.is_array() || !std::all_of(raw.as_array().begin(), raw.as_array().end(),
                                      [](const TomlValue& v) { return v.is_string(); })) {
    contact.fail("surfaces", "expected " + expected);
  }
  if (raw.as_array().size() != n) {
    contact.fail("surfaces", "expected " + expected + ", got " +
                                 std::to_string(raw.as_array().size()) + " names");
  }
  std::vector<std::string> given;
  for (const TomlValue& v : raw.as_array()) {
    given.push_back(v.as_string().str);
  }
  std::set<std::string> distinct(given.begin(), given.end());
  distinct.erase("");
  if (distinct.empty()) {
    contact.fail("surfaces", "names no edge: give at least one edge a surface name");
  }
  if (distinct.size() > max_contact_surfaces) {
    contact.fail("surfaces", "names " + std::to_string(distinct.size()) +
                                 " surfaces, more than the " +
                                 std::to_string(max_contact_surfaces) +
                                 " a structure may have: give edges that belong together one name");
  }
  // In the order the region stores its edges (counter-clockwise).
  std::vector<std::string> surfaces(n);
  for (std::size_t k = 0; k < n; ++k) {
    surfaces[k] = given[region.given_edge(k)];
  }
  return surfaces;
}

} // namespace mpile
