// V6c (elastic_couette.toml): elastic Couette flow. An annulus a <= r <= b between rollers, its
// inner face turned by phi and its outer face held, relaxed to rest. Torsional equilibrium,
// d(r^2 tau_rtheta)/dr = 0, gives omega = A + B/r^2 with A + B/a^2 = phi and A + B/b^2 = 0, so
// u_theta = r omega, tau_rtheta = G r d(omega)/dr = -2 G B/r^2 and the torque of the inner face
// per radian T = 2 G B H, the same on every cylinder r = const. Exercises gamma_rtheta =
// r d(omega)/dr in a field that varies across the cells (V6 has omega uniform in r), which the
// theta gradient in s = 1/r^2 makes exact (docs/design.md, "Angular momentum on the grid").
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/verification_cases.hpp"

#include <algorithm>
#include <cmath>

namespace mpile::verification {

Report run_elastic_couette(const Options& options) {
  CaseFileRun run("elastic_couette.toml", options);
  const Rectangle annulus = run.spec().bodies.at(0).region.bounds();
  const double a = annulus.r_min, b = annulus.r_max;
  const double height = annulus.y_max - annulus.y_min;
  const double shear_modulus = run.parameter("elastic", "young_modulus") /
                               (2.0 * (1.0 + run.parameter("elastic", "poisson_ratio")));
  const double twist = travel_of(*run.spec().motions.at(0).velocity[2], run.spec());
  const double B = twist / (1.0 / (a * a) - 1.0 / (b * b));
  const double A = -B / (b * b);

  Report report = run.run("V6c", "elastic Couette flow");

  const Particles& p = run.scene().particles;
  double max_tau_error = 0.0, max_yt = 0.0, max_u_error = 0.0;
  const double tau_max = 2.0 * shear_modulus * B / (a * a);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.r0[i];
    // Relative to the local value: tau falls ninefold from a to b, and the error of a gradient
    // taken in r grew towards a (docs/verification.md, V6c).
    const double tau = -2.0 * shear_modulus * B / (r * r);
    max_tau_error = std::max(max_tau_error, std::abs((p.stress[i][RT] - tau) / tau));
    max_yt = std::max(max_yt, std::abs(p.stress[i][YT]));
    max_u_error = std::max(max_u_error, std::abs(p.u_theta[i] - r * (A + B / (r * r))));
  }
  const double torque = run.scene().boundaries.constraint("inner face").torque;
  const double exact_torque = 2.0 * shear_modulus * B * height;
  report.checks = {
      {"torque of the inner face on the annulus", "N m/rad", torque, exact_torque, exact_torque,
       0.001},
      {"max |tau_rtheta / (-2 G B/r^2) - 1|", "-", max_tau_error, 0.0, 1.0, 0.01},
      {"max |tau_ytheta|", "Pa", max_yt, 0.0, tau_max, 0.01},
      {"max |u_theta - r (A + B/r^2)|", "m", max_u_error, 0.0, twist * a, 0.01},
      run.equilibrium(),
  };
  return report;
}

} // namespace mpile::verification
