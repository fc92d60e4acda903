// Body regions that are not rectangles: polygons and circles (engine/region.hpp). Their shapes are
// checked on construction, their particles tile the plane without gaps or doubles, their seeded
// volume follows the exact integral, and their outlines give contact normals a slanted incline can
// be verified with (V7 on a real slope).
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "engine/region.hpp"
#include "engine/structures/contact.hpp"
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <sstream>

namespace mpile {
namespace {

// ---------------------------------------------------------------------------------------------
// Shapes.

TEST(RegionPolygon, AClockwisePolygonIsStoredCounterClockwiseWithItsEdgesMapped) {
  // A unit square given clockwise.
  const Region region = Region::polygon({{0.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}, {1.0, 0.0}});
  EXPECT_DOUBLE_EQ(region.area(), 1.0);
  EXPECT_GT(signed_area(region.vertices()), 0.0);
  EXPECT_TRUE(region.convex());
  // Stored from (1, 0) backwards: stored edge k runs between given vertices 3 - k and 2 - k, which
  // is given edge 2 - k (mod 4).
  ASSERT_EQ(region.vertices().size(), 4u);
  EXPECT_EQ(region.vertices()[0], (Point{1.0, 0.0}));
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(region.given_vertex(k), 3 - k);
    EXPECT_EQ(region.given_edge(k), (6 - k) % 4);
  }
  const Rectangle& box = region.bounds();
  EXPECT_EQ(box.r_min, 0.0);
  EXPECT_EQ(box.r_max, 1.0);
  EXPECT_EQ(box.y_min, 0.0);
  EXPECT_EQ(box.y_max, 1.0);
}

TEST(RegionPolygon, AReflexVertexIsFoundAndACollinearOneIsNoTurn) {
  // An L shape turns inwards at (1, 1), given as vertex 3.
  const Region l_shape =
      Region::polygon({{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {1.0, 1.0}, {1.0, 2.0}, {0.0, 2.0}});
  EXPECT_FALSE(l_shape.convex());
  EXPECT_EQ(l_shape.given_vertex(l_shape.first_reflex_vertex()), 3u);
  EXPECT_DOUBLE_EQ(l_shape.area(), 3.0);
  // A cone with its sleeve and shaft: the vertex where the sleeve meets the shaft is on one line.
  const Region rod =
      Region::polygon({{0.0, 0.0}, {0.02, 0.03}, {0.02, 0.2}, {0.02, 0.5}, {0.0, 0.5}});
  EXPECT_TRUE(rod.convex());
}

struct BadPolygon {
  const char* what;
  std::vector<Point> vertices;
  const char* message; // a fragment of the reason
};

class RefusedPolygon : public testing::TestWithParam<BadPolygon> {};

TEST_P(RefusedPolygon, SaysWhatIsWrong) {
  const BadPolygon& bad = GetParam();
  try {
    (void)Region::polygon(bad.vertices);
    ADD_FAILURE() << bad.what << ": accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(bad.message), std::string::npos)
        << bad.what << ": " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Region, RefusedPolygon,
    testing::Values(
        BadPolygon{"two vertices", {{0.0, 0.0}, {1.0, 0.0}}, "needs at least 3 vertices, got 2"},
        BadPolygon{"repeated vertex",
                   {{0.0, 0.0}, {1.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}},
                   "vertex 2 (1, 0) repeats the vertex before it"},
        BadPolygon{"closed by hand",
                   {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {0.0, 0.0}},
                   "the last vertex repeats the first"},
        BadPolygon{"on one line", {{0.0, 0.0}, {1.0, 1.0}, {3.0, 3.0}}, "encloses no area"},
        BadPolygon{"bow tie",
                   {{0.0, 0.0}, {1.0, 1.0}, {1.0, 0.0}, {0.0, 1.0}},
                   "crosses itself: edges 0 and 2 meet"},
        BadPolygon{"folding back",
                   {{0.0, 0.0}, {2.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}},
                   "crosses itself: edges 0 and 1 overlap"},
        BadPolygon{"touching itself at a vertex",
                   {{0.0, 0.0}, {2.0, 0.0}, {1.0, 1.0}, {2.0, 2.0}, {0.0, 2.0}, {1.0, 1.0}},
                   "crosses itself"}));

TEST(RegionCircle, ARadiusMustBePositive) {
  EXPECT_THROW((void)Region::circle({0.5, 0.5}, 0.0), std::invalid_argument);
  EXPECT_THROW((void)Region::circle({0.5, 0.5}, -1.0), std::invalid_argument);
  EXPECT_THROW((void)Region::circle({0.5, 0.5}, std::nan("")), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Seeding.

Scene unit_scene(GeometryMode mode, int cells) {
  Scene scene(mode,
              Grid(GradedAxis::uniform(0.0, 1.0, cells), GradedAxis::uniform(0.0, 1.0, cells)));
  scene.add_material(std::make_unique<LinearElastic>(1e7, 0.3, 1000.0));
  return scene;
}

double body_volume(const Particles& p, std::uint16_t body) {
  double volume = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    volume += p.body[i] == body ? p.volume[i] : 0.0;
  }
  return volume;
}

TEST(RegionSeeding, TwoTrianglesSharingASlantedEdgeTileTheirSquareExactly) {
  // The diagonal of a square passes through sub-cell centres. Each centre on it must go to exactly
  // one of the two triangles: together they then hold every centre of the square once, and in
  // axisymmetry their volumes sum to the square's integral of r dA, which the sub-cell midpoint
  // rule integrates exactly (r is linear): (r1^2 - r0^2) / 2 (y1 - y0).
  // Dyadic coordinates, so that the centres lie on the diagonal exactly in binary too.
  Scene scene = unit_scene(GeometryMode::axisymmetric, 8);
  const double r0 = 0.25, r1 = 0.75, y0 = 0.125, y1 = 0.625; // 4 x 4 cells, 8 x 8 sub-cells
  const Region lower = Region::polygon({{r0, y0}, {r1, y0}, {r1, y1}});
  const Region upper = Region::polygon({{r0, y0}, {r1, y1}, {r0, y1}});
  const std::size_t below = fill_region(scene, lower, 2, 0, scene.add_body("lower"));
  const std::size_t above = fill_region(scene, upper, 2, 0, scene.add_body("upper"));
  EXPECT_EQ(below + above, 64u);
  // The 8 centres on the diagonal go to the lower triangle, which lies on the diagonal's +r side
  // (a point on an edge belongs to the polygon on the edge's +r side).
  EXPECT_EQ(below, 36u); // 8 x 9 / 2
  const double exact = (r1 * r1 - r0 * r0) / 2.0 * (y1 - y0);
  EXPECT_NEAR(body_volume(scene.particles, 0) + body_volume(scene.particles, 1), exact, 1e-15);
  // The square given as a polygon seeds the same particles as the rectangle.
  Scene as_rectangle = unit_scene(GeometryMode::axisymmetric, 8);
  fill_rectangle(as_rectangle, {r0, r1, y0, y1}, 2, 0, as_rectangle.add_body("square"));
  EXPECT_EQ(as_rectangle.particles.size(), 64u);
  EXPECT_NEAR(body_volume(as_rectangle.particles, 0), exact, 1e-15);
}

TEST(RegionSeeding, ATorusHoldsThePappusVolume) {
  // A circle of radius a centred at r_c sweeps a torus of volume 2 pi^2 r_c a^2, or pi a^2 r_c per
  // radian (Pappus). The sub-cell midpoint rule misses only along the boundary; an elementary
  // bound (every sub-cell the circle cuts lies within sqrt 2 sub-cells of it) allows 2 sqrt 2 / n
  // of the area at n sub-cells per radius, 7 % here; the lattice-point error of a circle is far
  // smaller in practice (Gauss's circle problem, n^(-4/3)), and 0.5 % at n = 40 is what a correct
  // containment test and volume give while a wrong weight r or a lost row of sub-cells misses by
  // 2.5 % or more.
  Scene scene = unit_scene(GeometryMode::axisymmetric, 50);
  const double a = 0.4, r_c = 0.5; // 20 cells, 40 sub-cells per radius
  fill_region(scene, Region::circle({r_c, 0.5}, a), 2, 0, scene.add_body("torus"));
  const double exact = std::numbers::pi * a * a * r_c;
  const double volume = body_volume(scene.particles, 0);
  std::cout << "torus: seeded volume / Pappus - 1 = " << volume / exact - 1.0 << "\n";
  EXPECT_NEAR(volume, exact, 0.005 * exact);
  // A sphere is the circle centred on the axis: (2/3) a^3 per radian.
  Scene sphere = unit_scene(GeometryMode::axisymmetric, 50);
  fill_region(sphere, Region::circle({0.0, 0.5}, a), 2, 0, sphere.add_body("sphere"));
  const double exact_sphere = 2.0 / 3.0 * a * a * a;
  EXPECT_NEAR(body_volume(sphere.particles, 0), exact_sphere, 0.005 * exact_sphere);
}

// ---------------------------------------------------------------------------------------------
// Outlines.

TEST(RegionOutline, ACircleIsOutlinedByAnInscribedPolygonAndASphereClosesOnTheAxis) {
  const double a = 0.3;
  const Region circle = Region::circle({0.5, 0.4}, a);
  const StructureOutline torus = region_outline(circle, GeometryMode::axisymmetric, {0});
  ASSERT_EQ(torus.vertices.size(), static_cast<std::size_t>(circle_outline_edges));
  double length = 0.0;
  for (std::size_t k = 0; k < torus.vertices.size(); ++k) {
    const Point& v = torus.vertices[k];
    const Point& next = torus.vertices[(k + 1) % torus.vertices.size()];
    EXPECT_NEAR(std::hypot(v[0] - 0.5, v[1] - 0.4), a, 1e-15);
    EXPECT_EQ(torus.edge_surface[k], 0);
    length += std::hypot(next[0] - v[0], next[1] - v[1]);
  }
  // The inscribed polygon's perimeter: 2 n a sin(pi / n), short of 2 pi a by 4e-4.
  const double n = circle_outline_edges;
  EXPECT_NEAR(length, 2.0 * n * a * std::sin(std::numbers::pi / n), 1e-14);
  EXPECT_NEAR(length / (2.0 * std::numbers::pi * a), 1.0, 5e-4);
  EXPECT_EQ(torus.vertices[0], (Point{0.5, 0.4 - a})); // a vertex at the bottom
  EXPECT_GT(signed_area(torus.vertices), 0.0);

  // Centred on the axis: the right half, from the bottom to the top, and the axis edge is no
  // contact surface.
  const StructureOutline sphere =
      region_outline(Region::circle({0.0, 0.4}, a), GeometryMode::axisymmetric, {0});
  ASSERT_EQ(sphere.vertices.size(), static_cast<std::size_t>(circle_outline_edges / 2 + 1));
  EXPECT_EQ(sphere.vertices.front(), (Point{0.0, 0.4 - a}));
  EXPECT_EQ(sphere.vertices.back(), (Point{0.0, 0.4 + a}));
  EXPECT_EQ(sphere.edge_surface.back(), -1);
  for (const Point& v : sphere.vertices) {
    EXPECT_GE(v[0], 0.0);
  }
  // In plane strain the same circle is a cylinder: the whole polygon.
  const StructureOutline cylinder =
      region_outline(Region::circle({0.0, 0.4}, a), GeometryMode::plane_strain, {0});
  EXPECT_EQ(cylinder.vertices.size(), static_cast<std::size_t>(circle_outline_edges));
}

// ---------------------------------------------------------------------------------------------
// V7 on a real slope: the incline a rigid polygon under vertical gravity, the block a rectangle
// turned to lie on it. Nothing is aligned with the grid, so the slope's normal reaches the nodes
// only through the polygon outline.

std::string slope_case(double angle_degrees, double mu) {
  const double a = angle_degrees * std::numbers::pi / 180.0;
  const double c = std::cos(a), s = std::sin(a);
  // The slope runs down from (0, 3.5) with the tangent t = (cos a, -sin a); n = (sin a, cos a).
  const double top = 3.5, length = 1.0, thickness = 0.5, start = 0.6;
  const auto on_slope = [&](double along, double above) {
    return Point{along * c + above * s, top - along * s + above * c};
  };
  const Point p0 = on_slope(start, 0.0), p1 = on_slope(start + length, 0.0),
              p2 = on_slope(start + length, thickness), p3 = on_slope(start, thickness);
  std::ostringstream text;
  text.precision(17);
  text << "title = \"V7 on a slanted rigid incline\"\n"
       << "geometry = \"plane_strain\"\n\n"
       << "[grid]\nr = [{ start = 0.0, end = 6.5, cells = 65 }]\n"
       << "y = [{ start = 0.0, end = 4.5, cells = 45 }]\n\n"
       << "[materials.block]\ntype = \"linear_elastic\"\nyoung_modulus = 10e6\n"
       << "poisson_ratio = 0.3\ndensity = 1000.0\n\n"
       << "[[bodies]]\nname = \"block\"\nmaterial = \"block\"\n"
       << "region = { polygon = [[" << p0[0] << ", " << p0[1] << "], [" << p1[0] << ", " << p1[1]
       << "], [" << p2[0] << ", " << p2[1] << "], [" << p3[0] << ", " << p3[1] << "]] }\n\n"
       << "[[bodies]]\nname = \"incline\"\nmaterial = \"block\"\n"
       << "region = { polygon = [[0.0, 0.0], [" << top / std::tan(a) << ", 0.0], [0.0, " << top
       << "]] }\n\n"
       << "[bodies.rigid]\nvelocity_r = 0.0\nvelocity_y = 0.0\nangular_velocity = 0.0\n\n"
       << "[[contact]]\nstructure = \"incline\"\nfriction = " << mu
       << "\nsurfaces = [\"\", \"slope\", \"\"]\n\n"
       << "[solver]\ngravity = [0.0, -9.81]\n\n"
       << "[[phases]]\nname = \"slide\"\nduration = 1.0\n";
  return text.str();
}

TEST(PolygonContact, ABlockSlidesDownASlantedRigidInclineAsCoulombFrictionSays) {
  // s(1 s) = g (sin a - mu cos a) / 2 along the slope: 1.1781 m at a = 30 deg and mu = 0.3, the
  // same 3 % as V7 on the grid-aligned incline (verification.md).
  const double a = 30.0 * std::numbers::pi / 180.0;
  CaseRun run(slope_case(30.0, 0.3));
  // The block starts in the equilibrium of an infinite layer on the slope, at depth d below its
  // top face: sigma_nn = -rho g cos a d, sigma_tn = rho g sin a d (as in V7, so that it does not
  // bounce).
  Particles& p = run.scene->particles;
  const double rho = 1000.0, g = 9.81, top = 3.5, thickness = 0.5;
  const double t[2] = {std::cos(a), -std::sin(a)}, n[2] = {std::sin(a), std::cos(a)};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != 0) {
      continue;
    }
    const double above = p.r[i] * n[0] + (p.y[i] - top) * n[1];
    const double d = thickness - above;
    const double nn = -rho * g * std::cos(a) * d, tn = rho * g * std::sin(a) * d;
    p.stress[i][RR] = nn * n[0] * n[0] + 2.0 * tn * t[0] * n[0];
    p.stress[i][YY] = nn * n[1] * n[1] + 2.0 * tn * t[1] * n[1];
    p.stress[i][RY] = nn * n[0] * n[1] + tn * (t[0] * n[1] + t[1] * n[0]);
  }
  run.run([] {});
  double mass = 0.0, along = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] == 0) {
      mass += p.mass[i];
      along += p.mass[i] * ((p.r[i] - p.r0[i]) * t[0] + (p.y[i] - p.y0[i]) * t[1]);
    }
  }
  const double slide = along / mass;
  const double reference = g * (std::sin(a) - 0.3 * std::cos(a)) / 2.0;
  std::cout << "V7 on a slanted polygon incline: s(1 s) = " << slide << " m (reference "
            << reference << " m)\n";
  EXPECT_NEAR(slide, reference, 0.03 * reference);
}

} // namespace
} // namespace mpile
