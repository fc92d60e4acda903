// V1 (vibrating_bar.toml): axial vibrating bar (Sulsky et al. 1995; Bardenhagen 2002) in
// axisymmetric mode with nu = 0, so the motion is exactly one-dimensional. Exact: v = v0 sin(beta
// y) cos(omega t) with beta = pi / 2L, mass-weighted mean velocity (2 v0 / pi) cos(omega t),
// period 4 L / c, energy rho A L v0^2 / 4 (0.03125 J/rad for the file's bar), conserved.
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/verification_cases.hpp"
#include "solver/diagnostics.hpp"

#include <cmath>
#include <numbers>

namespace mpile::verification {

Report run_vibrating_bar(const Options& options) {
  CaseFileRun run("vibrating_bar.toml", options);
  const Rectangle bar = run.spec().bodies.at(0).region.bounds();
  const double radius = bar.r_max, length = bar.y_max;
  const double young = run.parameter("bar", "young_modulus");
  const double density = run.parameter("bar", "density");
  const double period = 4.0 * length / std::sqrt(young / density);
  const Scene& scene = run.scene();
  // v0 from the file's velocity profile v0 sin(beta y), at the particle nearest the free end.
  std::size_t top = 0;
  for (std::size_t i = 0; i < scene.particles.size(); ++i) {
    top = scene.particles.y[i] > scene.particles.y[top] ? i : top;
  }
  const double v0 = scene.particles.v_y[top] /
                    std::sin(std::numbers::pi / (2.0 * length) * scene.particles.y[top]);

  const double energy0 = kinetic_energy(scene) + elastic_energy(scene);
  OscillationMeter meter(0.0, mean_velocity(scene)[1]);
  Report report = run.run("V1", "axial vibrating bar (axisymmetric)", [&](const ExplicitSolver& s) {
    meter.sample(s.time(), mean_velocity(s.scene())[1]);
  });
  const double energy = kinetic_energy(scene) + elastic_energy(scene);
  const double cycles = run.spec().phases[0].duration / period;

  const double exact_energy = density * 0.5 * radius * radius * length * v0 * v0 / 4.0;
  const double amplitude = 2.0 * v0 / std::numbers::pi;
  report.checks = {
      {"period", "s", meter.period(), period, period, 0.01},
      {"centre-of-mass velocity amplitude", "m/s", meter.amplitude(), amplitude, amplitude, 0.02},
      {"initial energy", "J/rad", energy0, exact_energy, exact_energy, 0.01},
      {"energy drift per period", "J/rad", (energy - energy0) / cycles, 0.0, energy0, 0.01},
  };
  return report;
}

} // namespace mpile::verification
