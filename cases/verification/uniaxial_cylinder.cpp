// V5 (uniaxial_cylinder.toml): solid cylinder R = 0.5, H = 1 between smooth rigid platens, E = 100
// MPa, nu = 0.3, axial strain -1e-3 applied quasi-statically by the top platen. The state is
// homogeneous: sigma_yy = E eps_y = -100 kPa, sigma_rr = sigma_thth = 0, u_r = -nu eps_y r (1.5e-4
// m at R), and the platen force is sigma_yy R^2 / 2 = -12.5 kN/rad.
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/verification_cases.hpp"

#include <algorithm>
#include <cmath>

namespace mpile::verification {

Report run_uniaxial_cylinder(const Options& options) {
  CaseFileRun run("uniaxial_cylinder.toml", options, PoissonRatio::the_options);
  const Rectangle cylinder = run.spec().bodies.at(0).region.bounds();
  const double radius = cylinder.r_max, height = cylinder.y_max;
  const double young = run.parameter("elastic", "young_modulus");
  const double nu = run.parameter("elastic", "poisson_ratio");
  const double travel = travel_of(*run.spec().motions.at(0).velocity[1], run.spec());
  const double strain = travel / height;

  Report report = run.run("V5", "solid cylinder in uniaxial compression");

  const Particles& p = run.scene().particles;
  const double h = run.scene().grid.y_axis().cell_size(0); // the cells are square
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
  const double reaction = run.scene().boundaries.constraint("top platen").reaction[1];
  const double sigma = young * strain;
  report.checks = {
      {"u_r(R) from the outer particles", "m", u_outer, exact_ratio * radius, exact_ratio * radius,
       0.01},
      {"max |u_r/r + nu eps_y| over all particles", "-", max_radial_strain_error, 0.0, exact_ratio,
       0.01},
      {"platen force", "N/rad", reaction, sigma * radius * radius / 2.0,
       std::abs(sigma) * radius * radius / 2.0, 0.01},
      {"mean sigma_yy", "Pa", mean_axial, sigma, std::abs(sigma), 0.01},
      {"max |sigma_rr|, |sigma_thth|", "Pa", max_lateral, 0.0, std::abs(sigma), 0.01},
      run.equilibrium(),
  };
  return report;
}

} // namespace mpile::verification
