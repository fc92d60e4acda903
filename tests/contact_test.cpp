// Contact and rigid bodies (physics.md sections 5 and 6): nodal contact areas against exact
// integrals, the approach test and momentum exchange, rigid-body dynamics, V7 (block on an
// incline) and V9 (the seed's torsion with adhesion), from the shipped case files.
#include "cases/case_builder.hpp"
#include "cases/case_spec.hpp"
#include "cases/verification/verification_cases.hpp"
#include "engine/parallel.hpp"
#include "engine/structures/contact.hpp"
#include "solver/diagnostics.hpp"
#include "solver/explicit_solver.hpp"
#include "tests/bitwise.hpp"
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <sstream>

namespace mpile {
namespace {

// ---------------------------------------------------------------------------------------------
// Nodal contact areas.

TEST(ContactAreas, OutlineAreasIntegrateEachEdgeExactlyInAxisymmetry) {
  // A graded grid and a rectangle whose edges lie off the grid lines: the areas of the nodes must
  // sum to each edge's integral of r ds (the pile wall's surface per radian), whatever the cuts.
  const AxisZone r_zones[] = {{0.0, 0.3, 3}, {0.3, 0.5, 8}, {0.5, 1.0, 5}};
  const AxisZone y_zones[] = {{0.0, 1.0, 7}};
  Grid grid{GradedAxis(r_zones), GradedAxis(y_zones)};
  ContactPair pair;
  pair.surfaces = {"tip", "outer", "head", "inner"};
  const double r0 = 0.3571, r1 = 0.373, y0 = 0.4123, y1 = 0.93;
  pair.outline = StructureOutline::rectangle(r0, r1, y0, y1, 0, 1, 2, 3);
  pair.allocate(grid.node_count());
  integrate_outline(grid, GeometryMode::axisymmetric, pair);
  const double exact[4] = {(r1 * r1 - r0 * r0) / 2, r1 * (y1 - y0), (r1 * r1 - r0 * r0) / 2,
                           r0 * (y1 - y0)};
  for (std::size_t q = 0; q < 4; ++q) {
    double sum = 0.0;
    for (std::size_t i = 0; i < grid.node_count(); ++i) {
      sum += pair.surface_area[i * 4 + q];
    }
    // Two-point Gauss is exact for the cubic integrand on each piece: only round-off remains.
    EXPECT_NEAR(sum, exact[q], 1e-14) << pair.surfaces[q];
  }
  // Every area-carrying node's normal has unit length.
  for (const int node : pair.outlined_nodes) {
    const auto& n = pair.normal[static_cast<std::size_t>(node)];
    EXPECT_NEAR(std::hypot(n[0], n[1]), 1.0, 1e-14);
  }
  // Integrating again (the next step) starts from zero: no accumulation.
  integrate_outline(grid, GeometryMode::axisymmetric, pair);
  double total = 0.0;
  for (std::size_t i = 0; i < grid.node_count(); ++i) {
    total += pair.area[i];
  }
  EXPECT_NEAR(total, exact[0] + exact[1] + exact[2] + exact[3], 1e-14);
}

TEST(ContactAreas, ConeAndSleeveGiveTheAreasTheirResistancesAreQuotedOver) {
  // The standard cone as one outline (counter-clockwise from the apex on the axis): cone face,
  // sleeve, rod, then head and axis edges that are no surface. q_c is quoted over the cone's plan
  // area pi R^2 (R^2 / 2 per radian), f_s over the sleeve's 2 pi R L (R L per radian). The cone
  // face's side area is the integral of r dy, R H / 2; a vertical face has no plan area. The
  // formulas are exact for straight edges: only round-off remains.
  const double radius = 0.01785, height = radius * std::sqrt(3.0), sleeve = 0.1337;
  const double apex = 1.7, shoulder = apex + height, top = shoulder + sleeve;
  StructureOutline outline;
  outline.vertices = {{0.0, apex}, {radius, shoulder}, {radius, top}, {radius, 2.9}, {0.0, 2.9}};
  outline.edge_surface = {0, 1, 2, -1, -1};
  const std::vector<SurfaceAreas> areas = surface_areas(outline, 3, GeometryMode::axisymmetric);
  ASSERT_EQ(areas.size(), 3u);
  EXPECT_NEAR(areas[0].plan, radius * radius / 2.0, 1e-17);
  EXPECT_NEAR(areas[0].side, radius * height / 2.0, 1e-17);
  EXPECT_EQ(areas[1].plan, 0.0);
  EXPECT_NEAR(areas[1].side, radius * sleeve, 1e-17);
  EXPECT_NEAR(areas[2].side, radius * (2.9 - top), 1e-16);
  // A pile wall in plane strain: the tip's plan area is the wall's thickness, the shaft's side
  // area its length; moving the pile changes neither.
  StructureOutline wall = StructureOutline::rectangle(2.0, 2.1, 1.0, 4.0, 0, 1, -1, 2);
  wall.translate(0.3, -0.7);
  const std::vector<SurfaceAreas> plane = surface_areas(wall, 3, GeometryMode::plane_strain);
  EXPECT_NEAR(plane[0].plan, 0.1, 1e-15);
  EXPECT_EQ(plane[0].side, 0.0);
  EXPECT_NEAR(plane[1].side, 3.0, 1e-15);
  EXPECT_NEAR(plane[2].side, 3.0, 1e-15);
}

TEST(ContactAreas, CornerNodeOnGridLinesGetsTheAreaWeightedNormal) {
  // A pile tip corner on grid nodes: the node at (r0, y0) carries half a cell of the inner wall
  // (r0 h / 2) and the first half cell of the base (integral of N r dr over [r0, r0 + h]); its
  // normal is their area-weighted mean of (-1, 0) and (0, -1).
  const double h = 0.1;
  Grid grid(GradedAxis::uniform(0.0, 1.0, 10), GradedAxis::uniform(0.0, 1.0, 10));
  ContactPair pair;
  pair.surfaces = {"base", "inner"};
  pair.outline = StructureOutline::rectangle(0.4, 0.6, 0.5, 1.0, 0, -1, -1, 1);
  pair.allocate(grid.node_count());
  integrate_outline(grid, GeometryMode::axisymmetric, pair);
  const auto corner = static_cast<std::size_t>(grid.node_index(4, 5));
  const double wall = 0.4 * h / 2;
  const double base = h * (0.4 / 2 + h / 6); // integral of (1 - s/h) (0.4 + s) ds over [0, h]
  EXPECT_NEAR(pair.area[corner], wall + base, 1e-15);
  EXPECT_NEAR(pair.surface_area[corner * 2 + 0], base, 1e-15);
  EXPECT_NEAR(pair.surface_area[corner * 2 + 1], wall, 1e-15);
  const double length = std::hypot(wall, base);
  EXPECT_NEAR(pair.normal[corner][0], -wall / length, 1e-14);
  EXPECT_NEAR(pair.normal[corner][1], -base / length, 1e-14);
  // Right and top edges are not contact surfaces: the node at (0.6, 1.0) carries nothing.
  EXPECT_EQ(pair.area[static_cast<std::size_t>(grid.node_index(6, 10))], 0.0);
}

TEST(ContactAreas, ATipARoundingOffItsGridLineGivesTheNextRowNoArea) {
  // A two-cell pile wall whose tip lies a rounding error (3e-16 m, as a pile translated step by
  // step drifts from the moving mesh's line set from its total displacement) above or below the
  // grid line y = 0.5 m. The nodes on the line must carry the tip's whole area and the nodes one
  // cell away, inside the wall or in the soil below the tip, exactly none: a share of 1e-15 of a
  // cell made them outline nodes with the tip's normal and surface.
  Grid grid(GradedAxis::uniform(0.0, 1.0, 10), GradedAxis::uniform(0.0, 1.0, 10));
  for (const double drift : {3e-16, -3e-16}) {
    ContactPair pair;
    pair.surfaces = {"tip", "outer", "inner"};
    pair.outline = StructureOutline::rectangle(0.4, 0.6, 0.5 + drift, 1.0, 0, 1, -1, 2);
    ASSERT_NE(pair.outline->vertices[0][1], 0.5) << drift; // the drift is representable there
    pair.allocate(grid.node_count());
    integrate_outline(grid, GeometryMode::axisymmetric, pair);
    for (int ir = 4; ir <= 6; ++ir) {
      EXPECT_EQ(pair.area[static_cast<std::size_t>(grid.node_index(ir, 4))], 0.0)
          << drift << " " << ir;
      EXPECT_GT(pair.area[static_cast<std::size_t>(grid.node_index(ir, 5))], 0.0)
          << drift << " " << ir;
    }
    // Inside the wall, one cell above the tip at its mid line: no edge within half a cell.
    EXPECT_EQ(pair.area[static_cast<std::size_t>(grid.node_index(5, 6))], 0.0) << drift;
    // The middle node of the tip has the tip's normal and the integral of N r dr over two cells.
    const auto middle = static_cast<std::size_t>(grid.node_index(5, 5));
    EXPECT_NEAR(pair.surface_area[middle * 3], 0.1 * 0.5, 1e-15) << drift;
    EXPECT_EQ(pair.normal[middle][0], 0.0) << drift;
    EXPECT_EQ(pair.normal[middle][1], -1.0) << drift;
  }
}

TEST(ContactNormals, InsideTheOutlineTiesGoToTheFaceTheSoilMovesInto) {
  // A wall two cells thick (r from 0.4 to 0.6, tip at y = 0.5; the inner face is the surface 1,
  // the outer 2, the tip 0): the node line r = 0.5 is as far from both faces, to rounding, so the
  // nearest edge alone picks one face for soil from either side.
  const StructureOutline wall = StructureOutline::rectangle(0.4, 0.6, 0.5, 1.0, 0, 2, -1, 1);
  const Grid grid(GradedAxis::uniform(0.0, 1.0, 10), GradedAxis::uniform(0.0, 1.0, 10));
  const double r = grid.node_r(grid.node_index(5, 8));
  const double y = grid.node_y(grid.node_index(5, 8));
  // Soil moving outward (from the plug) meets the inner face, soil moving inward the outer one.
  const EdgeNormal from_plug = facing_edge_normal(wall, r, y, {-1.0, 0.0});
  EXPECT_EQ(from_plug.surface, 1);
  EXPECT_EQ(from_plug.normal[0], -1.0);
  const EdgeNormal from_outside = facing_edge_normal(wall, r, y, {1.0, 0.0});
  EXPECT_EQ(from_outside.surface, 2);
  EXPECT_EQ(from_outside.normal[0], 1.0);
  // Three cells (r from 0.3 to 0.6): the node one cell above the tip and one cell from the inner
  // face is as far from both; soil pushed up from below meets the tip, soil from the plug the face.
  const StructureOutline thick = StructureOutline::rectangle(0.3, 0.6, 0.5, 1.0, 0, 2, -1, 1);
  const double r1 = grid.node_r(grid.node_index(4, 6));
  const double y1 = grid.node_y(grid.node_index(4, 6));
  EXPECT_EQ(facing_edge_normal(thick, r1, y1, {0.0, -1.0}).surface, 0);
  EXPECT_EQ(facing_edge_normal(thick, r1, y1, {-1.0, 0.0}).surface, 1);
  // Without a tie the nearest edge decides, whatever the soil does: (0.4, 0.8) is a cell from the
  // inner face and two from the outer one.
  const double r2 = grid.node_r(grid.node_index(4, 8));
  EXPECT_EQ(facing_edge_normal(thick, r2, y, {1.0, 0.0}).surface, 1);
  EXPECT_EQ(facing_edge_normal(thick, r2, y, {0.0, -1.0}).surface, 1);
}

/// block_above_soil's elastic soil to y = 2 m, weightless, and a rigid wall two cells thick (r from
/// 0.25 to 0.5 m, 0.125 m cells, all exact in binary) seeded above it and then moved 0.5 m down
/// into it, to y from 1.75 to 2.125 m, as a pile wall that soil has got into: the soil particles in
/// it (two per cell and axis) are given v_r = `soil_velocity_r`, everything else is at rest. The
/// wall's contact surfaces are its tip, inner (left) and outer (right) faces.
CaseRun soil_moving_inside_a_wall(double soil_velocity_r) {
  // block_above_soil on a grid of 0.125 m cells, without its moving mesh, the block made the wall.
  std::string text = replaced(
      replaced(std::string(block_above_soil),
               "cells = 10 }]\ny = [{ start = 0.0, end = 1.0, cells = 10 }, { start = 1.0, end = "
               "1.4, cells = 8 },\n     { start = 1.4, end = 2.5, cells = 11 }]",
               "cells = 8 }]\ny = [{ start = 0.0, end = 3.0, cells = 24 }]"),
      "r = [0.5, 0.6], y = [2.3, 2.4]", "r = [0.25, 0.5], y = [2.25, 2.625]");
  text = replaced(text, "velocity_y = -0.5", "velocity_y = 0.0");
  text = replaced(text, "structure = \"block\"\n",
                  "structure = \"block\"\nsurfaces = { bottom = \"tip\", right = \"outer\", left = "
                  "\"inner\" }\n");
  text = replaced(text, "[moving_mesh]\nbody = \"block\"\nband = [1.0, 1.4]\ntravel = 0.2\n", "");
  CaseRun run(text +
              "[solver]\ngravity = [0.0, 0.0]\n[[phases]]\nname = \"one step\"\nduration = 0.1\n");
  run.scene->contacts.at(0).outline->translate(0.0, -0.5);
  Particles& p = run.scene->particles;
  const StructureOutline& outline = *run.scene->contacts.at(0).outline;
  for (std::size_t q = 0; q < p.size(); ++q) {
    if (run.scene->body_names[p.body[q]] == "block") {
      p.y[q] -= 0.5;
    } else if (outline.contains(p.r[q], p.y[q])) {
      p.v_r[q] = soil_velocity_r;
    }
  }
  // A solver made after the changes, which locates the particles where they now are.
  run.solver = std::make_unique<ExplicitSolver>(
      *run.scene, phase_settings(run.spec, run.spec.phases[0]), run.log);
  run.solver->step(1.0);
  return run;
}

TEST(ContactNormals, SoilMovingIntoAWallFromEitherFaceIsStoppedByThatFace) {
  // The nodes on r = 0.375 m at y = 1.875 and 2.0 m lie inside the wall, as far from its inner face
  // as from its outer one (the first also from its tip). Soil there moving outward came in
  // through the inner face and must be stopped by it; soil moving inward, by the outer face. A
  // choice of face by rounding alone would call one of the two motions separating and let it on.
  for (const double v : {0.1, -0.1}) {
    const CaseRun run = soil_moving_inside_a_wall(v);
    const ContactPair& pair = run.pair();
    const Grid& grid = run.scene->grid;
    for (const int iy : {15, 16}) {
      const auto i = static_cast<std::size_t>(grid.node_index(3, iy));
      ASSERT_EQ(pair.area[i], 0.0) << iy;            // inside the outline, off its edges
      EXPECT_NE(pair.state[i], 0) << v << " " << iy; // 0: not in contact
      EXPECT_EQ(pair.contact_normal[i][0], v > 0.0 ? -1.0 : 1.0) << v << " " << iy;
      EXPECT_EQ(pair.contact_normal[i][1], 0.0) << v << " " << iy;
    }
    // The force those nodes take is booked to the face that stopped the soil: with the soil
    // moving outward, nothing pushes the outer face (its nodes see the soil leave), so its force
    // is exactly zero; moving inward, nothing pushes the inner one.
    const double inner = run.surface_force("inner", 0);
    const double outer = run.surface_force("outer", 0);
    EXPECT_EQ(v > 0.0 ? outer : inner, 0.0) << v;
    EXPECT_NE(v > 0.0 ? inner : outer, 0.0) << v;
  }
}

// ---------------------------------------------------------------------------------------------
// V7: block on an incline (plane strain), from cases/verification/v7_block_on_incline.toml.

/// Mean x displacement of the block's particles after 1 s on a 30 or 45 degree incline with mu.
std::string incline_text(double angle_degrees, double mu) {
  const double a = angle_degrees * std::numbers::pi / 180.0;
  std::ostringstream gravity, friction;
  gravity.precision(17);
  gravity << "gravity = [" << 9.81 * std::sin(a) << ", " << -9.81 * std::cos(a) << "]";
  friction << "friction = " << mu;
  std::string text = read_text(source / "cases/verification/v7_block_on_incline.toml");
  text = replaced(text, "gravity = [4.905, -8.49571]", gravity.str());
  text = replaced(text, "friction = 0.3", friction.str());
  return text;
}

/// The incline as a stiff elastic layer fixed at its base, with normals from its mass gradient.
std::string deformable_incline(std::string text) {
  text = replaced(text,
                  "[bodies.rigid]\nvelocity_r = { type = \"constant\", value = 0.0 }\n"
                  "velocity_y = { type = \"constant\", value = 0.0 }\n"
                  "angular_velocity = { type = \"constant\", value = 0.0 }\n",
                  "");
  text = replaced(text, "surfaces = { top = \"slope\" }", "normals = \"mass_gradient\"");
  text = replaced(text, "young_modulus = 10e6\npoisson_ratio = 0.3\ndensity = 1000.0\n\n[[bodies]]",
                  "young_modulus = 1e9\npoisson_ratio = 0.3\ndensity = 1000.0\n\n[[bodies]]");
  return text + "\n[boundaries]\ny_min = \"fixed\"\n";
}

double block_slide(const std::string& text, double angle_degrees) {
  const double a = angle_degrees * std::numbers::pi / 180.0;
  CaseRun run(text);
  // Start the block in the equilibrium of an infinitely long layer (zero at its top, y = 1):
  // sigma_yy = -rho g cos a (1 - y), sigma_xy = rho g sin a (1 - y). Released unstressed it would
  // bounce on the incline, and the normal force would dip below what holds it (a dynamic effect
  // that makes even a block with mu > tan a creep).
  Particles& p = run.scene->particles;
  const double rho = 1000.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] == 0) {
      p.stress[i][YY] = -rho * 9.81 * std::cos(a) * (1.0 - p.y[i]);
      p.stress[i][RY] = rho * 9.81 * std::sin(a) * (1.0 - p.y[i]);
    }
  }
  run.run([] {});
  double mass = 0.0, moment = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] == 0) {
      mass += p.mass[i];
      moment += p.mass[i] * (p.r[i] - p.r0[i]);
    }
  }
  return moment / mass;
}

struct InclineRow {
  double angle, mu, slide; // slide: s(1 s) = g (sin a - mu cos a) / 2, or 0 when mu >= tan a
  double tolerance;        // relative, verification.md: 2 % frictionless, 3 % frictional
};

class BlockOnIncline : public testing::TestWithParam<InclineRow> {};

TEST_P(BlockOnIncline, SlidesAsCoulombFrictionSays) {
  const InclineRow row = GetParam();
  const double s = block_slide(incline_text(row.angle, row.mu), row.angle);
  std::cout << "V7 a = " << row.angle << " deg, mu = " << row.mu << ": s(1 s) = " << s
            << " m (reference " << row.slide << " m)\n";
  if (row.slide > 0.0) {
    EXPECT_NEAR(s, row.slide, row.tolerance * row.slide);
  } else {
    // Sticking: the block only settles elastically. Bound its creep by 1 % of the frictionless
    // slide (2.45 m), far below any slip a missing friction limit would give.
    EXPECT_LT(std::abs(s), 0.01 * 2.4525);
  }
}

/// Hertz's impact of the sphere of cases/verification/hertz_sphere.toml (R = 0.1 m, E = 1 MPa,
/// nu = 0.3, 1000 kg/m^3, 0.1 m/s on a rigid plate, frictionless): the first step with a contact
/// force, the contact's duration and the extremes of the kinetic plus elastic energy over the run.
struct HertzImpact {
  double touch = -1.0;     // time the step with the first contact force started (s)
  double release = -1.0;   // time the step with the last contact force ended (s)
  double energy_low = 1.0; // (kinetic + elastic) / initial kinetic, its least over the run
  double energy_high = 1.0;
  double kinetic_end = 0.0; // kinetic / initial kinetic at the end
};

HertzImpact hertz_impact(const std::string& text) {
  CaseRun run(text);
  HertzImpact impact;
  const double initial = run.solver->energy_balance().kinetic;
  double before = run.solver->time();
  run.run([&] {
    const double now = run.solver->time();
    if (run.pair().surface_force[0][1] != 0.0) {
      if (impact.touch < 0.0) {
        impact.touch = before;
      }
      impact.release = now;
    }
    const EnergyBalance b = run.solver->energy_balance();
    impact.energy_low = std::min(impact.energy_low, (b.kinetic + b.elastic) / initial);
    impact.energy_high = std::max(impact.energy_high, (b.kinetic + b.elastic) / initial);
    impact.kinetic_end = b.kinetic / initial;
    before = now;
  });
  return impact;
}

TEST(HertzImpact, SphereTouchesOnTimeBouncesWithItsEnergyAndLastsTheElastodynamicTime) {
  // 2 mm cells (53 x 105) instead of the file's 1 mm, for the suite; the file's numbers are in
  // docs/verification.md.
  std::string text = read_text(source / "cases/verification/hertz_sphere.toml");
  text = replaced(text, "end = 0.105, cells = 105", "end = 0.106, cells = 53");
  text = replaced(text, "end = 0.21, cells = 210", "end = 0.21, cells = 105");
  text = replaced(text, "r = [0.0, 0.105], y = [0.0, 0.002]", "r = [0.0, 0.106], y = [0.0, 0.002]");
  text = replaced(text, "duration = 0.065", "duration = 0.056");
  const HertzImpact impact = hertz_impact(text);
  // Hertz (Johnson 1985, 11.4): m = 4/3 pi R^3 rho, E* = E / (1 - nu^2) against a rigid plate,
  // delta_max = (15 m v^2 / (16 E* R^(1/2)))^(2/5), t_c = 2.9432751 delta_max / v.
  const double R = 0.1, v = 0.1;
  const double mass = 4.0 / 3.0 * std::numbers::pi * R * R * R * 1000.0;
  const double e_star = 1e6 / (1.0 - 0.3 * 0.3);
  const double delta = std::pow(15.0 * mass * v * v / (16.0 * e_star * std::sqrt(R)), 0.4);
  const double hertz_time = 2.9432751 * delta / v;
  const double duration = impact.release - impact.touch;
  std::cout << "touch " << impact.touch << " s, contact " << duration << " s against Hertz's "
            << hertz_time << " s (" << 100.0 * (duration / hertz_time - 1.0)
            << " %), kinetic + elastic energy between " << impact.energy_low << " and "
            << impact.energy_high << ", kinetic energy at the end " << impact.kinetic_end << "\n";
  // The sphere starts 0.5 mm above the plate: it touches after 5 ms, to within a step (44 us).
  // Seeded by sub-cell centres its lowest particles' domains ended 1 mm above the sphere and it
  // touched after 10 ms.
  EXPECT_NEAR(impact.touch, 0.005, 5e-5);
  // Hertz's time takes the sphere near the contact for a half-space; this sphere is finite (its
  // patch reaches 0.13 R) and rings with a quarter of the contact's period. The reference is the
  // contact time of the same impact from independent dynamic finite elements (tools/hertz_fe.py:
  // -4.18 % of Hertz's on 1 mm and -4.23 % on 0.5 mm elements; docs/verification.md), -4.2 %. The
  // finite size, not the dynamics, makes it: the same elements quasi-static (--quasi-static) give
  // -4.6 %, the sphere lacking the half-space's compliance below its centre, and the dynamics adds
  // +0.4 %. The target, 2 %, is held against the reference: measured -0.15 % here (-4.35 % of
  // Hertz), -0.26 % and +0.20 % on 1 and 0.5 mm cells. It fails with what came before: contact
  // taken where any particle of a node's cells touches (-7.4 % of Hertz, -3.3 % of the reference)
  // and the staircase seeding (-24 %).
  const double elastodynamic_time = (1.0 - 0.042) * hertz_time;
  EXPECT_NEAR(duration / elastodynamic_time, 1.0, 0.02);
  // A purely elastic impact: the kinetic plus stored energy stays within 1 % of the initial
  // kinetic energy throughout (0.86 % at the deepest indentation), and the kinetic energy comes
  // back within 1 % (0.44 % stays in the ringing sphere). With bilinear weights the cell crossings
  // of FLIP put 7 % of it into the stresses' noise.
  EXPECT_GT(impact.energy_low, 0.99);
  EXPECT_LT(impact.energy_high, 1.01);
  EXPECT_GT(impact.kinetic_end, 0.99);
}

TEST(V7MassGradientNormals, BlockSlidesOnADeformableIncline) {
  // No outline: the incline is a stiff elastic layer (E = 1 GPa) and the normals come from its mass
  // gradient. The frictional row of V7 must hold to the same 3 %.
  const std::string text = deformable_incline(incline_text(30.0, 0.3));
  const double s = block_slide(text, 30.0);
  std::cout << "V7 with mass-gradient normals, a = 30 deg, mu = 0.3: s(1 s) = " << s << " m\n";
  EXPECT_NEAR(s, 1.1781, 0.03 * 1.1781);
}

INSTANTIATE_TEST_SUITE_P(V7, BlockOnIncline,
                         testing::Values(InclineRow{30.0, 0.0, 2.4525, 0.02},
                                         InclineRow{30.0, 0.3, 1.1781, 0.03},
                                         InclineRow{45.0, 0.3, 2.4279, 0.03},
                                         InclineRow{30.0, 0.7, 0.0, 0.0}));

TEST(ContactDamping, DiscAtRestOnSoilPassesItsWholeWeightThroughContact) {
  // cases/stability/stiff_contact_block.toml with the disc's modulus lowered 100 times (the
  // stiffness does not enter the static forces; the step grows tenfold): a disc on soft soil
  // brought to rest by local damping. The contact force on it must balance its weight,
  // 8000 * 9.81 * 0.1 * 0.4^2 / 2 = 627.8 N/rad. Local damping acting on the unbalanced force at
  // the nodes the two fields share (which only contact balances) held up two thirds of it.
  std::string text = read_text(source / "cases/stability/stiff_contact_block.toml");
  text = replaced(text, "young_modulus = 220e9", "young_modulus = 2.2e9");
  text = replaced(text, "duration = 0.5", "duration = 0.3");
  CaseRun run(text);
  run.run([] {});
  const double weight = 8000.0 * 9.81 * 0.1 * 0.4 * 0.4 / 2.0;
  // 1 %: the disc is at rest to an out-of-balance ratio of 1e-3 after 0.3 s of damping.
  EXPECT_NEAR(run.surface_force("disc surface", 1), weight, 0.01 * weight);
  std::cout << "disc at rest: contact force / weight - 1 "
            << run.surface_force("disc surface", 1) / weight - 1.0 << '\n';
  // A target 1.0001 stable steps away (a phase end or snapshot time): taken as two steps of about
  // half a step each, not a full step and a sliver of 2e-4 of one, whose contact correction (an
  // impulse that does not shrink with the step) over the sliver recorded 288 N/rad, less than half
  // the weight. The force must still balance the weight to the same 1 %.
  const double dt = run.solver->stable_time_step();
  run.solver->advance_to(run.solver->time() + 1.0001 * dt);
  EXPECT_GT(run.solver->last_time_step(), 0.45 * dt);
  EXPECT_NEAR(run.surface_force("disc surface", 1), weight, 0.01 * weight);
  std::cout << "disc at rest: contact force / weight - 1 after the short step "
            << run.surface_force("disc surface", 1) / weight - 1.0 << '\n';
}

TEST(ContactDeformablePile, SteelPileTipCrossesIntoTheNextRowOfCellsStably) {
  // cases/stability/steel_pile.toml: a steel pile (E = 220 GPa) jacked into sand, two fields
  // with contact. Its tip particles cross into the next row of cells at t = 0.0175 s. Before the
  // fixes the run blew up there within a millisecond: B-bar averaged the tip particles'
  // volumetric strain with the sand's in the cell they entered, and the separation test at the
  // nodes where the pile has only a sliver of mass rectified the tip's stress into the soil
  // (solver/contact_passes.cpp, structure_bonded_share). Run to 0.025 s, past the crossing.
  std::string text = read_text(source / "cases/stability/steel_pile.toml");
  text = replaced(text, "duration = 0.11", "duration = 0.025");
  CaseRun run(text);
  double peak_residual = 0.0;
  double peak_elastic = 0.0;
  run.run([&] {
    const EnergyBalance balance = run.solver->energy_balance();
    peak_elastic = std::max(peak_elastic, balance.elastic);
    // The first milliseconds put so little energy in play that their start-up error, of order
    // dt, is a large fraction of it (docs/design.md, "Energy balance and guards").
    if (run.solver->time() > 0.005) {
      peak_residual = std::max(peak_residual, balance.relative_residual);
    }
  });
  // Fixed, the balance closes to 0.02 % before the crossing and to about 1 % through it; the
  // blow-ups passed 50 % within 1 ms of it. 2 % leaves room for rounding and small changes of
  // the scheme while any return of the blow-up fails.
  EXPECT_LT(peak_residual, 0.02);
  // The stored energy grows with the push to about 40 J by 0.025 s; the blow-ups passed 1000 J.
  EXPECT_LT(peak_elastic, 100.0);
}

TEST(ContactDeformablePile, JackedATenthOfAMetreItsEnergyBalanceCloses) {
  // cases/stability/steel_pile.toml as shipped, through 0.105 m of jacking. The head's nodes drive
  // the pile, so its particles there take the drive's velocity and the drive's work is booked at
  // their mean velocity over the step (solver/apply_constraints.cpp); with GIMP, the kinetic
  // energy the tip's cell crossings create on the grid is about 20 J over the run
  // (docs/stability.md, "Where the energy goes in one step"). Measured at the end: 0.016 % (C =
  // 0.8) and 0.10 % (C = 0.4); before, 2.7 % with linear shape functions and 6.8 % with GIMP. The
  // peak, 2.2 to 2.3 % at 5.6 cm whatever the step, is a transient difference between the soil's
  // stress work and the work its grid forces do, which the run recovers.
  CaseRun run(read_text(source / "cases/stability/steel_pile.toml"));
  // The case's K0 stresses, as `mpile run` sets them; the balance starts from what they store.
  const double elastic_before = elastic_energy(*run.scene);
  apply_k0(*run.scene, run.spec, run.spec.phases[0]);
  run.solver->account_for_stress_reset(elastic_before);
  double peak_residual = 0.0;
  run.run([&] {
    if (run.solver->time() > 0.005) {
      peak_residual = std::max(peak_residual, run.solver->energy_balance().relative_residual);
    }
  });
  // 0.5 %: five times the larger of the two measured final residuals; the old bookings fail it.
  EXPECT_LT(run.solver->energy_balance().relative_residual, 0.005);
  // 3 %: the measured transient's 2.3 % with room for rounding; a blow-up passes 50 %.
  EXPECT_LT(peak_residual, 0.03);
}

TEST(ContactDeformablePile, AnAxialWaveRunsDownThePileAtTheBarSpeed) {
  // The steel pile of cases/stability/steel_pile.toml without gravity, its head's nodes (y =
  // 1.35 m) brought to 1 m/s downwards in 10 us. The front runs down at the bar speed sqrt(E /
  // rho) = 5 244 m/s, not the constrained 6 084 m/s: the wall is free to move radially (the sand
  // is 10^4 times softer) and the front far longer than the wall is thick. Each pile particle
  // between 0.8 and 1.25 m records when its velocity first passes half the head's (interpolated
  // between steps); a straight line through (depth below the head, time) gives the speed.
  std::string text = read_text(source / "cases/stability/steel_pile.toml");
  text = replaced(text, "gravity = [0.0, -9.81]", "gravity = [0.0, 0.0]");
  text = replaced(text, "[[0.0, 0.0], [0.01, -1.0]]", "[[0.0, 0.0], [1e-5, -1.0]]");
  text = replaced(text, "duration = 0.11", "duration = 1.3e-4");
  CaseRun run(text);
  const Particles& p = run.scene->particles;
  const auto& names = run.scene->body_names;
  const auto pile =
      static_cast<std::size_t>(std::find(names.begin(), names.end(), "pile") - names.begin());
  std::vector<std::size_t> watched;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] == pile && p.y[i] > 0.8 && p.y[i] < 1.25) {
      watched.push_back(i);
    }
  }
  ASSERT_GT(watched.size(), 20u);
  std::vector<double> depth(watched.size()), arrival(watched.size(), -1.0);
  std::vector<double> previous(watched.size(), 0.0);
  for (std::size_t k = 0; k < watched.size(); ++k) {
    depth[k] = 1.35 - p.y[watched[k]];
  }
  double time_before = 0.0;
  run.run([&] {
    const double now = run.solver->time();
    for (std::size_t k = 0; k < watched.size(); ++k) {
      const double v = -p.v_y[watched[k]];
      if (arrival[k] < 0.0 && v >= 0.5) {
        arrival[k] = time_before + (0.5 - previous[k]) / (v - previous[k]) * (now - time_before);
      }
      previous[k] = v;
    }
    time_before = now;
  });
  double sd = 0.0, st = 0.0, sdd = 0.0, sdt = 0.0;
  for (std::size_t k = 0; k < watched.size(); ++k) {
    ASSERT_GT(arrival[k], 0.0) << "the front did not reach y = " << 1.35 - depth[k];
    sd += depth[k];
    st += arrival[k];
    sdd += depth[k] * depth[k];
    sdt += depth[k] * arrival[k];
  }
  const double n = static_cast<double>(watched.size());
  const double slope = (n * sdt - sd * st) / (n * sdd - sd * sd);
  const double bar_speed = std::sqrt(220e9 / 8000.0);
  std::cout << "axial wave in the steel pile: " << 1.0 / slope << " m/s against the bar speed "
            << bar_speed << " m/s\n";
  // 2 %: the accuracy the arrival of a wave in the pile needs for drivability (L / c).
  EXPECT_NEAR(1.0 / slope, bar_speed, 0.02 * bar_speed);
}

// ---------------------------------------------------------------------------------------------
// V9: the seed's torsion with adhesion, from cases/verification/v9_torsion_adhesion.toml.

struct TorsionReactions {
  double internal = 0.0, external = 0.0, base = 0.0; // theta forces on the pile, mean over
                                                     // 0.5 to 1 s (N/rad)
};

TorsionReactions torsion_reactions(const std::string& text) {
  CaseRun run(text);
  TorsionReactions sum;
  double weight = 0.0;
  run.run([&] {
    if (run.solver->time() < 0.5) {
      return;
    }
    const double dt = run.solver->last_time_step();
    sum.internal += dt * run.surface_force("internal_shaft", 2);
    sum.external += dt * run.surface_force("external_shaft", 2);
    sum.base += dt * run.surface_force("base", 2);
    weight += dt;
  });
  return {sum.internal / weight, sum.external / weight, sum.base / weight};
}

void expect_seed_torsion(const TorsionReactions& f, const std::string& label) {
  std::cout << label << ": internal " << f.internal << ", external " << f.external << ", base "
            << f.base << " N/rad\n";
  // The soil resists the spin: forces on the pile are negative. Tolerances are the issue's: 3 % per
  // face, 2 % on the sum; the analytical values assume the whole interface slides.
  EXPECT_NEAR(f.internal, -2000.0, 0.03 * 2000.0) << label;
  EXPECT_NEAR(f.external, -3000.0, 0.03 * 3000.0) << label;
  EXPECT_NEAR(f.base, -1000.0, 0.03 * 1000.0) << label;
  EXPECT_NEAR(f.internal + f.external + f.base, -6000.0, 0.02 * 6000.0) << label;
}

TEST(V9TorsionWithAdhesion, RigidPileAtTheCaseFileResolution) {
  // 11 000 steps of 6 400 particles: the sanitizer presets leave this accuracy check to the
  // release build (docs/reliability.md, "What the sanitizer builds leave out").
  // `mpile verify V9`: the case file built into the program, run through the phase runner.
  const verification::Report report = verification::run_torsion_with_adhesion({});
  ASSERT_EQ(report.checks.size(), 4u);
  expect_seed_torsion(
      {report.checks[0].measured, report.checks[1].measured, report.checks[2].measured},
      "V9, 40 x 40 cells");
  EXPECT_TRUE(report.passed());
}

TEST(V9TorsionWithAdhesion, RigidPileAtTwoCoarserResolutions) {
  const std::string text = read_text(source / "cases/verification/v9_torsion_adhesion.toml");
  for (const char* cells : {"cells = 20", "cells = 10"}) {
    expect_seed_torsion(torsion_reactions(replaced(text, "cells = 40", cells)),
                        std::string("V9, ") + cells);
  }
}

TEST(V9TorsionWithAdhesion, ElasticPileTwistedAtItsHead) {
  // The seed's pile is elastic (E = 100 MPa): a deformable structure in its own field, its head
  // nodes spun at 0.02 rad/s by a prescribed motion on that field. The reactions must be those of
  // the rigid pile: the adhesion limits them, not the pile's stiffness.
  std::string text = read_text(source / "cases/verification/v9_torsion_adhesion.toml");
  text = replaced(text, "cells = 40", "cells = 20");
  text = replaced(text, "[bodies.rigid]\nangular_velocity = { type = \"constant\", value = 0.02 }",
                  "");
  text = replaced(text, "velocity_y = { type = \"constant\", value = 0.0 }\n", "");
  text += "\n[[prescribed]]\nname = \"pile head\"\nbody = \"pile\"\n"
          "nodes = { y = 1.0, r = [0.4, 0.6] }\n"
          "angular_velocity = { type = \"constant\", value = 0.02 }\n";
  CaseRun probe(text);
  ASSERT_TRUE(probe.scene->rigid_bodies.empty());
  ASSERT_EQ(probe.scene->contacts.size(), 1u);
  expect_seed_torsion(torsion_reactions(text), "V9, elastic pile, 20 x 20 cells");
}

// ---------------------------------------------------------------------------------------------
// Momentum exchange, separation and rigid-body dynamics.

TEST(RigidBody, ForceDrivenDofsIntegrateExactlyWithoutContact) {
  // A rigid block above the soil, never touching it, pushed by a constant force and a ramped
  // torque under gravity: V(t) = (F/M + g) t, omega(t) = T0 t^2 / (2 t_r J) on the ramp.
  std::string text = read_text(source / "cases/verification/v9_torsion_adhesion.toml");
  text = replaced(text, "cells = 40", "cells = 10");
  text = replaced(text, "region = { r = [0.4, 0.6], y = [0.5, 1.0] }",
                  "region = { r = [0.4, 0.6], y = [1.3, 1.5] }");
  text = replaced(text, "y = [{ start = 0.0, end = 1.0, cells = 10 }]",
                  "y = [{ start = 0.0, end = 2.0, cells = 20 }]");
  text = replaced(text, "angular_velocity = { type = \"constant\", value = 0.02 }   # rad/s",
                  "torque = { type = \"ramp\", value = 50.0, duration = 0.5 }\nmass = 40.0\n"
                  "polar_inertia = 3.0");
  text = replaced(text, "velocity_y = { type = \"constant\", value = 0.0 }",
                  "force_y = { type = \"constant\", value = 600.0 }");
  text = replaced(text, "duration = 1.0", "duration = 0.2");
  text += "\n[solver]\ngravity = [0.0, -9.81]\n";
  CaseRun run(text);
  run.run([] {});
  const RigidBody& body = run.scene->rigid_bodies.at(0);
  const double t = run.solver->time();
  // Exact to round-off: the drives are integrated with their exact means over each step.
  EXPECT_NEAR(body.velocity[RIGID_Y], (600.0 / 40.0 - 9.81) * t, 1e-12);
  EXPECT_NEAR(body.velocity[RIGID_ROTATION], 50.0 * t * t / (2.0 * 0.5 * 3.0), 1e-12);
  EXPECT_EQ(body.contact[RIGID_Y], 0.0);
  // The block's particles moved with it.
  const Particles& p = run.scene->particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (run.scene->field_of(p.body[i]) != 0) {
      EXPECT_NEAR(p.y[i] - p.y0[i], body.displacement[RIGID_Y], 1e-12);
    }
  }
}

// cases/verification/force_driven_plate.toml: a rigid plate pressed by a force onto an elastic
// layer in one-dimensional compression settles q H / E_oed and stays, damped or not. When the
// contact corrected the soil to the body's predicted (unresisted) velocity and the body closed its
// step at the resisted one, the soil under it moved further than the body every step and the
// plate sank without end: 1.07 mm at 0.1 s, 2.49 mm at 0.4 s, the energy residual over 60 %.
struct PlateSettlement {
  double at_0_2 = 0.0, at_0_4 = 0.0, residual = 0.0, contact = 0.0;
};

PlateSettlement press_plate(double local_damping) {
  std::string text = read_text(source / "cases/verification/force_driven_plate.toml");
  text = replaced(text, "local_damping = 0.7", "local_damping = " + std::to_string(local_damping));
  CaseRun run(text);
  PlateSettlement settled;
  run.run([&] {
    if (settled.at_0_2 == 0.0 && run.solver->time() >= 0.2) {
      settled.at_0_2 = -run.scene->rigid_bodies.at(0).displacement[RIGID_Y];
    }
  });
  settled.at_0_4 = -run.scene->rigid_bodies.at(0).displacement[RIGID_Y];
  settled.contact = run.scene->rigid_bodies.at(0).contact[RIGID_Y];
  settled.residual = run.solver->energy_balance().relative_residual;
  return settled;
}

TEST(RigidBody, AForceDrivenPlateSettlesOnAnElasticLayerAndStays) {
  const double e_oed = 3.714e6 * 0.7 / (1.3 * 0.4);
  const double settlement = 20e3 * 0.1 / e_oed;
  const PlateSettlement damped = press_plate(0.7);
  // 1 %: the same plate driven at a prescribed velocity meets the elastic reaction within 0.4 %
  // on these 1 cm cells (the discretisation's own error); sinking gave 1.07 mm at 0.1 s.
  EXPECT_NEAR(damped.at_0_4, settlement, 0.01 * settlement);
  EXPECT_NEAR(damped.contact, 600.0, 0.01 * 600.0);
  // At rest: no creep between 0.2 and 0.4 s (sinking went at a few mm/s).
  EXPECT_NEAR(damped.at_0_4, damped.at_0_2, 1e-4 * settlement);
  // The ledger closes to the quadrature of the ramp (0.04 % measured; 103 % when sinking).
  EXPECT_LT(std::abs(damped.residual), 0.005);
  // Undamped, the plate oscillates about the settlement (measured 0.394 to 0.409 mm after the
  // ramp): within the 2.5 % amplitude the ramp's 0.05 s leaves against the layer's period.
  const PlateSettlement free = press_plate(0.0);
  EXPECT_NEAR(free.at_0_2, settlement, 0.025 * settlement);
  EXPECT_NEAR(free.at_0_4, settlement, 0.025 * settlement);
  EXPECT_LT(std::abs(free.residual), 0.01);
}

// ---------------------------------------------------------------------------------------------
// Thread identity with contact: the contact pass corrects each node on its own and sums surfaces
// with a deterministic reduction, so 1 and 2 threads must agree bitwise.

struct ContactOutcome {
  Particles particles;
  std::vector<std::array<double, 3>> surface_force;
  std::vector<RigidBody> rigid;
};

ContactOutcome run_with_threads(const std::string& text, int threads) {
  ContactOutcome outcome;
  with_threads(threads, [&] {
    CaseRun run(text);
    run.run([] {});
    outcome.particles = run.scene->particles;
    outcome.surface_force = run.pair().surface_force;
    outcome.rigid = run.scene->rigid_bodies;
  });
  return outcome;
}

void expect_identical_contact(const ContactOutcome& a, const ContactOutcome& b) {
  expect_particles_identical(a.particles, b.particles);
  EXPECT_TRUE(bitwise_equal(a.surface_force, b.surface_force));
  expect_rigid_bodies_identical(a.rigid, b.rigid);
}

TEST(ContactThreadIdentity, TorsionWithAdhesionOneAndTwoThreads) {
  std::string text = read_text(source / "cases/verification/v9_torsion_adhesion.toml");
  text = replaced(text, "cells = 40", "cells = 20");
  text = replaced(text, "duration = 1.0", "duration = 0.1");
  text += "\n[solver]\nblock_cells = 2\n"; // many blocks per colour
  expect_identical_contact(run_with_threads(text, 1), run_with_threads(text, 2));
}

TEST(ContactThreadIdentity, SlidingOnADeformableInclineOneAndTwoThreads) {
  std::string text = deformable_incline(incline_text(30.0, 0.3));
  // 0.2 s of sliding at g (sin a - mu cos a) = 2.36 m/s^2 moves the block by about 4 cm: enough
  // for the particles 2.5 cm short of a block boundary to cross it (checked below), and under
  // ThreadSanitizer each tenth of a second costs about 45 s.
  text = replaced(text, "duration = 1.0", "duration = 0.2");
  text = replaced(text, "[solver]\n", "[solver]\nblock_cells = 2\n");
  const ContactOutcome one = run_with_threads(text, 1);
  expect_identical_contact(one, run_with_threads(text, 2));
  // Block particles that crossed into another block of two 0.1 m cells (boundaries at multiples
  // of 0.2 m from r = 0): the re-binning into other blocks was exercised.
  const double block_width = 0.2;
  int crossed = 0;
  for (std::size_t i = 0; i < one.particles.size(); ++i) {
    if (one.particles.body[i] == 0 && std::floor(one.particles.r[i] / block_width) !=
                                          std::floor(one.particles.r0[i] / block_width)) {
      ++crossed;
    }
  }
  EXPECT_GT(crossed, 0);
}

} // namespace
} // namespace mpile
