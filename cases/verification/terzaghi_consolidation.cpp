// V10 (terzaghi_consolidation.toml): Terzaghi's one-dimensional consolidation, coupled soil. A
// column of height H under a load q applied at t = 0, drained at the top (z = 0, z the depth) and
// impermeable at the base. Instantly the water takes u0 = B q of it, B = (K_w / n) / (E_oed +
// K_w / n) for an oedometric skeleton and incompressible grains; then
//   u(z, t) / u0 = sum_m (2 / M) sin(M z / H) exp(-M^2 T_v),   M = pi (2 m + 1) / 2,
//   U(T_v) = 1 - sum_m (2 / M^2) exp(-M^2 T_v),   T_v = c_v t / H^2,
//   c_v = k / (gamma_w (1 / E_oed + n / K_w)),
// U being the average degree of consolidation, 1 - the depth mean of u / u0.
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/verification_cases.hpp"
#include "engine/materials/pore_water.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace mpile::verification {

namespace {

constexpr int series_terms = 2000; // the series at T_v = 0.01 converges to 1e-12 well before

double excess_ratio(double z_over_h, double time_factor) {
  double sum = 0.0;
  for (int m = 0; m < series_terms; ++m) {
    const double M = std::numbers::pi * (2 * m + 1) / 2.0;
    sum += 2.0 / M * std::sin(M * z_over_h) * std::exp(-M * M * time_factor);
  }
  return sum;
}

double degree_of_consolidation(double time_factor) {
  double sum = 0.0;
  for (int m = 0; m < series_terms; ++m) {
    const double M = std::numbers::pi * (2 * m + 1) / 2.0;
    sum += 2.0 / (M * M) * std::exp(-M * M * time_factor);
  }
  return 1.0 - sum;
}

/// The excess pore pressure (compression positive) of each particle, and their volume-weighted
/// mean.
struct PressureState {
  double time = 0.0;
  std::vector<double> excess;
  double mean = 0.0;
};

PressureState pressures(const Scene& scene, double time) {
  const Particles& p = scene.particles;
  const Material& soil = *scene.materials.at(0);
  const auto slot = static_cast<std::size_t>(soil.pore_pressure_index() + 1);
  PressureState s{time, std::vector<double>(p.size()), 0.0};
  double volume = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    s.excess[i] = -p.state[i * static_cast<std::size_t>(p.state_stride) + slot];
    s.mean += p.volume[i] * s.excess[i];
    volume += p.volume[i];
  }
  s.mean /= volume;
  return s;
}

} // namespace

Report run_terzaghi_consolidation(const Options& options) {
  CaseFileRun run("terzaghi_consolidation.toml", options);
  const Rectangle column = run.spec().bodies.at(0).region.bounds();
  const double height = column.y_max - column.y_min;
  const MaterialSpec& soil = run.spec().materials.at(0);
  const double young = run.parameter("soil", "young_modulus");
  const double nu = run.parameter("soil", "poisson_ratio");
  const double oedometer = young * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double n = porosity(run.parameter("soil", "density"), soil.water);
  const double water_stiffness = soil.water.bulk_modulus / n;
  const double c_v = soil.water.hydraulic_conductivity /
                     (soil.water.density * standard_gravity *
                      (1.0 / oedometer + n / soil.water.bulk_modulus));
  const double load = -run.spec().loads.at(0).traction.value(1.0);
  const double u0 = load * water_stiffness / (oedometer + water_stiffness);

  // Each T_v sampled by linear interpolation between the steps around it.
  const std::vector<double> factors{0.01, 0.1, 0.5, 1.0};
  std::vector<PressureState> at_factor(factors.size());
  std::vector<bool> taken(factors.size(), false);
  PressureState before = pressures(run.scene(), 0.0);
  Report report = run.run("V10", "Terzaghi consolidation", [&](const ExplicitSolver& solver) {
    PressureState now = pressures(solver.scene(), solver.time());
    for (std::size_t f = 0; f < factors.size(); ++f) {
      const double t = factors[f] * height * height / c_v;
      if (!taken[f] && now.time >= t * (1.0 - 1e-12)) {
        const double a = now.time > before.time ? (t - before.time) / (now.time - before.time) : 1.0;
        PressureState s{t, now.excess, 0.0};
        for (std::size_t i = 0; i < s.excess.size(); ++i) {
          s.excess[i] = before.excess[i] + a * (now.excess[i] - before.excess[i]);
        }
        s.mean = before.mean + a * (now.mean - before.mean);
        at_factor[f] = s;
        taken[f] = true;
      }
    }
    before = std::move(now);
  });

  const Particles& p = run.scene().particles;
  for (std::size_t f = 0; f < factors.size(); ++f) {
    std::ostringstream name;
    name << "degree of consolidation U at T_v = " << factors[f];
    const double exact = degree_of_consolidation(factors[f]);
    const double measured = taken[f] ? 1.0 - at_factor[f].mean / u0 : 0.0;
    // 2 % of the consolidation (the target): the scale is the final degree, 1.
    report.checks.push_back({name.str(), "-", measured, exact, 1.0, 0.02});
  }
  for (const double factor : {0.1, 0.5}) {
    const auto f = static_cast<std::size_t>(
        std::find(factors.begin(), factors.end(), factor) - factors.begin());
    double worst = 0.0, worst_exact = 0.0;
    for (std::size_t i = 0; taken[f] && i < p.size(); ++i) {
      const double exact = u0 * excess_ratio((column.y_max - p.y0[i]) / height, factor);
      if (std::abs(at_factor[f].excess[i] - exact) > std::abs(worst - worst_exact)) {
        worst = at_factor[f].excess[i];
        worst_exact = exact;
      }
    }
    std::ostringstream name;
    name << "isochrone at T_v = " << factor << ": the particle farthest from u(z)";
    // Within 2 % of the applied load at every particle (the target).
    report.checks.push_back({name.str(), "Pa", worst, worst_exact, load, 0.02});
  }
  return report;
}

} // namespace mpile::verification
