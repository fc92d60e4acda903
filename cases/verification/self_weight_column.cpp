// V8: self-weight column. Soil cylinder R = 0.5, H = 1, rollers at r = R, fixed base,
// gamma = 20 kN/m^3, E = 100 MPa, nu = 0.3.
// (i) gravity switched on, damped to rest: sigma_v = gamma z, sigma_h / sigma_v = nu / (1 - nu),
//     u_y = -gamma / E_oed (H y - y^2 / 2), so the top settles by gamma H^2 / (2 E_oed) = 7.43e-5
//     m.
// (ii) K0 = 0.5 stresses initialised, gravity on: the state is in equilibrium and must stay put.
// Interior particles (two cells from every boundary) are compared.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/equilibrium.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace mpile::verification {

namespace {

constexpr double radius = 0.5, height = 1.0, unit_weight = 20e3, young = 100e6, nu = 0.3;
constexpr double gravity = 9.81;

struct Column {
  Scene scene;
  std::uint16_t body;
  double h;
};

Column make_column(const Options& options) {
  const int n = options.refinement;
  const double h = height / (16 * n);
  // One spare row above the surface; rollers at r = R keep the particles inside radially.
  Column column{Scene(GeometryMode::axisymmetric,
                      uniform_grid(0.0, radius, 8 * n, 0.0, height + h, 16 * n + 1)),
                0, h};
  Scene& scene = column.scene;
  const auto material =
      scene.add_material(std::make_unique<LinearElastic>(young, nu, unit_weight / gravity));
  column.body = scene.add_body("column");
  fill_rectangle(scene, {0.0, radius, 0.0, height}, options.particles_per_direction, material,
                 column.body);
  scene.boundaries.constraints = {
      axis_constraint(scene.grid),
      face_constraint(scene.grid, scene.mode, GridFace::r_max, FaceCondition::roller),
      face_constraint(scene.grid, scene.mode, GridFace::y_min, FaceCondition::fixed)};
  return column;
}

bool interior(const Particles& p, std::size_t i, double h) {
  return p.r0[i] < radius - 2.0 * h && p.y0[i] > 2.0 * h && p.y0[i] < height - 2.0 * h;
}

double oedometer_modulus() {
  return young * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

} // namespace

Report run_self_weight_column(const Options& options) {
  const auto start = std::chrono::steady_clock::now();
  Column column = make_column(options);
  Scene& scene = column.scene;
  SolverSettings settings;
  settings.local_damping = 0.75;
  settings.gravity = {0.0, -gravity};
  settings = apply_options(settings, options);
  RunLog log;
  ExplicitSolver solver(scene, settings, log);
  const EquilibriumResult rest = advance_to_equilibrium(solver, equilibrium_tolerance, 4.0);

  const Particles& p = scene.particles;
  const double e_oed = oedometer_modulus();
  const double ratio = nu / (1.0 - nu);
  // Bilinear cells carry a constant vertical strain, so the stress is compared as the mean of each
  // cell's particles against the closed form at the cell centre (the particles themselves sit
  // h/4 above and below it and differ from gamma z by gamma h / 4 by construction).
  struct CellSum {
    double vertical = 0.0, depth = 0.0;
    int count = 0;
  };
  std::map<std::pair<int, int>, CellSum> cells;
  double max_ratio_error = 0.0, max_hoop_split = 0.0;
  double settlement = 0.0, exact_settlement = 0.0;
  int top = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (interior(p, i, column.h)) {
      CellSum& cell =
          cells[{scene.grid.r_axis().locate(p.r0[i]), scene.grid.y_axis().locate(p.y0[i])}];
      cell.vertical += p.stress[i][YY];
      cell.depth += height - p.y0[i];
      ++cell.count;
      max_ratio_error =
          std::max(max_ratio_error, std::abs(p.stress[i][RR] / p.stress[i][YY] - ratio) / ratio);
      max_hoop_split = std::max(max_hoop_split, std::abs(p.stress[i][RR] - p.stress[i][TT]) /
                                                    std::abs(p.stress[i][YY]));
    }
    if (p.y0[i] > height - 0.5 * column.h && p.r0[i] < radius - 2.0 * column.h) {
      settlement += p.y[i] - p.y0[i];
      exact_settlement += -unit_weight / e_oed * (height * p.y0[i] - 0.5 * p.y0[i] * p.y0[i]);
      ++top;
    }
  }
  double max_vertical_error = 0.0;
  for (const auto& [index, cell] : cells) {
    const double exact = -unit_weight * cell.depth / cell.count;
    max_vertical_error = std::max(max_vertical_error,
                                  std::abs(cell.vertical / cell.count - exact) / std::abs(exact));
  }
  settlement /= top;
  exact_settlement /= top;
  Report report{
      "V8",          "self-weight column, gravity loading", {}, p.size(), solver.step_count(), 0.0,
      log.warnings()};
  report.checks = {
      {"max relative error of cell-mean sigma_v = gamma z (interior)", "-", max_vertical_error, 0.0,
       1.0, 0.01},
      {"max relative error of sigma_h / sigma_v = nu/(1-nu) (interior)", "-", max_ratio_error, 0.0,
       1.0, 0.02},
      {"max |sigma_rr - sigma_thth| / |sigma_v| (interior)", "-", max_hoop_split, 0.0, 1.0, 0.01},
      {"settlement of the top particles", "m", settlement, exact_settlement,
       std::abs(exact_settlement), 0.02},
      equilibrium_check(rest),
  };
  report.wall_seconds = seconds_since(start);
  return report;
}

Report run_k0_column(const Options& options) {
  const auto start = std::chrono::steady_clock::now();
  constexpr double k0 = 0.5;
  Column column = make_column(options);
  Scene& scene = column.scene;
  initialise_geostatic_stress(scene, column.body, height, unit_weight, k0);
  SolverSettings settings;
  settings.gravity = {0.0, -gravity}; // undamped: any imbalance would show as motion
  settings = apply_options(settings, options);
  RunLog log;
  ExplicitSolver solver(scene, settings, log);
  for (int s = 0; s < 100; ++s) {
    solver.step();
  }
  const Particles& p = scene.particles;
  double max_displacement = 0.0, max_stress_change = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    max_displacement = std::max(max_displacement, std::hypot(p.r[i] - p.r0[i], p.y[i] - p.y0[i]));
    // The stresses the K0 procedure set, recomputed at the particle's initial position.
    const double vertical = -unit_weight * (height - p.y0[i]);
    const Stress k0_state{k0 * vertical, vertical, k0 * vertical, 0.0, 0.0, 0.0};
    for (int c = 0; c < 6; ++c) {
      max_stress_change =
          std::max(max_stress_change, std::abs(p.stress[i][static_cast<std::size_t>(c)] -
                                               k0_state[static_cast<std::size_t>(c)]));
    }
  }
  const double settlement_i = unit_weight * height * height / (2.0 * oedometer_modulus());
  Report report{"V8k0",
                "self-weight column, K0 state stays put",
                {},
                p.size(),
                solver.step_count(),
                0.0,
                log.warnings()};
  report.checks = {
      {"max displacement after 100 steps / 1e-3 of (i)'s settlement", "m", max_displacement, 0.0,
       1e-3 * settlement_i, 1.0},
      {"max stress change / (gamma H)", "Pa", max_stress_change, 0.0, unit_weight * height, 0.01},
  };
  report.wall_seconds = seconds_since(start);
  return report;
}

} // namespace mpile::verification
