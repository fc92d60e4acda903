// V2: a single material point in one cell of length 1, plane strain with nu = 0 and rollers top and
// bottom, so the motion is one-dimensional. Node line x = 0 fixed; E = 4 pi^2, rho = 1, v0 = 0.1.
// With lumped mass the node carries m/2 and MUSL gives v_node = v_p, so v_p = v0 cos(2 pi t), T
// = 1.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/explicit_solver.hpp"

#include <chrono>
#include <cmath>
#include <numbers>

namespace mpile::verification {

Report run_single_point(const Options& options) {
  const auto start = std::chrono::steady_clock::now();
  constexpr double v0 = 0.1;
  const double young = 4.0 * std::numbers::pi * std::numbers::pi;
  Scene scene(GeometryMode::plane_strain, uniform_grid(0.0, 1.0, 1, 0.0, 1.0, 1));
  const auto material = scene.add_material(std::make_unique<LinearElastic>(young, 0.0, 1.0));
  const auto body = scene.add_body("point");
  fill_rectangle(scene, {0.0, 1.0, 0.0, 1.0}, 1, material, body);
  scene.particles.v_r[0] = v0;
  scene.boundaries.constraints = {
      face_constraint(scene.grid, scene.mode, GridFace::r_min, FaceCondition::fixed),
      face_constraint(scene.grid, scene.mode, GridFace::y_min, FaceCondition::roller),
      face_constraint(scene.grid, scene.mode, GridFace::y_max, FaceCondition::roller)};

  SolverSettings settings;
  settings.flip_fraction = 1.0;
  settings.courant_number = 0.1; // the period is resolved by ~100 steps per cycle
  settings = apply_options(settings, options);
  RunLog log;
  ExplicitSolver solver(scene, settings, log);

  OscillationMeter meter(0.0, v0);
  while (solver.time() < 3.0) {
    solver.step();
    meter.sample(solver.time(), scene.particles.v_r[0]);
  }
  Report report{"V2",
                "single material point vibration",
                {},
                scene.particles.size(),
                solver.step_count(),
                0.0,
                log.warnings()};
  report.checks = {
      {"period", "s", meter.period(), 1.0, 1.0, 0.005},
      {"velocity amplitude", "m/s", meter.amplitude(), v0, v0, 0.005},
  };
  report.wall_seconds = seconds_since(start);
  return report;
}

} // namespace mpile::verification
