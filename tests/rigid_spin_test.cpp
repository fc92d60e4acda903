// A rigid spin about the axis must be exact on the grid (docs/design.md, "Angular momentum on the
// grid"): particle-to-grid carries angular momentum sum N m r v_theta and rotational inertia
// sum N m r^2, so a body turning at Omega gives every node the angular velocity Omega, and
// gamma_rtheta = r d(omega)/dr vanishes. Checked against closed forms: free-spinning bodies stay
// stress free and keep their angular momentum; a shaft vibrating in its first torsional mode keeps
// every cross-section rigid (tau_rtheta = 0) at the period 4 H / c_s.
#include "cases/verification/verification_case.hpp"
#include "engine/materials/linear_elastic.hpp"
#include "engine/particle_fill.hpp"
#include "solver/explicit_solver.hpp"
#include "tests/bitwise.hpp"
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

namespace mpile {
namespace {

using verification::OscillationMeter;
using verification::uniform_grid;

constexpr double disc_young = 100e6, disc_poisson = 0.3, disc_density = 2000.0;
constexpr double shear_modulus = disc_young / (2.0 * (1.0 + disc_poisson));

double angular_momentum(const Particles& p) {
  double sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    sum += p.mass[i] * p.r[i] * p.v_theta[i];
  }
  return sum;
}

double largest_stress(const Particles& p) {
  double largest = 0.0;
  for (const Stress& s : p.stress) {
    for (const double component : s) {
      largest = std::max(largest, std::abs(component));
    }
  }
  return largest;
}

struct FreeSpin {
  double largest_stress_ratio =
      0.0;                       // max |sigma| over particles, components and steps / (G Omega dt)
  double momentum_drift = 0.0;   // max |L - L0| / L0 over the steps
  double first_step_ratio = 0.0; // max |sigma| / (G Omega dt) after the first step
};

/// An elastic body in `region`, turning at Omega about the axis with no support, load or gravity,
/// stepped 300 times (FLIP, C = 0.8).
FreeSpin spin_freely(Grid grid, const Rectangle& region) {
  constexpr double spin = 2.0; // rad/s
  Scene scene(GeometryMode::axisymmetric, std::move(grid));
  const auto material =
      scene.add_material(std::make_unique<LinearElastic>(disc_young, disc_poisson, disc_density));
  fill_rectangle(scene, region, 2, material, scene.add_body("spinner"));
  Particles& p = scene.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.v_theta[i] = spin * p.r[i];
  }
  RunLog log;
  ExplicitSolver solver(scene, SolverSettings{}, log);
  const double stress_scale = shear_modulus * spin * solver.stable_time_step();
  const double momentum0 = angular_momentum(p);
  FreeSpin result;
  for (int s = 0; s < 300; ++s) {
    solver.step();
    result.largest_stress_ratio =
        std::max(result.largest_stress_ratio, largest_stress(p) / stress_scale);
    if (s == 0) {
      result.first_step_ratio = result.largest_stress_ratio;
    }
    result.momentum_drift =
        std::max(result.momentum_drift, std::abs(angular_momentum(p) - momentum0) / momentum0);
  }
  return result;
}

// The exact motion is a rigid rotation: no strain, no stress (the engine has no centrifugal
// term), and nothing changes the angular momentum. Two tolerances:
// - stress below 1e-9 of G Omega dt, the shear one step of a wrong gamma_rtheta would give. With
//   the angular-momentum transfer every node gets omega = Omega up to one rounding (the quotient
//   of two sums whose terms differ by reordered products), so gamma_rtheta = r d(omega)/dr is of
//   order 1e-16 r / h of Omega dt per step; over 300 steps that stays below 1e-12 (measured:
//   below 1e-13). With momentum lumped with the mass (the transfer before), node i got
//   Omega sum(N m r) / sum(N m) instead of Omega r_i: measured 0.13 (disc) and 0.06 (annulus) of
//   G Omega dt in the first step, growing to 0.19 and 0.12.
// - angular momentum within 1e-12 relative: particle-to-grid and grid-to-particle carry
//   sum m r v_theta exactly and the internal torques sum to zero node by node, so only rounding
//   over 300 steps of about 1e3 particles is left (measured: below 1e-14).
TEST(RigidSpin, FreeDiscStaysStressFreeAndKeepsItsAngularMomentum) {
  // A disc through the axis, r in [0, 0.5]: its first column of particles sits at r = h / 4.
  const FreeSpin disc = spin_freely(uniform_grid(0.0, 0.6, 12, 0.0, 0.4, 8), {0.0, 0.5, 0.0, 0.4});
  std::cout << "free disc: max |sigma| / (G Omega dt) = " << disc.largest_stress_ratio
            << " (first step " << disc.first_step_ratio << "), angular momentum drift "
            << disc.momentum_drift << "\n";
  EXPECT_LT(disc.largest_stress_ratio, 1e-9);
  EXPECT_LT(disc.momentum_drift, 1e-12);
}

TEST(RigidSpin, FreeAnnulusOnAGradedGridStaysStressFreeAndKeepsItsAngularMomentum) {
  // An annulus r in [0.3, 0.8] on cells graded from 0.1 to 0.025 m and back: the rigid spin must
  // be exact whatever the cell sizes.
  const AxisZone r_zones[] = {{0.0, 0.3, 3}, {0.3, 0.5, 8}, {0.5, 0.9, 4}};
  const AxisZone y_zones[] = {{0.0, 0.3, 6}};
  const FreeSpin annulus =
      spin_freely(Grid(GradedAxis(r_zones), GradedAxis(y_zones)), {0.3, 0.8, 0.0, 0.3});
  std::cout << "free annulus: max |sigma| / (G Omega dt) = " << annulus.largest_stress_ratio
            << " (first step " << annulus.first_step_ratio << "), angular momentum drift "
            << annulus.momentum_drift << "\n";
  EXPECT_LT(annulus.largest_stress_ratio, 1e-9);
  EXPECT_LT(annulus.momentum_drift, 1e-12);
}

struct TorsionalVibration {
  double period = 0.0;
  double exact_period = 0.0;
  double max_tau_rtheta = 0.0;
  double max_tau_ytheta = 0.0;
  Particles particles;
};

/// An elastic shaft (R = 0.5 m, H = 2 m, G = 50 MPa, nu = 0, rho = 2000 kg/m^3, 10 x 40 cells of
/// 0.05 m, 2 x 2 particles per cell), fixed at its base, free at its top and side, released in
/// its first torsional mode v_theta = Omega r sin(pi y / 2H), Omega = 0.1 rad/s, and followed for
/// `periods` periods.
TorsionalVibration vibrate_shaft(double periods, const SolverSettings& settings) {
  constexpr double radius = 0.5, height = 2.0, h = 0.05, spin = 0.1;
  Scene scene(GeometryMode::axisymmetric, uniform_grid(0.0, radius + h, 11, 0.0, height, 40));
  const auto material =
      scene.add_material(std::make_unique<LinearElastic>(disc_young, 0.0, disc_density));
  fill_rectangle(scene, {0.0, radius, 0.0, height}, 2, material, scene.add_body("shaft"));
  Particles& p = scene.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.v_theta[i] = spin * p.r[i] * std::sin(std::numbers::pi * p.y[i] / (2.0 * height));
  }
  scene.boundaries.constraints = {
      axis_constraint(scene.grid),
      face_constraint(scene.grid, scene.mode, GridFace::y_min, FaceCondition::fixed)};
  RunLog log;
  ExplicitSolver solver(scene, settings, log);
  TorsionalVibration result;
  result.exact_period = 4.0 * height / std::sqrt(disc_young / 2.0 / disc_density);
  OscillationMeter meter(0.0, angular_momentum(p));
  while (solver.time() < periods * result.exact_period) {
    solver.step();
    meter.sample(solver.time(), angular_momentum(p));
    for (const Stress& s : p.stress) {
      result.max_tau_rtheta = std::max(result.max_tau_rtheta, std::abs(s[RT]));
      result.max_tau_ytheta = std::max(result.max_tau_ytheta, std::abs(s[YT]));
    }
  }
  result.period = meter.period();
  result.particles = p;
  return result;
}

// The exact first mode: u_theta = r phi(y, t) with phi_tt = c_s^2 phi_yy, so every cross-section
// turns rigidly (tau_rtheta = 0, tau_ytheta = G r phi_y) and the period is T = 4 H / c_s
// (c_s = sqrt(G / rho) = 158.1 m/s, T = 50.6 ms). The angular momentum sum m r v_theta goes as
// cos(2 pi t / T); its zero crossings give the period.
// Tolerances: the period within 0.5 %. On this mesh the whole discrete error is the dispersion of
// lumped bilinear cells, (k h)^2 / 24 with k = pi / 2H, about 1e-4, plus that of the time
// integration at C = 0.8, smaller still (measured: 0.02 %). max |tau_rtheta| at most 0.1 % of
// max |tau_ytheta|: on the tensor lattice of particles every node of a row gets the same angular
// velocity, and torque and inertia carry the same r^3 weights, so rows stay rigid to rounding
// (measured: 1e-14). The transfer before (momentum lumped with the mass) gave
// max |tau_rtheta| = 6.3 % of max |tau_ytheta| on this shaft, with the period 0.03 % off.
TEST(RigidSpin, ShaftInItsFirstTorsionalModeTurnsEachCrossSectionRigidly) {
  const TorsionalVibration shaft = vibrate_shaft(2.1, SolverSettings{});
  std::cout << "torsional shaft: period " << shaft.period << " s (exact " << shaft.exact_period
            << " s), max |tau_rtheta| / max |tau_ytheta| = "
            << shaft.max_tau_rtheta / shaft.max_tau_ytheta << "\n";
  EXPECT_NEAR(shaft.period, shaft.exact_period, 0.005 * shaft.exact_period);
  EXPECT_LE(shaft.max_tau_rtheta, 1e-3 * shaft.max_tau_ytheta);
}

// Contact exchanges angular momentum between the fields and keeps the sum: V9's soil spinning at
// 0.05 rad/s about an elastic pile at rest (a deformable structure with a field of its own), with
// friction mu = 0.4 and adhesion 10 kPa, and no support, gravity or drive. Nothing outside acts on
// theta and no force acts in the r-y plane (no particle moves radially), so sum m r v_theta over
// soil and pile is conserved exactly; the corrections take the theta inertia J / r^2 and give the
// pile the opposite angular impulse, so only rounding is left (measured: 7e-15 over 0.05 s).
// The tolerance, 1e-12, is that of the free spin above. The pile must have taken a real share, or
// the test would prove nothing (measured: 6 % of the total). The transfer before drifted by
// 5.3e-4.
TEST(RigidSpin, ContactBetweenDeformableBodiesConservesAngularMomentum) {
  std::string text = read_text(source / "cases/verification/v9_torsion_adhesion.toml");
  text = replaced(text, "cells = 40", "cells = 20");
  text = replaced(text, "duration = 1.0", "duration = 0.05");
  text = replaced(text, "[bodies.rigid]\nangular_velocity = { type = \"constant\", value = 0.02 }",
                  "");
  text = replaced(text, "velocity_y = { type = \"constant\", value = 0.0 }\n", "");
  text = replaced(text, "friction = 0.0", "friction = 0.4");
  text = replaced(text, "[boundaries]\nr_max = \"fixed\"\ny_min = \"fixed\"\n", "");
  const std::string spin = "\nvelocity_profile = { component = \"theta\", along = \"r\", "
                           "function = { type = \"table\", points = [[0.0, 0.0], [1.0, 0.05]] } }";
  for (const char* region : {"region = { r = [0.0, 1.0], y = [0.0, 0.5] }",
                             "region = { r = [0.0, 0.4], y = [0.5, 1.0] }",
                             "region = { r = [0.6, 1.0], y = [0.5, 1.0] }"}) {
    text = replaced(text, region, region + spin);
  }
  CaseRun run(text);
  ASSERT_TRUE(run.scene->rigid_bodies.empty());
  const Particles& p = run.scene->particles;
  const std::uint16_t pile = static_cast<std::uint16_t>(run.pair().structure_body);
  auto pile_momentum = [&] {
    double sum = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      sum += p.body[i] == pile ? p.mass[i] * p.r[i] * p.v_theta[i] : 0.0;
    }
    return sum;
  };
  const double total0 = angular_momentum(p);
  ASSERT_EQ(pile_momentum(), 0.0);
  double drift = 0.0;
  run.run([&] { drift = std::max(drift, std::abs(angular_momentum(p) - total0) / total0); });
  std::cout << "contact: angular momentum drift " << drift << ", pile's share "
            << pile_momentum() / total0 << "\n";
  EXPECT_LT(drift, 1e-12);
  EXPECT_GT(pile_momentum() / total0, 0.01);
}

// Colored scatter fixes the order of every nodal sum, the angular ones included: the shaft with
// 2 x 2 cell blocks (many per colour), a FLIP/PIC blend and damping gives the same bits on 1, 2
// and 3 threads.
TEST(RigidSpin, ShaftIsBitwiseIdenticalForOneTwoAndThreeThreads) {
  SolverSettings settings;
  settings.block_cells = 2;
  settings.flip_fraction = 0.97;
  settings.local_damping = 0.05;
  Particles one;
  with_threads(1, [&] { one = vibrate_shaft(0.3, settings).particles; });
  for (const int threads : threads_compared_with_one()) {
    with_threads(threads,
                 [&] { expect_particles_identical(one, vibrate_shaft(0.3, settings).particles); });
  }
}

} // namespace
} // namespace mpile
