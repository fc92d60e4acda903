// V1: axial vibrating bar (Sulsky et al. 1995; Bardenhagen 2002) in axisymmetric mode with nu = 0,
// so the motion is exactly one-dimensional. Exact: v = v0 sin(beta y) cos(omega t), mass-weighted
// mean velocity (2 v0 / pi) cos(omega t), period 10, energy rho A L v0^2 / 4 = 0.03125 J/rad.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/diagnostics.hpp"
#include "solver/explicit_solver.hpp"

#include <chrono>
#include <cmath>
#include <numbers>

namespace mpile::verification {

Report run_vibrating_bar(const Options& options) {
  const auto start = std::chrono::steady_clock::now();
  constexpr double radius = 1.0, length = 25.0, young = 100.0, density = 1.0, v0 = 0.1;
  const double beta = std::numbers::pi / (2.0 * length);
  const double omega = beta * std::sqrt(young / density);
  const double period = 2.0 * std::numbers::pi / omega;
  const int n = options.refinement;

  // Base mesh h = 1 (25 cells along the bar, one across); one spare cell above the free end.
  Scene scene(GeometryMode::axisymmetric, uniform_grid(0.0, radius, n, 0.0, length + 1.0, 26 * n));
  const auto material = scene.add_material(std::make_unique<LinearElastic>(young, 0.0, density));
  const auto body = scene.add_body("bar");
  fill_rectangle(scene, {0.0, radius, 0.0, length}, options.particles_per_direction, material,
                 body);
  for (std::size_t i = 0; i < scene.particles.size(); ++i) {
    scene.particles.v_y[i] = v0 * std::sin(beta * scene.particles.y[i]);
  }
  scene.boundaries.constraints = {
      axis_constraint(scene.grid),
      face_constraint(scene.grid, scene.mode, GridFace::y_min, FaceCondition::roller)};

  SolverSettings settings;
  settings.flip_fraction = 1.0; // FLIP: the reference conserves energy
  settings = apply_options(settings, options);
  RunLog log;
  ExplicitSolver solver(scene, settings, log);

  const double energy0 = kinetic_energy(scene) + elastic_energy(scene);
  OscillationMeter meter(0.0, mean_velocity(scene)[1]);
  while (solver.time() < 3.0 * period) {
    solver.step();
    meter.sample(solver.time(), mean_velocity(scene)[1]);
  }
  const double energy = kinetic_energy(scene) + elastic_energy(scene);
  const double cycles = solver.time() / period;

  Report report{"V1",
                "axial vibrating bar (axisymmetric)",
                {},
                scene.particles.size(),
                solver.step_count(),
                0.0,
                log.warnings()};
  const double exact_energy = density * 0.5 * radius * radius * length * v0 * v0 / 4.0;
  report.checks = {
      {"period", "s", meter.period(), period, period, 0.01},
      {"centre-of-mass velocity amplitude", "m/s", meter.amplitude(), 2.0 * v0 / std::numbers::pi,
       2.0 * v0 / std::numbers::pi, 0.02},
      {"initial energy", "J/rad", energy0, exact_energy, exact_energy, 0.01},
      {"energy drift per period", "J/rad", (energy - energy0) / cycles, 0.0, energy0, 0.01},
  };
  report.wall_seconds = seconds_since(start);
  return report;
}

} // namespace mpile::verification
