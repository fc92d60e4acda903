// V4: radial patch test through the axis. The whole grid moves with u_r = eps r, u_y = 0
// (eps = 1e-3), prescribed on every node over a time T. Every particle, including those in the
// first cell at the axis, must reach sigma_rr = sigma_thth = 2 (lambda + mu) eps and
// sigma_yy = 2 lambda eps. The grid is graded (two zones) so that grading is exercised too.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/explicit_solver.hpp"

#include <algorithm>
#include <cmath>

namespace mpile::verification {

Report run_radial_patch(const Options& options) {
  const auto start = std::chrono::steady_clock::now();
  constexpr double strain = 1e-3, duration = 0.01, young = 100e6, nu = 0.3, density = 2000;
  const int n = options.refinement;
  const AxisZone r_zones[] = {{0.0, 0.25, 4 * n}, {0.25, 1.0, 3 * n}};
  const AxisZone y_zones[] = {{0.0, 0.5, 2 * n}};
  Scene scene(GeometryMode::axisymmetric, Grid(GradedAxis(r_zones), GradedAxis(y_zones)));
  const auto material = scene.add_material(std::make_unique<LinearElastic>(young, nu, density));
  const auto body = scene.add_body("patch");
  fill_rectangle(scene, {0.0, 1.0, 0.0, 0.5}, options.particles_per_direction, material, body);
  scene.velocity_field = [&](double r, double, double) {
    return std::array<double, 3>{strain / duration * r, 0.0, 0.0};
  };

  SolverSettings settings = apply_options(SolverSettings{}, options);
  RunLog log;
  ExplicitSolver solver(scene, settings, log);
  solver.advance_to(duration);

  const auto& elastic = dynamic_cast<const LinearElastic&>(*scene.materials[material]);
  const double lambda = elastic.lame_lambda(), mu = elastic.shear_modulus();
  const double radial = 2.0 * (lambda + mu) * strain, axial = 2.0 * lambda * strain;
  double err_rr = 0.0, err_tt = 0.0, err_yy = 0.0, err_shear = 0.0;
  for (const Stress& s : scene.particles.stress) {
    err_rr = std::max(err_rr, std::abs(s[RR] - radial));
    err_tt = std::max(err_tt, std::abs(s[TT] - radial));
    err_yy = std::max(err_yy, std::abs(s[YY] - axial));
    err_shear = std::max({err_shear, std::abs(s[RY]), std::abs(s[YT]), std::abs(s[RT])});
  }
  Report report{"V4",
                "radial patch test through the axis",
                {},
                scene.particles.size(),
                solver.step_count(),
                0.0,
                log.warnings()};
  // Each check holds the largest deviation over all particles.
  report.checks = {
      {"max |sigma_rr - 2(lambda+mu) eps|", "Pa", radial + err_rr, radial, radial, 0.005},
      {"max |sigma_thth - 2(lambda+mu) eps|", "Pa", radial + err_tt, radial, radial, 0.005},
      {"max |sigma_yy - 2 lambda eps|", "Pa", axial + err_yy, axial, axial, 0.005},
      {"max |shear stress|", "Pa", err_shear, 0.0, radial, 0.005},
  };
  report.wall_seconds = seconds_since(start);
  return report;
}

} // namespace mpile::verification
