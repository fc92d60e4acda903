#include "engine/region.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

namespace mpile {

namespace {

double cross(const Point& a, const Point& b, const Point& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

int sign(double x) {
  return (x > 0.0) - (x < 0.0);
}

/// Whether c, collinear with segment ab, lies on it.
bool within(const Point& a, const Point& b, const Point& c) {
  return c[0] >= std::min(a[0], b[0]) && c[0] <= std::max(a[0], b[0]) &&
         c[1] >= std::min(a[1], b[1]) && c[1] <= std::max(a[1], b[1]);
}

/// Whether the closed segments ab and cd have a point in common.
bool segments_meet(const Point& a, const Point& b, const Point& c, const Point& d) {
  const int d1 = sign(cross(c, d, a));
  const int d2 = sign(cross(c, d, b));
  const int d3 = sign(cross(a, b, c));
  const int d4 = sign(cross(a, b, d));
  if (d1 * d2 < 0 && d3 * d4 < 0) {
    return true;
  }
  return (d1 == 0 && within(c, d, a)) || (d2 == 0 && within(c, d, b)) ||
         (d3 == 0 && within(a, b, c)) || (d4 == 0 && within(a, b, d));
}

std::string describe(std::size_t index, const Point& p) {
  std::ostringstream s;
  s << "vertex " << index << " (" << p[0] << ", " << p[1] << ")";
  return s.str();
}

/// Throws unless the vertices form a simple polygon; indices in the messages count from 0 in the
/// order given.
void check_simple(const std::vector<Point>& v) {
  const std::size_t n = v.size();
  if (n < 3) {
    throw std::invalid_argument("needs at least 3 vertices, got " + std::to_string(n));
  }
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t next = (k + 1) % n;
    if (v[k] == v[next]) {
      throw std::invalid_argument(
          next == 0 ? "the last vertex repeats the first: the polygon closes by itself, leave it "
                      "out"
                    : describe(next, v[next]) + " repeats the vertex before it");
    }
  }
  // Zero area: every vertex on the line through vertex 0 and the vertex farthest from it.
  std::size_t far = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (std::hypot(v[k][0] - v[0][0], v[k][1] - v[0][1]) >
        std::hypot(v[far][0] - v[0][0], v[far][1] - v[0][1])) {
      far = k;
    }
  }
  const double length = std::hypot(v[far][0] - v[0][0], v[far][1] - v[0][1]);
  const bool collinear = std::all_of(v.begin(), v.end(), [&](const Point& p) {
    return std::abs(cross(v[0], v[far], p)) <= 1e-12 * length * length;
  });
  if (collinear) {
    throw std::invalid_argument("encloses no area: its vertices lie on one line");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Point& a = v[i];
    const Point& b = v[(i + 1) % n];
    // The next edge shares vertex i + 1 with this one: it may only fold back onto it.
    const Point& c = v[(i + 2) % n];
    const bool folds = cross(a, b, c) == 0.0 &&
                       (b[0] - a[0]) * (c[0] - b[0]) + (b[1] - a[1]) * (c[1] - b[1]) < 0.0;
    if (folds) {
      throw std::invalid_argument("crosses itself: edges " + std::to_string(i) + " and " +
                                  std::to_string((i + 1) % n) + " overlap (" +
                                  describe((i + 2) % n, c) + " turns back along edge " +
                                  std::to_string(i) + ")");
    }
    // Edges that share no vertex must not meet at all.
    for (std::size_t j = i + 2; j < n; ++j) {
      if ((j + 1) % n == i) {
        continue;
      }
      if (segments_meet(a, b, v[j], v[(j + 1) % n])) {
        throw std::invalid_argument("crosses itself: edges " + std::to_string(i) + " and " +
                                    std::to_string(j) +
                                    " meet (edge k runs from vertex k to the next); a polygon "
                                    "must be simple");
      }
    }
  }
}

} // namespace

double signed_area(const std::vector<Point>& vertices) {
  double twice = 0.0;
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const Point& a = vertices[k];
    const Point& b = vertices[(k + 1) % vertices.size()];
    twice += a[0] * b[1] - b[0] * a[1];
  }
  return 0.5 * twice;
}

Region::Region(const Rectangle& rectangle)
    : shape_(Shape::rectangle), bounds_(rectangle), vertices_{{rectangle.r_min, rectangle.y_min},
                                                              {rectangle.r_max, rectangle.y_min},
                                                              {rectangle.r_max, rectangle.y_max},
                                                              {rectangle.r_min, rectangle.y_max}} {}

Region Region::polygon(std::vector<Point> vertices) {
  check_simple(vertices);
  Region region;
  region.shape_ = Shape::polygon;
  region.reversed_ = signed_area(vertices) < 0.0;
  if (region.reversed_) {
    std::reverse(vertices.begin(), vertices.end());
  }
  region.vertices_ = std::move(vertices);
  Rectangle& box = region.bounds_;
  box = {region.vertices_[0][0], region.vertices_[0][0], region.vertices_[0][1],
         region.vertices_[0][1]};
  for (const Point& p : region.vertices_) {
    box.r_min = std::min(box.r_min, p[0]);
    box.r_max = std::max(box.r_max, p[0]);
    box.y_min = std::min(box.y_min, p[1]);
    box.y_max = std::max(box.y_max, p[1]);
  }
  return region;
}

Region Region::circle(Point centre, double radius) {
  if (!(radius > 0.0)) {
    throw std::invalid_argument("the radius must be positive");
  }
  Region region;
  region.shape_ = Shape::circle;
  region.centre_ = centre;
  region.radius_ = radius;
  region.bounds_ = {centre[0] - radius, centre[0] + radius, centre[1] - radius, centre[1] + radius};
  return region;
}

bool Region::contains(double r, double y) const {
  switch (shape_) {
  case Shape::rectangle:
    return bounds_.contains(r, y);
  case Shape::circle: {
    const double dr = r - centre_[0];
    const double dy = y - centre_[1];
    return dr * dr + dy * dy <= radius_ * radius_;
  }
  case Shape::polygon:
    break;
  }
  // Crossings of the ray from (r, y) towards +r, with each edge half-open in y. Each edge is
  // evaluated from its lower end, so that a neighbouring polygon, which runs along a shared edge
  // the other way, finds bitwise the same crossing and the edge's points go to one side only.
  bool inside = false;
  const std::size_t n = vertices_.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Point& a = vertices_[k];
    const Point& b = vertices_[(k + 1) % n];
    const Point& low = a[1] <= b[1] ? a : b;
    const Point& high = a[1] <= b[1] ? b : a;
    if (low[1] <= y && y < high[1]) {
      const double crossing = low[0] + (y - low[1]) * (high[0] - low[0]) / (high[1] - low[1]);
      if (r < crossing) {
        inside = !inside;
      }
    }
  }
  return inside;
}

std::size_t Region::given_edge(std::size_t k) const {
  const std::size_t n = vertices_.size();
  return reversed_ ? (2 * n - 2 - k) % n : k;
}

std::size_t Region::given_vertex(std::size_t k) const {
  return reversed_ ? vertices_.size() - 1 - k : k;
}

double Region::area() const {
  switch (shape_) {
  case Shape::rectangle:
    return (bounds_.r_max - bounds_.r_min) * (bounds_.y_max - bounds_.y_min);
  case Shape::circle:
    return std::numbers::pi * radius_ * radius_;
  case Shape::polygon:
    break;
  }
  return signed_area(vertices_);
}

std::size_t Region::first_reflex_vertex() const {
  const std::size_t n = vertices_.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Point& before = vertices_[(k + n - 1) % n];
    const Point& at = vertices_[k];
    const Point& after = vertices_[(k + 1) % n];
    const double turn = cross(before, at, after);
    const double scale = std::hypot(at[0] - before[0], at[1] - before[1]) *
                         std::hypot(after[0] - at[0], after[1] - at[1]);
    // A vertex on the line of its edges is no turn at all (a sleeve joining a shaft).
    if (turn < -1e-12 * scale) {
      return k;
    }
  }
  return n;
}

bool Region::convex() const {
  return first_reflex_vertex() == vertices_.size();
}

} // namespace mpile
