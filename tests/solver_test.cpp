// Checks of the explicit step against exact answers: the CFL time step, mass scaling, free fall
// under gravity, stress-free rigid spin about the axis, and the guards on bad scenes.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/explicit_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <utility>

namespace mpile {
namespace {

using verification::uniform_grid;

Scene elastic_block(GeometryMode mode, double young = 100e6, double nu = 0.3) {
  Scene scene(mode, uniform_grid(0.0, 2.0, 20, 0.0, 2.0, 20));
  const auto material = scene.add_material(std::make_unique<LinearElastic>(young, nu, 2000.0));
  const auto body = scene.add_body("block");
  fill_rectangle(scene, {0.5, 1.5, 0.5, 1.5}, 2, material, body);
  return scene;
}

TEST(Solver, TimeStepIsCourantTimesCellOverWaveSpeed) {
  Scene scene = elastic_block(GeometryMode::axisymmetric);
  SolverSettings settings;
  settings.courant_number = 0.5;
  RunLog log;
  ExplicitSolver solver(scene, settings, log);
  const double modulus = 100e6 * 0.7 / (1.3 * 0.4); // E (1 - nu) / ((1 + nu)(1 - 2 nu))
  EXPECT_NEAR(solver.stable_time_step(), 0.5 * 0.1 / std::sqrt(modulus / 2000.0), 1e-15);
  EXPECT_TRUE(log.warnings().empty());
}

// Stretches one particle by 1.4 times its volume a step for six steps (its wave speed 1.18 times
// a step, as fast as the Courant guard lets it grow), 7.5 times in all, so its wave speed grows
// 2.7 times and the step falls to 1.4^-3 = 0.37 of what it was; returns that ratio and the count
// of the log's reports of a falling step.
std::pair<double, std::size_t> stretch_one_particle(Scene& scene, ExplicitSolver& solver,
                                                    const std::ostringstream& said) {
  const double before = solver.stable_time_step();
  for (int s = 0; s < 6; ++s) {
    scene.particles.volume[37] *= 1.4;
    solver.step();
  }
  const std::string text = said.str();
  std::size_t reports = 0;
  for (std::size_t at = text.find("the stable step fell to "); at != std::string::npos;
       at = text.find("the stable step fell to ", at + 1)) {
    ++reports;
  }
  return {solver.stable_time_step() / before, reports};
}

// When the stable step falls below half of what it was, the log says which particle sets it and
// why: one halving, one report.
TEST(Solver, AFallingStepIsTracedToTheParticleThatSetsIt) {
  Scene scene = elastic_block(GeometryMode::axisymmetric);
  std::ostringstream said;
  RunLog log(&said);
  ExplicitSolver solver(scene, SolverSettings{}, log);
  const auto [fall, reports] = stretch_one_particle(scene, solver, said);
  EXPECT_NEAR(fall, std::pow(1.4, -3.0), 0.02);
  const std::string text = said.str();
  EXPECT_EQ(reports, 1u) << text;
  EXPECT_NE(text.find("it is set by particle 37 at (r, y) = ("), std::string::npos) << text;
  EXPECT_NE(text.find("of body 'block' in a cell of 0.1 m"), std::string::npos) << text;
  EXPECT_NE(text.find("kg/m^3 (its material's 2000)"), std::string::npos) << text;
}

// A phase that scales the mass grows the step tenfold at once; a fall by more than half from
// there is reported as well (it was not, when falls were measured from the first phase's step).
TEST(Solver, AFallingStepIsTracedAfterMassScalingGrewIt) {
  Scene scene = elastic_block(GeometryMode::axisymmetric);
  SolverSettings settings;
  std::ostringstream said;
  RunLog log(&said);
  ExplicitSolver solver(scene, settings, log);
  settings.mass_scaling = 100.0;
  solver.change_settings(settings);
  const auto [fall, reports] = stretch_one_particle(scene, solver, said);
  EXPECT_NEAR(fall, std::pow(1.4, -3.0), 0.02);
  EXPECT_EQ(reports, 1u) << said.str();
  EXPECT_NE(said.str().find("it is set by particle 37 at (r, y) = ("), std::string::npos);
}

TEST(Solver, MassScalingGrowsTheStepAndWarns) {
  Scene plain = elastic_block(GeometryMode::axisymmetric);
  Scene scaled = elastic_block(GeometryMode::axisymmetric);
  RunLog plain_log, scaled_log;
  SolverSettings settings;
  ExplicitSolver reference(plain, settings, plain_log);
  settings.mass_scaling = 100.0;
  ExplicitSolver solver(scaled, settings, scaled_log);
  EXPECT_NEAR(solver.stable_time_step(), 10.0 * reference.stable_time_step(), 1e-15);
  ASSERT_EQ(scaled_log.warnings().size(), 1u);
  EXPECT_NE(scaled_log.warnings()[0].find("mass scaling x100"), std::string::npos);
  EXPECT_NE(scaled_log.warnings()[0].find("inertia is distorted"), std::string::npos);
}

TEST(Solver, FreeFallMatchesTheDiscreteExactSolution) {
  for (const GeometryMode mode : {GeometryMode::axisymmetric, GeometryMode::plane_strain}) {
    Scene scene = elastic_block(mode);
    SolverSettings settings;
    settings.gravity = {0.0, -9.81};
    settings.max_time_step = 1e-4; // a fixed step, so the discrete answer is known
    RunLog log;
    ExplicitSolver solver(scene, settings, log);
    constexpr int steps = 200;
    for (int s = 0; s < steps; ++s) {
      solver.step();
    }
    const double dt = 1e-4;
    // Symplectic Euler: v_n = -g n dt, y_n - y_0 = -g dt^2 n (n + 1) / 2. An unsupported block
    // stays stress free, so every particle follows it exactly (up to rounding).
    for (std::size_t i = 0; i < scene.particles.size(); ++i) {
      ASSERT_NEAR(scene.particles.v_y[i], -9.81 * steps * dt, 1e-12);
      ASSERT_NEAR(scene.particles.y[i] - scene.particles.y0[i],
                  -9.81 * dt * dt * steps * (steps + 1) / 2.0, 1e-12);
      ASSERT_NEAR(scene.particles.stress[i][YY], 0.0, 1e-6);
    }
  }
}

TEST(Solver, RigidSpinAboutTheAxisIsStressFree) {
  // Omega on every node (the velocity field sets each node's angular velocity v_theta / r):
  // gamma_rtheta = dv/dr - v/r = r d(omega)/dr = 0 (physics.md section 2); without the -v/r term
  // each particle would shear by Omega dt per step. A free spin, through the transfer, is in
  // tests/rigid_spin_test.cpp.
  Scene scene = elastic_block(GeometryMode::axisymmetric);
  constexpr double spin = 2.0; // rad/s
  scene.velocity_field = [](double r, double, double) {
    return std::array<double, 3>{0.0, 0.0, spin * r};
  };
  RunLog log;
  ExplicitSolver solver(scene, SolverSettings{}, log);
  solver.advance_to(0.01);
  for (std::size_t i = 0; i < scene.particles.size(); ++i) {
    for (const double component : scene.particles.stress[i]) {
      // A shear of Omega t = 0.02 would give tau = G 0.02 = 7.7e5 Pa; rounding gives ~1e-7 Pa.
      ASSERT_NEAR(component, 0.0, 1e-3);
    }
    ASSERT_NEAR(scene.particles.u_theta[i], spin * scene.particles.r0[i] * 0.01, 1e-12);
  }
}

TEST(Solver, ParticleLeavingTheGridStopsTheRunWithItsPosition) {
  Scene scene = elastic_block(GeometryMode::plane_strain);
  for (double& v : scene.particles.v_r) {
    v = 400.0; // out of the 2 m grid within a few steps
  }
  RunLog log;
  ExplicitSolver solver(scene, SolverSettings{}, log);
  try {
    solver.advance_to(0.01);
    FAIL() << "expected a SimulationError";
  } catch (const SimulationError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("left the grid"), std::string::npos) << message;
    EXPECT_NE(message.find("particle "), std::string::npos) << message;
    EXPECT_NE(message.find("(r, y) = ("), std::string::npos) << message;
  }
}

TEST(Solver, RejectsBadScenesAndSettings) {
  RunLog log;
  {
    Scene scene = elastic_block(GeometryMode::axisymmetric);
    scene.particles.r[0] = 0.0;
    scene.particles.r0[0] = 0.0;
    EXPECT_THROW(ExplicitSolver(scene, SolverSettings{}, log), std::invalid_argument);
  }
  {
    Scene scene = elastic_block(GeometryMode::axisymmetric);
    scene.particles.y[3] = 5.0;
    EXPECT_THROW(ExplicitSolver(scene, SolverSettings{}, log), std::invalid_argument);
  }
  for (const auto& change : std::vector<std::function<void(SolverSettings&)>>{
           [](SolverSettings& s) { s.courant_number = 0.0; },
           [](SolverSettings& s) { s.flip_fraction = 1.5; },
           [](SolverSettings& s) { s.local_damping = -0.1; },
           [](SolverSettings& s) { s.mass_scaling = 0.5; },
           [](SolverSettings& s) { s.block_cells = 0; }}) {
    SolverSettings settings;
    change(settings);
    Scene scene = elastic_block(GeometryMode::axisymmetric);
    EXPECT_THROW(ExplicitSolver(scene, settings, log), std::invalid_argument);
  }
}

} // namespace
} // namespace mpile
