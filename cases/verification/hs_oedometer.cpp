// VHS: Hardening Soil in a full MPM run against its own element test. A cylinder R = 0.5, H = 1 of
// the seed's sand (Table 5) starts from the normally consolidated K0 state sigma_v = 100 kPa,
// sigma_h = K0nc sigma_v, and is compressed oedometrically (smooth rigid base and platen, lateral
// roller) to eps_y = -0.5 %, primary loading on the cap. The state stays homogeneous, so every
// particle must follow the single-point oedometer path: the reference integrates the same model
// along eps_y alone in 20 000 equal increments (the element test's own integration, which the
// hardening-soil tests pin to the published curves). What the MPM run adds, and what the error
// measures, is the dynamics of the loading and the time step.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/hardening_soil.hpp"
#include "engine/particle_fill.hpp"
#include "solver/equilibrium.hpp"

#include <cmath>
#include <vector>

namespace mpile::verification {

HardeningSoilParameters seed_sand() {
  HardeningSoilParameters s;
  s.e50_ref = 44e6;
  s.eoed_ref = 44e6;
  s.eur_ref = 132e6;
  s.power = 0.47;
  s.poisson_ur = 0.2;
  s.k0_nc = 0.5;
  s.failure_ratio = 0.91;
  s.p_ref = 100e3;
  s.friction_angle = 37.5;
  s.dilatancy_angle = 0.0;
  s.density = 1656.25;
  return s;
}

Report run_hs_oedometer(const Options& options) {
  const auto start = std::chrono::steady_clock::now();
  constexpr double radius = 0.5, height = 1.0, strain = -5e-3, sigma_v0 = -100e3;
  const int n = options.refinement;
  Scene scene(GeometryMode::axisymmetric, uniform_grid(0.0, radius, 4 * n, 0.0, height, 8 * n));
  const auto material = scene.add_material(std::make_unique<HardeningSoil>(seed_sand()));
  const Material& sand = *scene.materials[material];
  const auto body = scene.add_body("sample");
  fill_rectangle(scene, {0.0, radius, 0.0, height}, options.particles_per_direction, material,
                 body);
  const Stress initial{0.5 * sigma_v0, sigma_v0, 0.5 * sigma_v0, 0.0, 0.0, 0.0};
  Particles& p = scene.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.stress[i] = initial;
    sand.initialise_state(initial, p.state.data() + i * static_cast<std::size_t>(p.state_stride));
  }

  // The platen moves by a trapezoidal velocity history over 25 wave transits of the sample.
  constexpr double load_time = 0.15;
  const NodeConstraint platen = top_platen(scene.grid, strain * height, load_time);
  scene.boundaries.constraints = {
      axis_constraint(scene.grid),
      face_constraint(scene.grid, scene.mode, GridFace::r_max, FaceCondition::roller),
      face_constraint(scene.grid, scene.mode, GridFace::y_min, FaceCondition::roller), platen};

  SolverSettings settings;
  settings.local_damping = 0.7;
  // Pure FLIP keeps particle velocities the grid cannot see (its null space): the plastic update
  // feeds them a little, damping at the nodes never reaches them, and the run would not come to
  // rest. A 2 % PIC share removes them.
  settings.flip_fraction = 0.98;
  settings = apply_options(settings, options);
  RunLog log;
  ExplicitSolver solver(scene, settings, log);
  solver.advance_to(load_time);
  const EquilibriumResult rest = advance_to_equilibrium(solver, equilibrium_tolerance, 2.0);

  // The single-point reference along the same oedometric path.
  Stress reference = initial;
  std::vector<double> state(sand.state_size());
  sand.initialise_state(reference, state.data());
  constexpr int increments = 20000;
  for (int k = 0; k < increments; ++k) {
    update_single_point(sand, reference, state.data(),
                        {0.0, strain / increments, 0.0, 0.0, 0.0, 0.0});
  }

  double mean_axial = 0.0, mean_lateral = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    mean_axial += p.stress[i][YY] / static_cast<double>(p.size());
    mean_lateral += 0.5 * (p.stress[i][RR] + p.stress[i][TT]) / static_cast<double>(p.size());
  }
  const double reaction = scene.boundaries.constraint("top platen").reaction[1];
  const double increment = reference[YY] - sigma_v0; // errors are relative to the change
  Report report{"VHS",
                "Hardening Soil oedometer under a platen",
                {},
                p.size(),
                solver.step_count(),
                0.0,
                log.warnings()};
  report.checks = {
      {"mean sigma_yy", "Pa", mean_axial, reference[YY], std::abs(increment), 0.01},
      {"mean lateral stress", "Pa", mean_lateral, reference[RR],
       std::abs(reference[RR] - 0.5 * sigma_v0), 0.01},
      {"platen force", "N/rad", reaction, reference[YY] * radius * radius / 2.0,
       std::abs(increment) * radius * radius / 2.0, 0.01},
      equilibrium_check(rest),
  };
  report.wall_seconds = seconds_since(start);
  return report;
}

} // namespace mpile::verification
