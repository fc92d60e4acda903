// Plane-strain patch test: a uniform, symmetric velocity gradient prescribed on every node of a
// graded grid. Every particle must reach the uniform stress C : eps of linear elasticity with
// eps_zz = 0, whatever its position, with and without B-bar.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/explicit_solver.hpp"

#include <algorithm>
#include <cmath>

namespace mpile::verification {

Report run_plane_strain_patch(const Options& options) {
  const auto start = std::chrono::steady_clock::now();
  constexpr double young = 100e6, nu = 0.3, density = 2000, duration = 0.01;
  constexpr double exx = 1e-3, eyy = -4e-4, gxy = 6e-4; // engineering shear
  const int n = options.refinement;
  const AxisZone x_zones[] = {{0.0, 0.3, 3 * n}, {0.3, 1.0, 2 * n}};
  const AxisZone y_zones[] = {{0.0, 0.2, 1 * n}, {0.2, 0.5, 3 * n}, {0.5, 1.0, 2 * n}};
  Scene scene(GeometryMode::plane_strain, Grid(GradedAxis(x_zones), GradedAxis(y_zones)));
  const auto material = scene.add_material(std::make_unique<LinearElastic>(young, nu, density));
  const auto body = scene.add_body("patch");
  fill_rectangle(scene, {0.0, 1.0, 0.0, 1.0}, options.particles_per_direction, material, body);
  // v = L x with L symmetric (no spin), so the total strain after T is exactly (exx, eyy, gxy).
  scene.velocity_field = [&](double x, double y, double) {
    return std::array<double, 3>{(exx * x + 0.5 * gxy * y) / duration,
                                 (0.5 * gxy * x + eyy * y) / duration, 0.0};
  };
  SolverSettings settings = apply_options(SolverSettings{}, options);
  RunLog log;
  ExplicitSolver solver(scene, settings, log);
  solver.advance_to(duration);

  const auto& elastic = dynamic_cast<const LinearElastic&>(*scene.materials[material]);
  const double lambda = elastic.lame_lambda(), mu = elastic.shear_modulus();
  const Stress exact{lambda * (exx + eyy) + 2 * mu * exx,
                     lambda * (exx + eyy) + 2 * mu * eyy,
                     lambda * (exx + eyy),
                     mu * gxy,
                     0.0,
                     0.0};
  double worst = 0.0;
  for (const Stress& s : scene.particles.stress) {
    for (int c = 0; c < 6; ++c) {
      worst = std::max(
          worst, std::abs(s[static_cast<std::size_t>(c)] - exact[static_cast<std::size_t>(c)]));
    }
  }
  const double scale = std::abs(exact[RR]);
  Report report{"V4p",
                "plane-strain patch test",
                {},
                scene.particles.size(),
                solver.step_count(),
                0.0,
                log.warnings()};
  report.checks = {{"max stress deviation from C:eps", "Pa", worst, 0.0, scale, 0.005}};
  report.wall_seconds = seconds_since(start);
  return report;
}

} // namespace mpile::verification
