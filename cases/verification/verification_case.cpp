#include "cases/verification/verification_case.hpp"

#include <algorithm>
#include <cmath>

namespace mpile::verification {

double Check::error() const {
  return std::abs(measured - reference) / scale;
}

bool Report::passed() const {
  for (const Check& c : checks) {
    if (!c.passed()) {
      return false;
    }
  }
  return !checks.empty();
}

Grid uniform_grid(double r0, double r1, int nr, double y0, double y1, int ny) {
  return Grid(GradedAxis::uniform(r0, r1, nr), GradedAxis::uniform(y0, y1, ny));
}

SolverSettings apply_options(SolverSettings settings, const Options& options) {
  settings.implicit_pore_pressure =
      settings.implicit_pore_pressure || options.implicit_pore_pressure;
  if (options.bbar) {
    settings.bbar = *options.bbar;
  }
  if (options.flip_fraction) {
    settings.flip_fraction = *options.flip_fraction;
  }
  if (options.xpic_order) {
    // XPIC replaces the case's FLIP/PIC blend.
    settings.xpic_order = *options.xpic_order;
    settings.flip_fraction = options.flip_fraction.value_or(1.0);
  }
  if (options.courant_number) {
    settings.courant_number = *options.courant_number;
  }
  if (options.musl) {
    settings.musl = *options.musl;
  }
  if (options.shape_functions) {
    settings.shape_functions = *options.shape_functions;
  }
  if (options.mass_scaling) {
    settings.mass_scaling = *options.mass_scaling;
  }
  settings.block_cells = options.block_cells;
  return settings;
}

} // namespace mpile::verification

namespace mpile::verification {

std::array<double, 2> fit_two_functions(const std::vector<double>& f1,
                                        const std::vector<double>& f2,
                                        const std::vector<double>& y) {
  double a11 = 0.0, a12 = 0.0, a22 = 0.0, b1 = 0.0, b2 = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    a11 += f1[i] * f1[i];
    a12 += f1[i] * f2[i];
    a22 += f2[i] * f2[i];
    b1 += f1[i] * y[i];
    b2 += f2[i] * y[i];
  }
  const double det = a11 * a22 - a12 * a12;
  return {(a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det};
}

void OscillationMeter::sample(double t, double v) {
  amplitude_ = std::max(amplitude_, std::abs(v));
  if ((v > 0.0) != (previous_v_ > 0.0)) {
    crossings_.push_back(previous_t_ + (t - previous_t_) * previous_v_ / (previous_v_ - v));
  }
  previous_t_ = t;
  previous_v_ = v;
}

double OscillationMeter::period() const {
  return crossings_.size() >= 2 ? 2.0 * (crossings_.back() - crossings_.front()) /
                                      static_cast<double>(crossings_.size() - 1)
                                : 0.0;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace mpile::verification
