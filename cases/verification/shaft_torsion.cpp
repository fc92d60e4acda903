// V6 (shaft_torsion.toml): shaft torsion. R = 0.5, H = 1, G = 50 MPa (E = 100 MPa, nu = 0), base
// fixed, top rotated by phi = 1e-3 rad quasi-statically. u_theta = phi r y / H, tau_ytheta = G phi
// r / H and the torque T = G phi R^4 / (4 H) = 781.25 N m/rad. Exercises the theta DOF,
// gamma_ytheta and the -N/r term (without which gamma_rtheta of the rigid-rotation part would not
// vanish).
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/verification_cases.hpp"

#include <algorithm>
#include <cmath>

namespace mpile::verification {

Report run_shaft_torsion(const Options& options) {
  CaseFileRun run("shaft_torsion.toml", options);
  const Rectangle shaft = run.spec().bodies.at(0).region.bounds();
  const double radius = shaft.r_max, height = shaft.y_max;
  const double shear_modulus = run.parameter("elastic", "young_modulus") /
                               (2.0 * (1.0 + run.parameter("elastic", "poisson_ratio")));
  const double twist = travel_of(*run.spec().motions.at(0).velocity[2], run.spec());

  Report report = run.run("V6", "shaft torsion");

  const Particles& p = run.scene().particles;
  double max_tau_error = 0.0, max_rt = 0.0, max_u_error = 0.0;
  const double tau_max = shear_modulus * twist * radius / height;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double tau = shear_modulus * twist * p.r0[i] / height;
    max_tau_error = std::max(max_tau_error, std::abs(p.stress[i][YT] - tau));
    max_rt = std::max(max_rt, std::abs(p.stress[i][RT]));
    const double u = twist * p.r0[i] * p.y0[i] / height;
    max_u_error = std::max(max_u_error, std::abs(p.u_theta[i] - u));
  }
  const double torque = run.scene().boundaries.constraint("top cap").torque;
  const double exact_torque = shear_modulus * twist * std::pow(radius, 4) / (4.0 * height);
  report.checks = {
      {"torque of the cap on the shaft", "N m/rad", torque, exact_torque, exact_torque, 0.01},
      {"max |tau_ytheta - G phi r/H|", "Pa", max_tau_error, 0.0, tau_max, 0.01},
      {"max |tau_rtheta|", "Pa", max_rt, 0.0, tau_max, 0.01},
      {"max |u_theta - phi r y/H|", "m", max_u_error, 0.0, twist * radius, 0.01},
      run.equilibrium(),
  };
  return report;
}

} // namespace mpile::verification
