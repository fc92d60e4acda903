// Colored scatter fixes the order of every nodal sum, so results must be bitwise identical for any
// thread count. The scene is made to stress that: large motion (particles change cells and blocks,
// so re-binning and physical re-sorting happen), small blocks (many per colour), B-bar, a FLIP/PIC
// blend, damping, gravity and a circumferential swirl.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/diagnostics.hpp"
#include "solver/explicit_solver.hpp"
#include "tests/bitwise.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace mpile {
namespace {

struct Outcome {
  Particles particles;
  double time = 0.0;
  double kinetic = 0.0;
  std::array<double, 3> reaction{};
};

Outcome collapse(GeometryMode mode, int threads, ShapeFunctions shape = ShapeFunctions::linear,
                 int xpic_order = 0) {
  Outcome outcome;
  with_threads(threads, [&] {
    const AxisZone r_zones[] = {{0.0, 0.6, 24}, {0.6, 2.0, 14}};
    const AxisZone y_zones[] = {{0.0, 1.4, 28}};
    Scene scene(mode, Grid(GradedAxis(r_zones), GradedAxis(y_zones)));
    const auto material = scene.add_material(std::make_unique<LinearElastic>(5e4, 0.3, 2000.0));
    const auto body = scene.add_body("column");
    fill_rectangle(scene, {0.0, 0.5, 0.0, 1.0}, 3, material, body);
    for (std::size_t i = 0; i < scene.particles.size(); ++i) {
      if (has_theta(mode)) {
        scene.particles.v_theta[i] = 0.5 * scene.particles.r[i];
      }
      scene.particles.v_r[i] = 0.2 * scene.particles.y[i];
    }
    scene.boundaries.constraints = {
        face_constraint(scene.grid, mode, GridFace::y_min, FaceCondition::fixed),
        face_constraint(scene.grid, mode, GridFace::r_max, FaceCondition::roller)};
    if (has_theta(mode)) {
      scene.boundaries.constraints.push_back(axis_constraint(scene.grid));
    } else {
      scene.boundaries.constraints.push_back(
          face_constraint(scene.grid, mode, GridFace::r_min, FaceCondition::roller));
    }
    SolverSettings settings;
    settings.gravity = {0.0, -9.81};
    settings.flip_fraction = xpic_order > 0 ? 1.0 : 0.97;
    settings.xpic_order = xpic_order;
    settings.local_damping = 0.05;
    // The smallest blocks allowed: with GIMP, whose particles write one cell beyond their block,
    // two blocks of one colour then stand just far enough apart (a race would show here, and
    // under ThreadSanitizer).
    settings.shape_functions = shape;
    settings.block_cells = shape == ShapeFunctions::gimp ? 3 : 2;
    RunLog log;
    ExplicitSolver solver(scene, settings, log);
    for (int s = 0; s < 400; ++s) {
      solver.step();
    }
    outcome.particles = scene.particles;
    outcome.time = solver.time();
    outcome.kinetic = kinetic_energy(scene);
    outcome.reaction = scene.boundaries.constraint("y_min").reaction;
    // The scene must have moved particles far enough to exercise re-binning.
    double max_move = 0.0;
    for (std::size_t i = 0; i < scene.particles.size(); ++i) {
      max_move = std::max(max_move, std::abs(scene.particles.y[i] - scene.particles.y0[i]));
    }
    EXPECT_GT(max_move, 0.1) << "the scene did not deform enough to test re-binning";
  });
  return outcome;
}

void expect_identical(const Outcome& a, const Outcome& b) {
  EXPECT_EQ(std::memcmp(&a.time, &b.time, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&a.kinetic, &b.kinetic, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(a.reaction.data(), b.reaction.data(), sizeof(a.reaction)), 0);
  expect_particles_identical(a.particles, b.particles);
}

TEST(ThreadIdentity, AxisymmetricResultsAreBitwiseIdenticalForOneTwoAndThreeThreads) {
  const Outcome one = collapse(GeometryMode::axisymmetric, 1);
  expect_identical(one, collapse(GeometryMode::axisymmetric, 2));
  expect_identical(one, collapse(GeometryMode::axisymmetric, 3));
}

TEST(ThreadIdentity, PlaneStrainResultsAreBitwiseIdenticalForOneAndTwoThreads) {
  const Outcome one = collapse(GeometryMode::plane_strain, 1);
  expect_identical(one, collapse(GeometryMode::plane_strain, 2));
}

TEST(ThreadIdentity, GimpResultsAreBitwiseIdenticalForOneTwoAndThreeThreads) {
  const Outcome one = collapse(GeometryMode::axisymmetric, 1, ShapeFunctions::gimp);
  expect_identical(one, collapse(GeometryMode::axisymmetric, 2, ShapeFunctions::gimp));
  expect_identical(one, collapse(GeometryMode::axisymmetric, 3, ShapeFunctions::gimp));
}

// XPIC adds colored gather-scatters of its own (solver/xpic.cpp).
TEST(ThreadIdentity, XpicResultsAreBitwiseIdenticalForOneTwoAndThreeThreads) {
  const Outcome one = collapse(GeometryMode::axisymmetric, 1, ShapeFunctions::linear, 3);
  expect_identical(one, collapse(GeometryMode::axisymmetric, 2, ShapeFunctions::linear, 3));
  expect_identical(one, collapse(GeometryMode::axisymmetric, 3, ShapeFunctions::linear, 3));
}

} // namespace
} // namespace mpile
