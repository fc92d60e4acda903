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

const std::vector<Case>& all_cases() {
  static const std::vector<Case> cases = {
      {"V1", "axial vibrating bar (axisymmetric)", run_vibrating_bar},
      {"V2", "single material point vibration", run_single_point},
      {"V3", "Lame thick cylinder under internal pressure", run_lame_cylinder},
      {"V4", "radial patch test through the axis", run_radial_patch},
      {"V4p", "plane-strain patch test", run_plane_strain_patch},
      {"V5", "solid cylinder in uniaxial compression", run_uniaxial_cylinder},
      {"V6", "shaft torsion", run_shaft_torsion},
      {"V8", "self-weight column, gravity loading", run_self_weight_column},
      {"V8k0", "self-weight column, K0 state stays put", run_k0_column},
      {"VHS", "Hardening Soil oedometer under a platen", run_hs_oedometer},
  };
  return cases;
}

const Case* find_case(const std::string& id) {
  for (const Case& c : all_cases()) {
    if (c.id == id) {
      return &c;
    }
  }
  return nullptr;
}

Grid uniform_grid(double r0, double r1, int nr, double y0, double y1, int ny) {
  return Grid(GradedAxis::uniform(r0, r1, nr), GradedAxis::uniform(y0, y1, ny));
}

SolverSettings apply_options(SolverSettings settings, const Options& options) {
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

Check equilibrium_check(const EquilibriumResult& result) {
  // The larger of the two ratios of the equilibrium test; the force ratio is NaN (a failed check)
  // when the kinetic energy never passed.
  return {"out-of-balance force and kinetic/work ratios, the larger (equilibrium)",
          "-",
          std::max(result.measure.force_ratio, result.measure.kinetic_ratio),
          0.0,
          1.0,
          equilibrium_tolerance};
}

TimeFunction trapezoid_velocity(double travel, double duration) {
  const double peak = travel / (0.75 * duration);
  return TimeFunction::table(
      {{0.0, 0.0}, {0.25 * duration, peak}, {0.75 * duration, peak}, {duration, 0.0}});
}

NodeConstraint top_platen(const Grid& grid, double travel, double duration) {
  NodeConstraint platen;
  platen.name = "top platen";
  platen.nodes = nodes_on_face(grid, GridFace::y_max);
  platen.dofs = DOF_Y;
  platen.velocity[1] = trapezoid_velocity(travel, duration);
  return platen;
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
