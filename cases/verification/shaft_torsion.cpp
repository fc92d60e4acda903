// V6: shaft torsion. R = 0.5, H = 1, G = 50 MPa (E = 100 MPa, nu = 0), base fixed, top rotated by
// phi = 1e-3 rad quasi-statically. u_theta = phi r y / H, tau_ytheta = G phi r / H and the torque
// T = G phi R^4 / (4 H) = 781.25 N m/rad. Exercises the theta DOF, gamma_ytheta and the -N/r term
// (without which gamma_rtheta of the rigid-rotation part would not vanish).
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/equilibrium.hpp"

#include <algorithm>
#include <cmath>

namespace mpile::verification {

Report run_shaft_torsion(const Options& options) {
  const auto start = std::chrono::steady_clock::now();
  constexpr double radius = 0.5, height = 1.0, young = 100e6, density = 2000, twist = 1e-3;
  const double shear_modulus = young / 2.0;
  const int n = options.refinement;
  const double h = height / (16 * n);
  Scene scene(GeometryMode::axisymmetric,
              uniform_grid(0.0, radius + h, 8 * n + 1, 0.0, height, 16 * n));
  const auto material = scene.add_material(std::make_unique<LinearElastic>(young, 0.0, density));
  const auto body = scene.add_body("shaft");
  fill_rectangle(scene, {0.0, radius, 0.0, height}, options.particles_per_direction, material,
                 body);

  constexpr double load_time = 0.02;
  NodeConstraint cap;
  cap.name = "top cap";
  cap.nodes = nodes_on_face(scene.grid, GridFace::y_max);
  cap.dofs = DOF_THETA;
  cap.theta_is_rotation = true;
  cap.velocity[2] = trapezoid_velocity(twist, load_time); // angular velocity, rad/s
  scene.boundaries.constraints = {
      axis_constraint(scene.grid),
      face_constraint(scene.grid, scene.mode, GridFace::y_min, FaceCondition::fixed), cap};

  SolverSettings settings;
  settings.local_damping = 0.7;
  settings = apply_options(settings, options);
  RunLog log;
  ExplicitSolver solver(scene, settings, log);
  solver.advance_to(load_time);
  const EquilibriumResult rest = advance_to_equilibrium(solver, equilibrium_tolerance, 2.0);

  const Particles& p = scene.particles;
  double max_tau_error = 0.0, max_rt = 0.0, max_u_error = 0.0;
  const double tau_max = shear_modulus * twist * radius / height;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double tau = shear_modulus * twist * p.r0[i] / height;
    max_tau_error = std::max(max_tau_error, std::abs(p.stress[i][YT] - tau));
    max_rt = std::max(max_rt, std::abs(p.stress[i][RT]));
    const double u = twist * p.r0[i] * p.y0[i] / height;
    max_u_error = std::max(max_u_error, std::abs(p.u_theta[i] - u));
  }
  const double torque = scene.boundaries.constraint("top cap").torque;
  const double exact_torque = shear_modulus * twist * std::pow(radius, 4) / (4.0 * height);
  Report report{"V6", "shaft torsion", {}, p.size(), solver.step_count(), 0.0, log.warnings()};
  report.checks = {
      {"torque of the cap on the shaft", "N m/rad", torque, exact_torque, exact_torque, 0.01},
      {"max |tau_ytheta - G phi r/H|", "Pa", max_tau_error, 0.0, tau_max, 0.01},
      {"max |tau_rtheta|", "Pa", max_rt, 0.0, tau_max, 0.01},
      {"max |u_theta - phi r y/H|", "m", max_u_error, 0.0, twist * radius, 0.01},
      equilibrium_check(rest),
  };
  report.wall_seconds = seconds_since(start);
  return report;
}

} // namespace mpile::verification
