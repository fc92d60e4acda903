// V8 (self_weight_column.toml): a soil cylinder R = 0.5, H = 1, rollers at r = R, fixed base,
// gamma = 20 kN/m^3, E = 100 MPa, nu = 0.3, gravity switched on and damped to rest: sigma_v =
// gamma z, sigma_h / sigma_v = nu / (1 - nu), u_y = -gamma / E_oed (H y - y^2 / 2), so the top
// settles by gamma H^2 / (2 E_oed) = 7.43e-5 m.
// V8k0 (k0_column.toml): the same column with K0 = 0.5 stresses initialised and gravity on,
// undamped: the state is in equilibrium and must stay put.
// Interior particles (two cells from every boundary) are compared.
#include "cases/verification/case_file_run.hpp"
#include "cases/verification/verification_cases.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace mpile::verification {

namespace {

/// The column of either file: its size, material and cell size.
struct Column {
  double radius, height, unit_weight, young, nu, h;
  double oedometer_modulus() const { return young * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)); }
  bool interior(const Particles& p, std::size_t i) const {
    return p.r0[i] < radius - 2.0 * h && p.y0[i] > 2.0 * h && p.y0[i] < height - 2.0 * h;
  }
};

Column column_of(const CaseFileRun& run) {
  const Rectangle soil = run.spec().bodies.at(0).region.bounds();
  const double g = std::hypot(run.spec().solver.gravity[0], run.spec().solver.gravity[1]);
  return {soil.r_max,
          soil.y_max,
          run.parameter("soil", "density") * g,
          run.parameter("soil", "young_modulus"),
          run.parameter("soil", "poisson_ratio"),
          run.scene().grid.y_axis().cell_size(0)};
}

} // namespace

Report run_self_weight_column(const Options& options) {
  CaseFileRun run("self_weight_column.toml", options);
  const Column column = column_of(run);
  Report report = run.run("V8", "self-weight column, gravity loading");

  const Scene& scene = run.scene();
  const Particles& p = scene.particles;
  const double e_oed = column.oedometer_modulus();
  const double ratio = column.nu / (1.0 - column.nu);
  const double height = column.height;
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
    if (column.interior(p, i)) {
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
    if (p.y0[i] > height - 0.5 * column.h && p.r0[i] < column.radius - 2.0 * column.h) {
      settlement += p.y[i] - p.y0[i];
      exact_settlement +=
          -column.unit_weight / e_oed * (height * p.y0[i] - 0.5 * p.y0[i] * p.y0[i]);
      ++top;
    }
  }
  double max_vertical_error = 0.0;
  for (const auto& [index, cell] : cells) {
    const double exact = -column.unit_weight * cell.depth / cell.count;
    max_vertical_error = std::max(max_vertical_error,
                                  std::abs(cell.vertical / cell.count - exact) / std::abs(exact));
  }
  settlement /= top;
  exact_settlement /= top;
  report.checks = {
      {"max relative error of cell-mean sigma_v = gamma z (interior)", "-", max_vertical_error, 0.0,
       1.0, 0.01},
      {"max relative error of sigma_h / sigma_v = nu/(1-nu) (interior)", "-", max_ratio_error, 0.0,
       1.0, 0.02},
      {"max |sigma_rr - sigma_thth| / |sigma_v| (interior)", "-", max_hoop_split, 0.0, 1.0, 0.01},
      {"settlement of the top particles", "m", settlement, exact_settlement,
       std::abs(exact_settlement), 0.02},
      run.equilibrium(),
  };
  return report;
}

Report run_k0_column(const Options& options) {
  CaseFileRun run("k0_column.toml", options);
  const Column column = column_of(run);
  const double k0 = run.spec().phases[0].k0.at(0).k0;
  Report report = run.run("V8k0", "self-weight column, K0 state stays put");

  const Particles& p = run.scene().particles;
  double max_displacement = 0.0, max_stress_change = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    max_displacement = std::max(max_displacement, std::hypot(p.r[i] - p.r0[i], p.y[i] - p.y0[i]));
    // The stresses the K0 procedure set, recomputed at the particle's initial position.
    const double vertical = -column.unit_weight * (column.height - p.y0[i]);
    const Stress k0_state{k0 * vertical, vertical, k0 * vertical, 0.0, 0.0, 0.0};
    for (std::size_t c = 0; c < 6; ++c) {
      max_stress_change = std::max(max_stress_change, std::abs(p.stress[i][c] - k0_state[c]));
    }
  }
  const double settlement_i =
      column.unit_weight * column.height * column.height / (2.0 * column.oedometer_modulus());
  report.checks = {
      {"max displacement at the end / 1e-3 of (i)'s settlement", "m", max_displacement, 0.0,
       1e-3 * settlement_i, 1.0},
      {"max stress change / (gamma H)", "Pa", max_stress_change, 0.0,
       column.unit_weight * column.height, 0.01},
  };
  return report;
}

} // namespace mpile::verification
