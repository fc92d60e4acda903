// V5: solid cylinder R = 0.5, H = 1 between smooth rigid platens, E = 100 MPa, nu = 0.3, axial
// strain -1e-3 applied quasi-statically by the top platen. The state is homogeneous:
// sigma_yy = E eps_y = -100 kPa, sigma_rr = sigma_thth = 0, u_r = -nu eps_y r (1.5e-4 m at R), and
// the platen force is sigma_yy R^2 / 2 = -12.5 kN/rad.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/equilibrium.hpp"

#include <algorithm>
#include <cmath>

namespace mpile::verification {

Report run_uniaxial_cylinder(const Options& options) {
  const auto start = std::chrono::steady_clock::now();
  constexpr double radius = 0.5, height = 1.0, young = 100e6, density = 2000, strain = -1e-3;
  const double nu = options.poisson_ratio.value_or(0.3);
  const int n = options.refinement;
  const double h = height / (16 * n);
  // 8 cells across the radius, 16 over the height, one spare column outside for the bulging.
  Scene scene(GeometryMode::axisymmetric,
              uniform_grid(0.0, radius + h, 8 * n + 1, 0.0, height, 16 * n));
  const auto material = scene.add_material(std::make_unique<LinearElastic>(young, nu, density));
  const auto body = scene.add_body("cylinder");
  fill_rectangle(scene, {0.0, radius, 0.0, height}, options.particles_per_direction, material,
                 body);

  // Top platen: a trapezoidal velocity history whose integral is exactly the platen travel.
  constexpr double load_time = 0.02;
  const NodeConstraint platen = top_platen(scene.grid, strain * height, load_time);
  scene.boundaries.constraints = {
      axis_constraint(scene.grid),
      face_constraint(scene.grid, scene.mode, GridFace::y_min, FaceCondition::roller), platen};

  SolverSettings settings;
  settings.local_damping = 0.7;
  settings = apply_options(settings, options);
  RunLog log;
  ExplicitSolver solver(scene, settings, log);
  solver.advance_to(load_time);
  const EquilibriumResult rest = advance_to_equilibrium(solver, equilibrium_tolerance, 2.0);

  const Particles& p = scene.particles;
  double max_radial_strain_error = 0.0, mean_axial = 0.0, max_lateral = 0.0;
  double u_outer = 0.0;
  int outer = 0;
  const double exact_ratio = -nu * strain; // u_r / r
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double ratio = (p.r[i] - p.r0[i]) / p.r0[i];
    max_radial_strain_error = std::max(max_radial_strain_error, std::abs(ratio - exact_ratio));
    mean_axial += p.stress[i][YY] / static_cast<double>(p.size());
    max_lateral = std::max({max_lateral, std::abs(p.stress[i][RR]), std::abs(p.stress[i][TT])});
    if (p.r0[i] > radius - 0.5 * h) { // outermost particle column
      u_outer += ratio * radius;
      ++outer;
    }
  }
  u_outer /= outer;
  const double reaction = scene.boundaries.constraint("top platen").reaction[1];
  const double sigma = young * strain;
  Report report{"V5",
                "solid cylinder in uniaxial compression",
                {},
                p.size(),
                solver.step_count(),
                0.0,
                log.warnings()};
  report.checks = {
      {"u_r(R) from the outer particles", "m", u_outer, exact_ratio * radius, exact_ratio * radius,
       0.01},
      {"max |u_r/r + nu eps_y| over all particles", "-", max_radial_strain_error, 0.0, exact_ratio,
       0.01},
      {"platen force", "N/rad", reaction, sigma * radius * radius / 2.0,
       std::abs(sigma) * radius * radius / 2.0, 0.01},
      {"mean sigma_yy", "Pa", mean_axial, sigma, std::abs(sigma), 0.01},
      {"max |sigma_rr|, |sigma_thth|", "Pa", max_lateral, 0.0, std::abs(sigma), 0.01},
      equilibrium_check(rest),
  };
  report.wall_seconds = seconds_since(start);
  return report;
}

} // namespace mpile::verification
