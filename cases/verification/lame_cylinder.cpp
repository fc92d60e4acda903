// V3 (lame_cylinder.toml): Lame thick cylinder, a = 0.2, b = 0.6, internal pressure p = 100 kPa,
// E = 100 MPa, nu = 0.3, a slab of height 0.1 between rollers (eps_y = 0). sigma_r = A - B/r^2,
// sigma_th = A + B/r^2 with A = p a^2 / (b^2 - a^2), B = p a^2 b^2 / (b^2 - a^2); u_r = (1 +
// nu)/E [(1 - 2 nu) A r + B / r]. Loaded quasi-statically (a pressure ramp, then relaxed with
// local damping to equilibrium).
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/verification_cases.hpp"

#include <algorithm>
#include <cmath>

namespace mpile::verification {

Report run_lame_cylinder(const Options& options) {
  CaseFileRun run("lame_cylinder.toml", options, PoissonRatio::the_options);
  const Rectangle wall = run.spec().bodies.at(0).region.bounds();
  const double a = wall.r_min, b = wall.r_max;
  // The pressure the ramp has reached at the phase's end.
  const double pressure = run.spec().loads.at(0).traction.value(run.spec().phases.at(0).duration);
  const double young = run.parameter("elastic", "young_modulus");
  const double nu = run.parameter("elastic", "poisson_ratio");
  const double A = pressure * a * a / (b * b - a * a);
  const double B = pressure * a * a * b * b / (b * b - a * a);
  auto exact_u = [&](double r) { return (1.0 + nu) / young * ((1.0 - 2.0 * nu) * A * r + B / r); };
  auto exact_hoop = [&](double r) { return A + B / (r * r); };

  Report report = run.run("V3", "Lame thick cylinder under internal pressure");

  const Particles& p = run.scene().particles;
  std::vector<double> r0, inverse_r0, u, ones, inverse_r2, hoop;
  double max_hoop_error = 0.0, mean_axial = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    r0.push_back(p.r0[i]);
    inverse_r0.push_back(1.0 / p.r0[i]);
    u.push_back(p.r[i] - p.r0[i]);
    ones.push_back(1.0);
    inverse_r2.push_back(1.0 / (p.r0[i] * p.r0[i]));
    hoop.push_back(p.stress[i][TT]);
    if (p.r0[i] >= 0.3 && p.r0[i] <= 0.5) {
      max_hoop_error = std::max(max_hoop_error, std::abs(p.stress[i][TT] - exact_hoop(p.r0[i])) /
                                                    exact_hoop(p.r0[i]));
    }
    mean_axial += p.stress[i][YY] / static_cast<double>(p.size());
  }
  // Fits of the closed form's shape through all particles give values at the faces.
  const auto u_fit = fit_two_functions(r0, inverse_r0, u);
  const auto hoop_fit = fit_two_functions(ones, inverse_r2, hoop);
  const double u_a = exact_u(a), u_b = exact_u(b), hoop_a = exact_hoop(a);
  report.checks = {
      {"u_r(a) (fit)", "m", u_fit[0] * a + u_fit[1] / a, u_a, u_a, 0.02},
      {"u_r(b) (fit)", "m", u_fit[0] * b + u_fit[1] / b, u_b, u_b, 0.02},
      {"sigma_thth(a) (fit)", "Pa", hoop_fit[0] + hoop_fit[1] / (a * a), hoop_a, hoop_a, 0.02},
      {"max sigma_thth error, 0.3 <= r <= 0.5", "-", max_hoop_error, 0.0, 1.0, 0.02},
      {"mean sigma_yy (2 nu A)", "Pa", mean_axial, 2.0 * nu * A, 2.0 * nu * A, 0.02},
      run.equilibrium(),
  };
  return report;
}

} // namespace mpile::verification
