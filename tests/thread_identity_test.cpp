// Colored scatter fixes the order of every nodal sum, so results must be bitwise identical for any
// thread count. The scene is made to stress that: large motion (particles change cells and blocks,
// so re-binning and physical re-sorting happen), small blocks (many per colour), B-bar, a FLIP/PIC
// blend, damping, gravity and a circumferential swirl.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/hardening_soil.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/diagnostics.hpp"
#include "solver/explicit_solver.hpp"
#include "tests/bitwise.hpp"
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <iostream>
#include <map>
#include <utility>

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
  for (const int threads : threads_compared_with_one()) {
    expect_identical(one, collapse(GeometryMode::axisymmetric, threads));
  }
}

TEST(ThreadIdentity, PlaneStrainResultsAreBitwiseIdenticalForOneAndTwoThreads) {
  const Outcome one = collapse(GeometryMode::plane_strain, 1);
  expect_identical(one, collapse(GeometryMode::plane_strain, 2));
}

TEST(ThreadIdentity, GimpResultsAreBitwiseIdenticalForOneTwoAndThreeThreads) {
  const Outcome one = collapse(GeometryMode::axisymmetric, 1, ShapeFunctions::gimp);
  for (const int threads : threads_compared_with_one()) {
    expect_identical(one, collapse(GeometryMode::axisymmetric, threads, ShapeFunctions::gimp));
  }
}

// XPIC adds colored gather-scatters of its own (solver/xpic.cpp).
TEST(ThreadIdentity, XpicResultsAreBitwiseIdenticalForOneTwoAndThreeThreads) {
  const Outcome one = collapse(GeometryMode::axisymmetric, 1, ShapeFunctions::linear, 3);
  for (const int threads : threads_compared_with_one()) {
    expect_identical(one, collapse(GeometryMode::axisymmetric, threads, ShapeFunctions::linear, 3));
  }
}

// The production path: the quick GDP case (Hardening Soil with its ordered return and substeps,
// Coulomb contact with adhesion against the rigid pile, the torque drive, the moving mesh with
// GIMP, B-bar and the particles' own time step) from its K0 state. The geostatic phase is left out
// and its K0 procedure applied directly, so that a few hundredths of a second of driving, with
// plastic returns from the first step, reach every pass.
struct GdpOutcome {
  Particles particles;
  std::vector<std::array<double, 3>> surface_force;
  std::vector<RigidBody> rigid;
  std::vector<double> grid_lines;
  double time = 0.0;
  int hardened = 0; // soil particles whose plastic shear strain grew during the drive
};

GdpOutcome drive_quick_gdp(int threads) {
  std::string text = read_text(source / "tests/data/gdp_quick_flat.toml");
  text = replaced(text,
                  "name = \"geostatic\"\nduration = 2.0\nlocal_damping = 0.7\n"
                  "equilibrium_tolerance = 0.01\nk0 = [{ material = \"sand\", surface = 10.0, "
                  "k0 = 0.5 }]\n\n[[phases]]\nname = \"installation\"\nduration = 30.0",
                  "name = \"installation\"\nduration = 0.006\nk0 = [{ material = \"sand\", "
                  "surface = 10.0, k0 = 0.5 }]");
  GdpOutcome outcome;
  with_threads(threads, [&] {
    CaseRun run(text);
    EXPECT_EQ(run.spec.phases[0].name, "installation");
    apply_k0(*run.scene, run.spec, run.spec.phases[0]);
    // The K0 state's plastic shear strain of each particle, by its initial position (the run
    // re-sorts the particles).
    std::map<std::pair<double, double>, double> k0_gamma;
    const Particles& p = run.scene->particles;
    const auto stride = static_cast<std::size_t>(p.state_stride);
    ASSERT_GT(stride, 0u);
    for (std::size_t i = 0; i < p.size(); ++i) {
      k0_gamma[{p.r0[i], p.y0[i]}] = p.state[i * stride + HardeningSoil::GAMMA_P];
    }
    // The solver as `mpile run` makes it, after the K0 stresses: its first step is taken from them.
    run.solver = std::make_unique<ExplicitSolver>(
        *run.scene, phase_settings(run.spec, run.spec.phases[0]), run.log);
    switch_on_absorbing_faces(*run.solver, run.spec, 0);
    run.run([] {});
    outcome.particles = run.scene->particles;
    outcome.surface_force = run.pair().surface_force;
    outcome.rigid = run.scene->rigid_bodies;
    const auto y = run.scene->grid.y_axis().nodes();
    outcome.grid_lines.assign(y.begin(), y.end());
    outcome.time = run.solver->time();
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto start = k0_gamma.find({p.r0[i], p.y0[i]});
      if (start != k0_gamma.end() && p.state[i * stride + HardeningSoil::GAMMA_P] > start->second) {
        ++outcome.hardened;
      }
    }
  });
  return outcome;
}

void expect_identical(const GdpOutcome& a, const GdpOutcome& b) {
  EXPECT_EQ(std::memcmp(&a.time, &b.time, sizeof(double)), 0);
  expect_particles_identical(a.particles, b.particles);
  EXPECT_TRUE(bitwise_equal(a.particles.state, b.particles.state)); // gamma_p and the cap
  EXPECT_TRUE(bitwise_equal(a.surface_force, b.surface_force));
  EXPECT_TRUE(bitwise_equal(a.grid_lines, b.grid_lines));
  expect_rigid_bodies_identical(a.rigid, b.rigid);
}

TEST(ThreadIdentity, TheQuickGdpInstallationIsBitwiseIdenticalForOneTwoAndThreeThreads) {
  const GdpOutcome one = drive_quick_gdp(1);
  // The run must have reached the pile's twist and the soil's plastic state, or it tests little.
  ASSERT_EQ(one.rigid.size(), 1u);
  EXPECT_GT(std::abs(one.rigid[0].velocity[2]), 0.0) << "the pile did not turn";
  EXPECT_GT(one.hardened, 100) << "too few plastic returns to test the Hardening Soil path";
  std::cout << "quick GDP driven for " << one.time << " s: pile omega " << one.rigid[0].velocity[2]
            << " rad/s, " << one.hardened << " of " << one.particles.size()
            << " particles hardened in shear\n";
  expect_identical(one, drive_quick_gdp(2));
  expect_identical(one, drive_quick_gdp(3));
}

} // namespace
} // namespace mpile
