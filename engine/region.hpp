#pragma once

// The part of the r-y plane a body fills at the start: a rectangle, a simple polygon or a circle
// (in axisymmetric mode a ring of rectangular or polygonal section, a torus, or a sphere when the
// circle is centred on the axis).

#include <array>
#include <cstddef>
#include <vector>

namespace mpile {

/// An axis-aligned region of the r-y plane, edges included.
struct Rectangle {
  double r_min, r_max, y_min, y_max;
  bool contains(double r, double y) const {
    return r >= r_min && r <= r_max && y >= y_min && y <= y_max;
  }
};

using Point = std::array<double, 2>; // (r, y)

class Region {
public:
  enum class Shape { rectangle, polygon, circle };

  /// A rectangle is a region (implicit, so that code written for rectangles reads as before).
  Region(const Rectangle& rectangle); // NOLINT(google-explicit-constructor)

  /// A simple polygon (at least 3 vertices, no repeated consecutive vertex, not all on one line,
  /// no two edges meeting except consecutive ones at their shared vertex), given in either
  /// orientation and stored counter-clockwise. Throws std::invalid_argument saying what is wrong.
  static Region polygon(std::vector<Point> vertices);
  /// A circle of positive radius; throws std::invalid_argument otherwise.
  static Region circle(Point centre, double radius);

  Shape shape() const { return shape_; }

  /// Whether (r, y) lies in the region. A rectangle and a circle include their boundary. A point
  /// on a polygon's edge belongs to the polygon only when the polygon lies on its +r side (above
  /// it, for a horizontal edge): two polygons that share an edge then never both hold a point of
  /// it, so bodies meeting along a slanted edge do not get two particles at one place.
  bool contains(double r, double y) const;

  /// The smallest rectangle holding the region.
  const Rectangle& bounds() const { return bounds_; }

  /// Counter-clockwise vertices: a polygon's, or a rectangle's corners from (r_min, y_min) (its
  /// edges are then bottom, right, top, left); empty for a circle.
  const std::vector<Point>& vertices() const { return vertices_; }
  /// Index, in the order the vertices were given, of stored edge k (from vertices()[k] to the
  /// next): k itself unless the polygon was given clockwise and stored reversed.
  std::size_t given_edge(std::size_t k) const;
  /// Likewise for stored vertex k.
  std::size_t given_vertex(std::size_t k) const;

  Point centre() const { return centre_; }
  double radius() const { return radius_; }

  /// Area in the r-y plane (m^2).
  double area() const;
  /// Whether no vertex turns clockwise (collinear vertices allowed); a circle is convex.
  bool convex() const;
  /// The first vertex where a polygon turns clockwise, or vertices().size() when it is convex.
  std::size_t first_reflex_vertex() const;

private:
  Region() = default;

  Shape shape_ = Shape::rectangle;
  Rectangle bounds_{0.0, 0.0, 0.0, 0.0};
  std::vector<Point> vertices_;
  bool reversed_ = false;
  Point centre_{0.0, 0.0};
  double radius_ = 0.0;
};

/// Signed area of a closed polygon (m^2): positive when counter-clockwise.
double signed_area(const std::vector<Point>& vertices);

} // namespace mpile
