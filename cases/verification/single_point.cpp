// V2 (single_point.toml): a single material point in one cell of length L = 1, plane strain with nu
// = 0 and rollers top and bottom, so the motion is one-dimensional. Node line x = 0 fixed; E = 4
// pi^2, rho = 1, v0 = 0.1. The free node carries m/2 and feels -E u; the point takes half the
// node's acceleration, and MUSL maps v_node = v_p, so u'' = -(E / rho L^2) u: v_p = v0 cos(omega
// t) with omega = sqrt(E / rho) / L, a period of 1 s for the file's spring.
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/verification_cases.hpp"

#include <cmath>
#include <numbers>

namespace mpile::verification {

Report run_single_point(const Options& options) {
  // One point in one cell is the case: a refinement or more particles would make it another.
  Options single = options;
  single.refinement = 1;
  single.particles_per_direction.reset();
  CaseFileRun run("single_point.toml", single);
  // L = 1 (the file's single cell).
  const double omega =
      std::sqrt(run.parameter("spring", "young_modulus") / run.parameter("spring", "density"));
  const double period = 2.0 * std::numbers::pi / omega;
  const double v0 = run.scene().particles.v_r.at(0);
  OscillationMeter meter(0.0, v0);
  Report report = run.run("V2", "single material point vibration", [&](const ExplicitSolver& s) {
    meter.sample(s.time(), s.scene().particles.v_r[0]);
  });
  report.checks = {
      {"period", "s", meter.period(), period, period, 0.005},
      {"velocity amplitude", "m/s", meter.amplitude(), v0, v0, 0.005},
  };
  return report;
}

} // namespace mpile::verification
