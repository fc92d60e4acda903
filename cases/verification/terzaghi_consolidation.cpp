// V10 (terzaghi_consolidation.toml): Terzaghi's one-dimensional consolidation, coupled soil. A
// column of height H under a load q applied at t = 0, drained at the top (z = 0, z the depth) and
// impermeable at the base. Instantly the water takes u0 = B q of it, B = (K_w / n) / (E_oed +
// K_w / n) for an oedometric skeleton and incompressible grains; then
//   u(z, t) / u0 = sum_m (2 / M) sin(M z / H) exp(-M^2 T_v),   M = pi (2 m + 1) / 2,
//   U(T_v) = 1 - sum_m (2 / M^2) exp(-M^2 T_v),   T_v = c_v t / H^2,
//   c_v = k / (gamma_w (1 / E_oed + n / K_w)),
// U being the average degree of consolidation, 1 - the depth mean of u / u0. The load rises over a
// time (the case file says why); the reference superposes the step response over the rise, and
// both are averaged over one period of the undrained column, 4 H / c_p, about each time compared.
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

/// sum_m a(M) exp(-M^2 T_v) over M = pi (2 m + 1) / 2, until the terms fall below round-off.
template <class Coefficient> double series(double time_factor, Coefficient a) {
  double sum = 0.0;
  for (int m = 0;; ++m) {
    const double M = std::numbers::pi * (2 * m + 1) / 2.0;
    const double decay = std::exp(-M * M * time_factor);
    sum += a(M) * decay;
    if (decay < 1e-17 || m > 100000) {
      return sum;
    }
  }
}

double excess_ratio(double z_over_h, double time_factor) {
  return series(time_factor, [&](double M) { return 2.0 / M * std::sin(M * z_over_h); });
}

double degree_of_consolidation(double time_factor) {
  return 1.0 - series(time_factor, [](double M) { return 2.0 / (M * M); });
}

/// The excess pore pressure (compression positive) of each particle, and their volume-weighted
/// mean.
struct PressureState {
  std::vector<double> excess;
  double mean = 0.0;
};

PressureState pressures(const Scene& scene) {
  const Particles& p = scene.particles;
  const Material& soil = *scene.materials.at(0);
  const auto slot = static_cast<std::size_t>(soil.pore_pressure_index() + 1);
  PressureState s{std::vector<double>(p.size()), 0.0};
  double volume = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    s.excess[i] = -p.state[i * static_cast<std::size_t>(p.state_stride) + slot];
    s.mean += p.volume[i] * s.excess[i];
    volume += p.volume[i];
  }
  s.mean /= volume;
  return s;
}

/// A time average of the run's pressures over [from, to], accumulated step by step (each step's
/// overlap with the window at the step's mean state).
struct WindowAverage {
  double from = 0.0, to = 0.0;
  PressureState sum;
  void add(const PressureState& a, const PressureState& b, double t0, double t1) {
    const double overlap = std::min(t1, to) - std::max(t0, from);
    if (overlap <= 0.0) {
      return;
    }
    sum.excess.resize(a.excess.size(), 0.0);
    for (std::size_t i = 0; i < a.excess.size(); ++i) {
      sum.excess[i] += 0.5 * (a.excess[i] + b.excess[i]) * overlap / (to - from);
    }
    sum.mean += 0.5 * (a.mean + b.mean) * overlap / (to - from);
  }
};

/// The closed form for the case's load history, averaged over [from, to]: the step response
/// superposed over the load's increments, f(T_v) being Terzaghi's response to a unit step.
template <class Response>
double averaged_reference(const TimeFunction& load, double rise_time, double c_v_over_h2,
                          double from, double to, Response f) {
  constexpr int samples = 64, increments = 256;
  const double final_load = load.value(to);
  double sum = 0.0;
  for (int a = 0; a < samples; ++a) {
    const double t = from + (a + 0.5) * (to - from) / samples;
    const double rise = std::min(t, rise_time);
    double value = load.value(0.0) / final_load * f(c_v_over_h2 * t);
    for (int j = 0; rise > 0.0 && j < increments; ++j) {
      const double s0 = rise * j / increments, s1 = rise * (j + 1) / increments;
      const double increment = (load.value(s1) - load.value(s0)) / final_load;
      value += increment * f(c_v_over_h2 * (t - 0.5 * (s0 + s1)));
    }
    sum += value / samples;
  }
  return sum;
}

/// When a load that rises to its value at `end` and then holds has risen (bisection).
double rise_time(const TimeFunction& load, double end) {
  const double final_load = load.value(end);
  double low = 0.0, high = end;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (low + high);
    (std::abs(load.value(mid) - final_load) <= 1e-12 * std::abs(final_load) ? high : low) = mid;
  }
  return high;
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
  const double dry_density = run.parameter("soil", "density");
  const double n = porosity(dry_density, soil.water);
  const double water_stiffness = soil.water.bulk_modulus / n;
  const double c_v =
      soil.water.hydraulic_conductivity /
      (soil.water.density * standard_gravity * (1.0 / oedometer + n / soil.water.bulk_modulus));
  const double c_v_over_h2 = c_v / (height * height);
  const TimeFunction& traction = run.spec().loads.at(0).traction;
  const double load = -traction.value(1.0);
  const double rise = rise_time(traction, run.spec().end_time());
  const double u0 = load * water_stiffness / (oedometer + water_stiffness);
  const double saturated = dry_density + n * soil.water.density;
  const double period = 4.0 * height / std::sqrt((oedometer + water_stiffness) / saturated);

  const std::vector<double> factors{0.01, 0.1, 0.5, 1.0};
  std::vector<WindowAverage> windows;
  for (const double factor : factors) {
    const double t = factor / c_v_over_h2;
    // The last window ends where the run does.
    const double end = std::min(t + 0.5 * period, run.spec().end_time());
    windows.push_back({end - period, end, {}});
  }
  PressureState before = pressures(run.scene());
  double time_before = 0.0;
  double residual = 0.0;
  Report report = run.run("V10", "Terzaghi consolidation", [&](const ExplicitSolver& solver) {
    PressureState now = pressures(solver.scene());
    for (WindowAverage& window : windows) {
      window.add(before, now, time_before, solver.time());
    }
    before = std::move(now);
    time_before = solver.time();
    residual = solver.energy_balance().relative_residual;
  });

  const Particles& p = run.scene().particles;
  for (std::size_t f = 0; f < factors.size(); ++f) {
    const WindowAverage& w = windows[f];
    std::ostringstream name;
    name << "degree of consolidation U at T_v = " << factors[f];
    const double exact =
        1.0 - averaged_reference(traction, rise, c_v_over_h2, w.from, w.to,
                                 [](double tv) { return 1.0 - degree_of_consolidation(tv); });
    // 2 % of the consolidation (the target): the scale is the final degree, 1.
    report.checks.push_back({name.str(), "-", 1.0 - w.sum.mean / u0, exact, 1.0, 0.02});
  }
  for (const std::size_t f : {std::size_t{1}, std::size_t{2}}) {
    const WindowAverage& w = windows[f];
    double worst = 0.0, worst_exact = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double z = (column.y_max - p.y0[i]) / height;
      const double exact = u0 * averaged_reference(traction, rise, c_v_over_h2, w.from, w.to,
                                                   [z](double tv) { return excess_ratio(z, tv); });
      if (std::abs(w.sum.excess[i] - exact) >= std::abs(worst - worst_exact)) {
        worst = w.sum.excess[i];
        worst_exact = exact;
      }
    }
    std::ostringstream name;
    name << "isochrone at T_v = " << factors[f] << ": the particle farthest from u(z)";
    // Within 2 % of the applied load at every particle (the target).
    report.checks.push_back({name.str(), "Pa", worst, worst_exact, load, 0.02});
  }
  // The ledger with the water's terms (drag, its kinetic and stored energy) closes: 2 % is the
  // target; what a consistent explicit step leaves is O(dt) of the energy in play.
  report.checks.push_back({"energy residual at the end", "-", residual, 0.0, 1.0, 0.02});
  return report;
}

} // namespace mpile::verification
