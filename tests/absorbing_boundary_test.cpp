// Absorbing faces against the closed form of a dashpot at normal incidence: a plane wave of
// impedance Z meeting a dashpot of coefficient C per area reflects with the amplitude ratio
// R = (Z - C) / (Z + C), so it carries R^2 of its energy back. The faces take C = Z (R = 0); a
// face whose impedance is scaled by s must reflect ((1 - s) / (1 + s))^2.
#include "case_run.hpp"
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/diagnostics.hpp"
#include "solver/explicit_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

namespace mpile {
namespace {

using verification::uniform_grid;

constexpr double young = 100e6, poisson = 0.25, density = 2000.0;
constexpr double length = 12.0, width = 0.4, cell = 0.1, pulse = 2.0;
const double constrained = young * (1 - poisson) / ((1 + poisson) * (1 - 2 * poisson));
const double shear = young / (2 * (1 + poisson));

/// A smooth pulse cos^2 of width `pulse` centred at the middle of the column, 0 elsewhere.
double pulse_shape(double x) {
  const double s = (x - 0.5 * length) / pulse;
  return std::abs(s) < 0.5 ? std::pow(std::cos(std::numbers::pi * s), 2) : 0.0;
}

enum class Wave { p, s };

/// A column along y (axisymmetric: radius `width`, the wave along the axis; theta for the S wave)
/// or a strip along r (plane strain: the wave along r, v_y for the S wave) whose two ends absorb.
/// Its particles start with the pulse's velocity, which splits into two waves running to the ends.
struct Column {
  Scene scene;
  double wave_speed = 0.0;

  Column(GeometryMode mode, Wave wave)
      : scene(mode, mode == GeometryMode::axisymmetric
                        ? uniform_grid(0.0, width, 4, 0.0, length, 120)
                        : uniform_grid(0.0, length, 120, 0.0, width, 4)) {
    const bool along_y = mode == GeometryMode::axisymmetric;
    const auto material =
        scene.add_material(std::make_unique<LinearElastic>(young, poisson, density));
    const auto body = scene.add_body("column");
    fill_rectangle(
        scene, along_y ? Rectangle{0.0, width, 0.0, length} : Rectangle{0.0, length, 0.0, width}, 2,
        material, body);
    Particles& p = scene.particles;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double amplitude = pulse_shape(along_y ? p.y[i] : p.r[i]);
      if (along_y) {
        (wave == Wave::p ? p.v_y[i] : p.v_theta[i]) =
            0.01 * amplitude * (wave == Wave::p ? 1 : p.r[i]);
      } else {
        (wave == Wave::p ? p.v_r[i] : p.v_y[i]) = 0.01 * amplitude;
      }
    }
    wave_speed = std::sqrt((wave == Wave::p ? constrained : shear) / density);
    Boundaries& b = scene.boundaries;
    if (along_y) {
      // Uniaxial strain: the axis and a roller on the mantle; the mantle is free in theta.
      b.constraints = {axis_constraint(scene.grid),
                       face_constraint(scene.grid, mode, GridFace::r_max, FaceCondition::roller)};
    } else {
      // The strip's sides hold the DOF the plane wave does not move: v_y for the P wave, v_r for
      // the S wave (whose shear stress on the sides they then carry).
      for (const GridFace side : {GridFace::y_min, GridFace::y_max}) {
        NodeConstraint c;
        c.name = side == GridFace::y_min ? "bottom" : "top";
        c.nodes = nodes_on_face(scene.grid, side);
        c.dofs = wave == Wave::p ? DOF_Y : DOF_R;
        b.constraints.push_back(c);
      }
    }
    for (const GridFace end : along_y ? std::array{GridFace::y_min, GridFace::y_max}
                                      : std::array{GridFace::r_min, GridFace::r_max}) {
      AbsorbingFace face;
      face.face = end;
      face.nodes = nodes_on_face(scene.grid, end);
      b.absorbing.push_back(face);
    }
  }

  struct Outcome {
    double left = 0.0;     // share of the pulse's energy still in the column
    double residual = 0.0; // energy balance residual over the pulse's energy
  };

  /// Runs until both halves of the pulse have met the ends and their reflections are back at the
  /// middle (t = length / c), with each face's impedance scaled by `scale`.
  Outcome run(double scale, double courant = 0.8) {
    RunLog log;
    SolverSettings settings;
    settings.courant_number = courant;
    ExplicitSolver solver(scene, settings, log);
    solver.switch_on_absorbing({0, 1});
    for (AbsorbingFace& face : scene.boundaries.absorbing) {
      for (double& z : face.p_impedance) {
        z *= scale;
      }
      for (double& z : face.s_impedance) {
        z *= scale;
      }
    }
    const double start = kinetic_energy(scene);
    solver.advance_to(length / wave_speed);
    const EnergyBalance b = solver.energy_balance();
    EXPECT_EQ(b.external_work, 0.0); // no gravity, and nothing held the faces at the start
    EXPECT_GE(b.radiated, 0.0);
    return {(b.kinetic + b.elastic) / start, b.residual / start};
  }
};

double reflected_share(double scale) {
  const double r = (1.0 - scale) / (1.0 + scale);
  return r * r;
}

TEST(AbsorbingBoundary, ImpedanceIsSampledFromTheSoilBesideTheFace) {
  Column column(GeometryMode::axisymmetric, Wave::p);
  RunLog log;
  ExplicitSolver solver(column.scene, SolverSettings{}, log);
  solver.switch_on_absorbing({0, 1});
  for (const AbsorbingFace& face : column.scene.boundaries.absorbing) {
    ASSERT_EQ(face.p_impedance.size(), 4u);
    for (std::size_t j = 0; j < 4; ++j) {
      // The particles' density is the material's (nothing has moved): exact to round-off.
      EXPECT_NEAR(face.p_impedance[j], std::sqrt(density * constrained), 1e-9 * density * 250);
      EXPECT_NEAR(face.s_impedance[j], std::sqrt(density * shear), 1e-9 * density * 250);
    }
  }
}

// The P wave along the axis of an axisymmetric column (the y faces' weights, int N r dr) and the
// torsional S wave (the theta dashpot's torque, int N r^3 dr per angular velocity), and the plane
// P and S waves along r in plane strain (the r faces' weights).
TEST(AbsorbingBoundary, PlaneWavesLeaveThroughMatchedDashpots) {
  for (const auto& [mode, wave, name] :
       {std::tuple{GeometryMode::axisymmetric, Wave::p, "axisymmetric P"},
        std::tuple{GeometryMode::axisymmetric, Wave::s, "axisymmetric torsional S"},
        std::tuple{GeometryMode::plane_strain, Wave::p, "plane strain P"},
        std::tuple{GeometryMode::plane_strain, Wave::s, "plane strain S"}}) {
    const Column::Outcome outcome = Column(mode, wave).run(1.0);
    std::cout << name << ": left " << outcome.left << ", residual " << outcome.residual << '\n';
    // Zero for the continuum; the grid's dispersion of a pulse 20 cells long reflects a little
    // (measured 0.08 to 0.21 %). The target is 5 %.
    EXPECT_LT(outcome.left, 0.005) << name;
    // What left the column is what the dashpots took, up to the explicit step's residual, which
    // is first order in dt (measured 0.6 to 1.1 % at C = 0.8; 0.15 to 0.26 % at C = 0.2) and is
    // as large without dashpots (free ends: 1.2 to 2.2 %): the next test checks its order.
    EXPECT_LT(std::abs(outcome.residual), 0.015) << name;
  }
}

TEST(AbsorbingBoundary, EnergyBalanceResidualIsFirstOrderInTheTimeStep) {
  for (const Wave wave : {Wave::p, Wave::s}) {
    const double coarse = Column(GeometryMode::axisymmetric, wave).run(1.0, 0.8).residual;
    const double fine = Column(GeometryMode::axisymmetric, wave).run(1.0, 0.4).residual;
    std::cout << "residual at C = 0.8: " << coarse << ", at 0.4: " << fine << ", ratio "
              << coarse / fine << '\n';
    // Halving dt halves a first-order residual; an error in the radiated energy's accounting
    // would not shrink with dt. Measured ratios 2.1 and 2.1.
    EXPECT_NEAR(coarse / fine, 2.0, 0.3);
  }
}

TEST(AbsorbingBoundary, MismatchedDashpotsReflectTheirClosedFormShare) {
  for (const double scale : {0.5, 2.0}) {
    for (const Wave wave : {Wave::p, Wave::s}) {
      // At C = 0.4: the dashpot taken implicitly over a step has an effective impedance off by
      // O(dt C / m), an error that halves with dt (measured |left - R^2| 0.015, 0.008, 0.005 at
      // C = 0.8, 0.4, 0.2 for the stiffer dashpot). 0.01 is 9 % of R^2 = 1/9.
      const double left = Column(GeometryMode::axisymmetric, wave).run(scale, 0.4).left;
      std::cout << "impedance x " << scale << ": reflected share " << left << '\n';
      EXPECT_NEAR(left, reflected_share(scale), 0.01) << "scale " << scale;
    }
  }
}

// The shipped case file: absorbing ends switched on from the start through the case format.
TEST(AbsorbingBoundary, TheShippedColumnLetsItsPulseOut) {
  CaseRun run(read_text(source / "cases/verification/absorbing_column.toml"));
  const double start = run.solver->energy_balance().kinetic;
  // rho (R^2 / 2) v^2 L / 6 for a triangular pulse of 0.01 m/s over L = 2 m: 5.333e-3 J/rad; the
  // particles' quadrature of the triangle is exact to its kinks' share (measured 5.330e-3).
  EXPECT_NEAR(start, 2000.0 * 0.08 * 1e-4 * 2.0 / 6.0, 1e-3 * start);
  run.run([] {});
  const EnergyBalance end = run.solver->energy_balance();
  // Measured 0.38 % left (the triangle's kinks reflect more than the smooth pulse above).
  EXPECT_LT(end.kinetic + end.elastic, 0.01 * start);
  // The dashpots took it, up to the explicit step's first-order residual (measured 0.8 %).
  EXPECT_NEAR(end.radiated, start, 0.015 * start);
}

/// The largest |u_y| of a column of soil under its own weight, from its geostatic stresses, after
/// 0.1 s with its base fixed, or fixed and then switched to absorbing at the start (optionally
/// without the holding traction).
double settlement(bool absorbing, bool holding = true) {
  constexpr double height = 6.0, k0 = 0.5, gravity = 9.81;
  Scene scene(GeometryMode::axisymmetric, uniform_grid(0.0, width, 4, 0.0, height, 60));
  const auto material =
      scene.add_material(std::make_unique<LinearElastic>(young, poisson, density));
  fill_rectangle(scene, {0.0, width, 0.0, height}, 2, material, scene.add_body("column"));
  Particles& p = scene.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double vertical = -density * gravity * (height - p.y[i]);
    p.stress[i] = Stress{};
    p.stress[i][YY] = vertical;
    p.stress[i][RR] = p.stress[i][TT] = k0 * vertical;
  }
  scene.boundaries.constraints = {
      axis_constraint(scene.grid),
      face_constraint(scene.grid, scene.mode, GridFace::r_max, FaceCondition::roller),
      face_constraint(scene.grid, scene.mode, GridFace::y_min, FaceCondition::fixed)};
  AbsorbingFace base;
  base.face = GridFace::y_min;
  base.nodes = nodes_on_face(scene.grid, GridFace::y_min);
  scene.boundaries.absorbing = {base};
  SolverSettings settings;
  settings.gravity = {0.0, -gravity};
  RunLog log;
  ExplicitSolver solver(scene, settings, log);
  if (absorbing) {
    solver.switch_on_absorbing({0});
    EXPECT_EQ(scene.boundaries.constraint("y_min").dofs, 0); // the support gave way
    if (!holding) {
      for (auto& t : scene.boundaries.absorbing[0].holding_traction) {
        t = {0.0, 0.0, 0.0};
      }
    } else {
      // The base holds the column's weight, rho g H R^2 / 2 per radian, to round-off.
      const AbsorbingFace& face = scene.boundaries.absorbing[0];
      const auto weights = segment_weights(scene.grid, face, 1);
      double held_weight = 0.0;
      for (std::size_t k = 0; k < face.nodes.size(); ++k) {
        const double w =
            (k > 0 ? weights[k - 1][1] : 0.0) + (k < weights.size() ? weights[k][0] : 0.0);
        held_weight += w * face.holding_traction[k][1];
      }
      const double weight = density * gravity * height * width * width / 2.0;
      EXPECT_NEAR(held_weight, weight, 1e-9 * weight);
    }
  }
  solver.advance_to(0.1);
  double largest = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    largest = std::max(largest, std::abs(p.y[i] - p.y0[i]));
  }
  return largest;
}

TEST(AbsorbingBoundary, HoldingTractionKeepsASoilColumnAtRestUnderItsWeight) {
  const double fixed = settlement(false);
  const double held = settlement(true);
  const double unheld = settlement(true, false);
  std::cout << "largest |u_y|: fixed " << fixed << ", held " << held << ", unheld " << unheld
            << " m\n";
  // Two particles per cell represent the geostatic stress exactly, so the fixed column does not
  // move at all (measured 0); the held one must not either: its base nodes start with the force
  // that balanced them. Without the holding traction the column sinks into its dashpots (18 mm).
  EXPECT_LE(held, fixed + 1e-12);
  EXPECT_GT(unheld, 0.01);
}

} // namespace
} // namespace mpile
