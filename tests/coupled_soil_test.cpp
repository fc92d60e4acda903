// Saturated soil whose water flows (drainage = "coupled", two-phase single-point MPM): Terzaghi's
// consolidation (V10, against the closed form), the undrained P-wave a coupled column with a small
// k carries as an undrained one does, Biot's damping of that wave growing with k, the energy
// ledger closing with the drag and the water's energies, the same bits on one, two and three
// threads, and the water's keys refused where they make no sense.
#include "cases/case_builder.hpp"
#include "cases/case_error.hpp"
#include "cases/verification/verification_cases.hpp"
#include "engine/materials/pore_water.hpp"
#include "tests/bitwise.hpp"
#include "tests/case_run.hpp"
#include "tests/saturated_column.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>

namespace mpile {
namespace {

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at != std::string::npos) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// V10's checks (degree of consolidation at T_v = 0.01, 0.1, 0.5 and 1 within 2 %, isochrones at
// 0.1 and 0.5 within 2 % of the load, energy residual under 2 %), each with its reason in
// cases/verification/terzaghi_consolidation.cpp.
TEST(CoupledSoil, TerzaghiConsolidationMatchesTheClosedForm) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  // 42 000 steps take 9 s in the release suite, which runs this test; under a sanitizer they would
  // take minutes. The water's passes are exercised there by the shorter tests below.
  GTEST_SKIP() << "V10 runs in the release suite (42 000 steps)";
#endif
  const verification::Report report = verification::run_terzaghi_consolidation({});
  ASSERT_EQ(report.checks.size(), 7u);
  for (const verification::Check& check : report.checks) {
    EXPECT_LE(check.error(), check.tolerance)
        << check.quantity << " = " << check.measured << ", reference " << check.reference;
  }
}

// With a k so small that the water cannot move against the skeleton within the wave's passage
// (its relaxation time k / (n g) is 2.6e-10 s against a 3 us step), the coupled column carries
// the undrained P-wave c = sqrt((M + K_w / n) / rho_sat) = 1 690 m/s. The front is measured
// between two instants so that its start-up and its smearing over a few cells cancel: 2 % is
// what a 0.05 m cell and half a cell of front position allow over the 10 m between them (the
// undrained material's test, UndrainedSoil.UndrainedPWaveRunsAtTheSaturatedSpeed, uses the same).
TEST(CoupledSoil, SmallConductivityCarriesTheUndrainedPWave) {
  CaseRun run(saturated_wave_column("drainage = \"coupled\"\nhydraulic_conductivity = 1e-9"));
  expect_undrained_p_wave(run);
  // And the ledger closes: the piston's work is the two phases' kinetic energy, the skeleton's
  // and the water's stored energy, and what the drag took (2 %, the target).
  EXPECT_LT(run.solver->energy_balance().relative_residual, 0.02);
  std::cout << "k = 1e-9: residual " << run.solver->energy_balance().relative_residual << '\n';
}

// Biot: the water lags behind the skeleton as k grows, and the drag between them takes a growing
// share of the piston's work (zero for an undrained column, all of the relative motion's energy
// in the limit). Over k = 1e-7, 1e-5 and 1e-3 m/s the share grows strictly, and each run's ledger
// closes within 2 %.
TEST(CoupledSoil, WaveDampingGrowsWithConductivity) {
  double previous = -1.0;
  for (const char* k : {"1e-7", "1e-5", "1e-3"}) {
    CaseRun run(saturated_wave_column(
        std::string("drainage = \"coupled\"\nhydraulic_conductivity = ") + k));
    run.solver->advance_to(0.006);
    const EnergyBalance balance = run.solver->energy_balance();
    const double share = balance.drag / balance.external_work;
    EXPECT_GT(share, previous) << "k = " << k;
    EXPECT_LT(balance.relative_residual, 0.02) << "k = " << k;
    std::cout << "k = " << k << ": drag share " << share << ", residual "
              << balance.relative_residual << '\n';
    previous = share;
  }
  EXPECT_GT(previous, 0.01); // at k = 1e-3 m/s the drag is no rounding error
}

// Runs a case to `until` on one thread and on each count of threads_compared_with_one() (two and
// three; two alone under ThreadSanitizer) and expects the same particles, material state and drag
// to the bit.
void expect_bitwise_for_compared_thread_counts(const std::string& text, double until) {
  std::vector<Particles> runs;
  std::vector<double> drag;
  for (const int threads : compared_thread_counts()) {
    with_threads(threads, [&] {
      CaseRun run(text);
      run.solver->advance_to(until);
      runs.push_back(run.scene->particles);
      drag.push_back(run.solver->energy_balance().drag);
    });
  }
  ASSERT_GT(drag[0], 0.0);
  for (std::size_t k = 1; k < runs.size(); ++k) {
    expect_particles_identical(runs[0], runs[k]);
    EXPECT_TRUE(bitwise_equal(runs[0].state, runs[k].state));
    EXPECT_TRUE(bitwise_equal(std::vector<double>{drag[0]}, std::vector<double>{drag[k]}));
  }
}

// The water's passes are colored scatters and per-block sums: Terzaghi's column (its first 20 ms,
// the load's rise and the first drainage) is bitwise the same on one, two and three threads, the
// water's state and the energy ledger included.
TEST(CoupledSoil, ResultsAreBitwiseIdenticalForOneTwoAndThreeThreads) {
  expect_bitwise_for_compared_thread_counts(
      replaced(read_text(source / "cases/verification/terzaghi_consolidation.toml"),
               "duration = 0.505", "duration = 0.02"),
      0.02);
}

// V10's column (terzaghi_consolidation.toml) drained at its base as well, `base` the base's keys
// and `more` lines after its phase's duration: the water leaves through the held base as through
// the free top, so the column consolidates as two of half its height, each drained on one side
// (Terzaghi's closed form with H / 2). At T_v = c_v t / (H / 2)^2 = 0.3 the degree of
// consolidation is 0.61, against 0.31 for the same time with the base impermeable.
void expect_half_the_drainage_path(const std::string& base, const std::string& more) {
  const std::string text =
      replaced(replaced(read_text(source / "cases/verification/terzaghi_consolidation.toml"),
                        "y_min = \"fixed\"", "y_min = \"fixed\"\n" + base),
               "duration = 0.505", "duration = 0.045\n" + more);
  CaseRun run(text);
  if (!run.spec.phases[0].k0.empty()) {
    apply_k0(*run.scene, run.spec, run.spec.phases[0]);
    run.solver = std::make_unique<ExplicitSolver>(
        *run.scene, phase_settings(run.spec, run.spec.phases[0]), run.log);
  }
  const double height = 1.0, q = 10e3, rise = 2.3962e-3, k = 1.9648e-3;
  const double oedometer = 10e6, bulk = 2.2e9, n = 1.0 - 1600.0 / 2650.0;
  const double c_v = k / (1000.0 * 9.80665 * (1.0 / oedometer + n / bulk));
  const double u0 = q * (bulk / n) / (oedometer + bulk / n);
  const double half = 0.5 * height;
  const auto degree = [](double tv) { // Terzaghi's U, one side drained
    double sum = 0.0;
    for (int m = 0; m < 200; ++m) {
      const double M = std::numbers::pi * (2 * m + 1) / 2.0;
      sum += 2.0 / (M * M) * std::exp(-M * M * tv);
    }
    return 1.0 - sum;
  };
  // The load rises linearly over `rise`: the closed form superposed over the rise.
  const auto reference = [&](double t) {
    double sum = 0.0;
    const int parts = 400;
    for (int j = 0; j < parts; ++j) {
      const double s = (j + 0.5) * rise / parts;
      sum += degree(c_v * (t - s) / (half * half));
    }
    return sum / parts;
  };
  // The run's degree and the reference both averaged over one period of the undrained column
  // (4 H / c_p = 2.396 ms), over which what the load's rise left ringing cancels (as in V10).
  const double period = 2.3962e-3;
  const double centre = 0.3 * half * half / c_v;
  const int samples = 24;
  double measured = 0.0, expected = 0.0;
  std::vector<double> upper, lower; // the excess at depth z and at H - z, mirrored
  const Particles& p = run.scene->particles;
  const Material& soil = *run.scene->materials.at(0);
  const auto change = static_cast<std::size_t>(soil.pore_pressure_index() + 1);
  const auto stride = static_cast<std::size_t>(p.state_stride);
  for (int s = 0; s < samples; ++s) {
    const double t = centre - 0.5 * period + (s + 0.5) * period / samples;
    run.solver->advance_to(t);
    double mean = 0.0, volume = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      mean -= p.volume[i] * p.state[i * stride + change];
      volume += p.volume[i];
    }
    measured += (1.0 - mean / volume / u0) / samples;
    expected += reference(t) / samples;
  }
  // 2 % of the consolidation, V10's tolerance (it holds 0.6 % at T_v = 0.01 with 40 cells over
  // its drainage path; here 20).
  EXPECT_NEAR(measured, expected, 0.02) << "degree of consolidation at T_v = 0.3 (H / 2)";
  EXPECT_NEAR(expected, 0.61, 0.01); // Terzaghi's U(0.3) = 0.613: the time is the one meant
  // The mirror image: the particle at depth z and the one at H - z carry the same excess, within
  // 2 % of the load (the closed form's symmetry about the mid-plane).
  double worst = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = 0; j < p.size(); ++j) {
      if (std::abs(p.y0[i] + p.y0[j] - height) < 1e-9 && std::abs(p.r0[i] - p.r0[j]) < 1e-9) {
        worst =
            std::max(worst, std::abs(p.state[i * stride + change] - p.state[j * stride + change]));
      }
    }
  }
  EXPECT_LT(worst, 0.02 * q);
  std::cout << "U at T_v = 0.3 (H / 2): " << measured << " against " << expected
            << "; mirrored particles within " << worst << " Pa\n";
}

TEST(CoupledSoil, ADrainedBaseHalvesTheDrainagePath) {
  expect_half_the_drainage_path("drained = [\"y_min\"]", "");
}

// The same under gravity from its K0 state, the base drained into the far field's hydrostatic
// water ([boundaries] drained_pressure): the excess pore pressure consolidates as without gravity.
// Drained into an open drain (p = 0 beyond the base) the column's own water runs out as well: its
// excess pore pressure at T_v = 0.3 is then the load's and 10 kPa of the water's weight.
TEST(CoupledSoil, ABaseDrainedIntoTheFarFieldsWaterHalvesTheDrainagePathUnderGravity) {
  expect_half_the_drainage_path(
      "drained = [\"y_min\"]\ndrained_pressure = \"hydrostatic\"\n[solver]\ngravity = [0.0, -9.81]",
      "k0 = [{ body = \"column\", surface = 1.0, k0 = 0.4286 }]");
}

// A saturated column at rest in its K0 state on a base drained into the far field's hydrostatic
// water: nothing moves. The water at the base meets the far field's pressure, integrated on the
// particles' points as the water's own force is, so node by node the column is in equilibrium: the
// water's velocity stays at round-off (an open drain, p = 0 beyond, empties the column at about
// k = 1e-3 m/s), the pore pressure hydrostatic to round-off, and the base's support carries the
// skeleton's buoyant weight alone, the far field's water the rest.
TEST(CoupledSoil, ABaseDrainedIntoTheFarFieldsWaterHoldsAColumnAtRest) {
  const std::string text = replaced(
      saturated_column(5.0, 20, 0.5,
                       "type = \"linear_elastic\"\nyoung_modulus = 50e6\npoisson_ratio = 0.3\n"
                       "density = 1600.0\ndrainage = \"coupled\"\nhydraulic_conductivity = 1e-3\n"),
      "y_min = \"fixed\"\n",
      "y_min = \"fixed\"\ndrained = [\"y_min\"]\ndrained_pressure = \"hydrostatic\"\n");
  CaseRun run(text);
  apply_k0(*run.scene, run.spec, run.spec.phases[0]);
  run.solver = std::make_unique<ExplicitSolver>(
      *run.scene, phase_settings(run.spec, run.spec.phases[0]), run.log);
  run.solver->advance_to(0.5);
  const Particles& p = run.scene->particles;
  const Material& sand = *run.scene->materials.at(0);
  const auto stride = static_cast<std::size_t>(p.state_stride);
  const auto pore = static_cast<std::size_t>(sand.pore_pressure_index());
  const LiquidPhase* phase = sand.liquid_phase();
  ASSERT_NE(phase, nullptr);
  const auto water_velocity = static_cast<std::size_t>(phase->velocity_slot);
  const double rho_w = 1000.0, g = 9.81, height = 5.0;
  double fastest = 0.0, worst = 0.0, weight = 0.0, buoyancy = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double* state = p.state.data() + i * stride;
    fastest =
        std::max({fastest, std::abs(state[water_velocity]), std::abs(state[water_velocity + 1])});
    worst = std::max(worst, std::abs(state[pore] + rho_w * g * (height - p.y[i])));
    weight += p.mass[i] * g;
  }
  // The far field's water under the base: rho_w g H over the base's area per radian, R^2 / 2.
  buoyancy = rho_w * g * height * 0.5 * 0.5 * 0.5;
  double base = 0.0;
  for (const NodeConstraint& c : run.scene->boundaries.constraints) {
    if (c.name == "y_min") {
      base = c.reaction[1];
    }
  }
  EXPECT_LT(fastest, 1e-9) << "m/s; k = 1e-3 m/s";
  EXPECT_LT(worst, 1e-6 * rho_w * g * height) << "Pa from hydrostatic";
  EXPECT_NEAR(base / (weight - buoyancy), 1.0, 1e-4)
      << "base " << base << " N/rad, weight " << weight << ", the far field's water " << buoyancy;
  std::cout << "water velocity " << fastest << " m/s, pore pressure off hydrostatic "
            << worst / (rho_w * g * height) << " of rho_w g H, reaction / buoyant weight - 1 "
            << base / (weight - buoyancy) - 1.0 << '\n';
}

// A drained well and a rigid plate's underside, where the water flows along the wall past the
// skeleton (update_water_velocities' split after the contact) and the drain keeps its water's
// velocity: the radial consolidation cell under its plate, over the load's rise and the first
// drainage, is bitwise the same on one, two and three threads.
TEST(CoupledSoil, AWallAndADrainAreBitwiseIdenticalForOneTwoAndThreeThreads) {
  expect_bitwise_for_compared_thread_counts(
      replaced(read_text(source / "cases/verification/radial_consolidation_plate.toml"),
               "duration = 5.0", "duration = 0.03"),
      0.03);
}

// The same under XPIC(2): the water's own XPIC adds colored gather-scatters of the water
// (solver/water_xpic.cpp), and the plate's wall and the drain decide some of its DOFs.
TEST(CoupledSoil, TheWatersXpicIsBitwiseIdenticalForOneTwoAndThreeThreads) {
  expect_bitwise_for_compared_thread_counts(
      replaced(read_text(source / "cases/verification/radial_consolidation_plate.toml"),
               "duration = 5.0", "duration = 0.03") +
          "[solver]\nxpic_order = 2\n",
      0.03);
}

// The column of the tests below; `solver` holds its [solver] table's lines.
std::string self_weight_column(const std::string& solver) {
  return R"(title = "self-weight consolidation"
geometry = "axisymmetric"
[grid]
r = [{ start = 0.0, end = 0.05, cells = 2 }]
y = [{ start = 0.0, end = 1.05, cells = 42 }]
[materials.soil]
type = "linear_elastic"
young_modulus = 226590.0       # E_oed = 305 kPa with nu = 0.3
poisson_ratio = 0.3
density = 1600.0               # dry; n0 = 1 - 1600 / 2650 = 0.396
drainage = "coupled"
hydraulic_conductivity = 0.1
[[bodies]]
name = "column"
material = "soil"
region = { r = [0.0, 0.05], y = [0.0, 1.0] }
[boundaries]
r_max = "roller"
y_min = "fixed"
[solver]
gravity = [0.0, -9.81]
)" + solver +
         R"(
[[phases]]
name = "consolidation"
duration = 0.96
)";
}

// The column consolidated to T_v = 3 (c_v = k / (gamma_w (1 / E_oed + n / K_w)) = 3.11 m^2/s):
// its strain, and the water's share of the stress at its base against the water's share of the
// column's weight.
void expect_consolidated_under_its_own_weight(CaseRun& run) {
  run.solver->advance_to(0.96);
  const Particles& p = run.scene->particles;
  const Material& soil = *run.scene->materials.at(0);
  const auto pore = static_cast<std::size_t>(soil.pore_pressure_index());
  const auto stride = static_cast<std::size_t>(p.state_stride);
  const double area = 0.5 * 0.05 * 0.05; // per radian
  double volume = 0.0, mass = 0.0, lowest = 1.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    volume += p.volume[i];
    mass += p.mass[i];
    lowest = std::min(lowest, p.y[i]);
  }
  const double height = volume / area;
  EXPECT_NEAR(1.0 - height, 0.016, 0.002); // gamma' H / (2 E_oed): the strain meant
  double water = 0.0, total = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.y[i] < lowest + 1e-3) { // the bottom row
      water += p.state[i * stride + pore];
      total += p.stress[i][YY];
    }
  }
  const double share = 1000.0 * 9.81 * height / (mass * 9.81 / area);
  EXPECT_NEAR(water / total / share, 1.0, 0.005) << "the water's share of the stress at the base";
}

// A soft saturated column (E_oed = 305 kPa, n0 = 0.396, k = 0.1 m/s, drained at its free top)
// consolidates under its own weight from rest: at first the water carries the buoyant weight, at
// the end the skeleton does, with a mean volumetric strain of 1.6 %, and the pore water is
// hydrostatic, p = -rho_w g depth. The water that drained takes its weight with it: a particle that
// kept its initial water mass weighed its water n0 V0 / (n V) times too heavily (5 to 9 % at the
// base). Read at the base as the share of the total vertical stress the water carries, p /
// sigma_yy, against the water's share of the column's weight, rho_w g H / (W / A): both stresses
// carry the same discretisation offset near the free surface (each about 2.5 % above the weight
// above them at 40 cells), which the ratio cancels. Run to T_v = c_v t / H^2 = 3, where Terzaghi's
// series leaves 0.1 % of the initial excess; 0.5 % bounds that and the bottom row's height above
// the base (0.6 % of H, in both numerator and denominator). XPIC(2) and one excess pore pressure
// per cell: under pure FLIP or per-particle pressures a checkerboard grows in the pressure over
// the 80 000 steps (docs/saturated.md).
TEST(CoupledSoil, AColumnConsolidatingUnderItsOwnWeightEndsWithHydrostaticWater) {
  CaseRun run(self_weight_column("xpic_order = 2\ncell_mean_pore_pressure = true"));
  expect_consolidated_under_its_own_weight(run);
}

// The same column with the implicit pore pressure under pure FLIP (the saturated installation
// cases' settings). The projection's correction used to move the particles' velocities but not
// their positions, and booked its kinetic energy as damping: in slow consolidation the momentum
// balance, taken at p^n, accelerates the column by what the correction stops in every step, so
// that damping (0.047 J of 0.14 J of gravity's work) was never put in; the ledger ran 30 % out of
// balance and the energy guard stopped the run at 0.46 s. Now it ends within 0.01 % (1 % allowed:
// the ledger's first-order terms); the strain and the water's share as in the explicit run above.
TEST(CoupledSoil, TheColumnWithTheImplicitPorePressureUnderPureFlipKeepsItsEnergyBalance) {
  CaseRun run(self_weight_column("implicit_pore_pressure = true\ncell_mean_pore_pressure = true"));
  expect_consolidated_under_its_own_weight(run);
  const EnergyBalance energy = run.solver->energy_balance();
  EXPECT_LT(std::abs(energy.relative_residual), 0.01)
      << "residual " << energy.residual << " J of external work " << energy.external_work << " J";
  EXPECT_LT(energy.damping, 1e-3 * energy.external_work) << "nothing damps this column but drag";
}

// A saturated column at rest in its K0 state on an impermeable fixed base: the base holds the
// skeleton and, being impermeable, the water too, so its reaction is the column's whole weight.
// The recorded reaction left out the force that holds the water to the skeleton there: it read
// 10.55 of 12.24 kN/rad (0.862), the water's share at the base missing. Now within 1e-4 of the
// weight (the column at rest: only the grid's rounding moves it).
TEST(CoupledSoil, AnImpermeableBaseCarriesTheWholeWeightOfAColumnAtRest) {
  const std::string text =
      saturated_column(5.0, 20, 0.01,
                       "type = \"linear_elastic\"\nyoung_modulus = 50e6\npoisson_ratio = 0.3\n"
                       "density = 1600.0\ndrainage = \"coupled\"\nhydraulic_conductivity = 1e-3\n");
  CaseRun run(text);
  apply_k0(*run.scene, run.spec, run.spec.phases[0]);
  run.solver = std::make_unique<ExplicitSolver>(
      *run.scene, phase_settings(run.spec, run.spec.phases[0]), run.log);
  run.solver->advance_to(0.01);
  double weight = 0.0;
  for (std::size_t i = 0; i < run.scene->particles.size(); ++i) {
    weight += run.scene->particles.mass[i] * 9.81;
  }
  double base = 0.0;
  for (const NodeConstraint& c : run.scene->boundaries.constraints) {
    if (c.name == "y_min") {
      base = c.reaction[1];
    }
  }
  EXPECT_NEAR(base / weight, 1.0, 1e-4) << "base " << base << " N/rad, weight " << weight;
}

/// The reader's refusal of a case ("accepted" if it builds).
std::string coupled_error_of(const std::string& text) {
  try {
    CaseRun run(text);
  } catch (const CaseError& e) {
    return std::string(e.what());
  }
  return std::string("accepted");
}

// Settings that would be read and then ignored are refused at their key: one excess pore pressure
// per cell in a scene without pore water, and a saturated material on a rigid body (whose
// particles carry neither stress nor water).
TEST(CoupledSoil, SettingsWithoutPoreWaterToActOnAreRefusedAtTheirKey) {
  std::string error =
      coupled_error_of(saturated_wave_column("") + "[solver]\ncell_mean_pore_pressure = true\n");
  EXPECT_NE(error.find(": solver.cell_mean_pore_pressure: no material is undrained or coupled"),
            std::string::npos)
      << error;
  error = coupled_error_of(
      replaced(saturated_wave_column("drainage = \"coupled\"\nhydraulic_conductivity = 1e-4"),
               "region = { r = [0.0, 0.1], y = [0.0, 30.0] }",
               "region = { r = [0.0, 0.1], y = [0.0, 30.0] }\n[bodies.rigid]\nvelocity_y = 0.0"));
  EXPECT_NE(error.find(": bodies[0].material: 'sand' is saturated (drainage = \"coupled\"), but a "
                       "rigid body has no pores"),
            std::string::npos)
      << error;
}

// The far field's water is refused, at drained_pressure's line, where it has nothing to act
// through (no drained face), no hydrostatic state (gravity along r) or no surface to stand on (no
// K0 procedure gives the saturated body one).
TEST(CoupledSoil, AFarFieldWithoutADrainGravityOrASurfaceIsRefusedAtItsKey) {
  const std::string column =
      saturated_column(5.0, 20, 0.01,
                       "type = \"linear_elastic\"\nyoung_modulus = 50e6\npoisson_ratio = 0.3\n"
                       "density = 1600.0\ndrainage = \"coupled\"\nhydraulic_conductivity = 1e-3\n");
  const std::string hydrostatic = "drained_pressure = \"hydrostatic\"\n";
  const std::string drained = "drained = [\"y_min\"]\n" + hydrostatic;
  // The key's line: the column's [boundaries] table, after its faces (and the drained list).
  const std::string key = ": boundaries.drained_pressure: ";
  std::string error = coupled_error_of(
      replaced(column, "y_min = \"fixed\"\n", "y_min = \"fixed\"\n" + hydrostatic));
  EXPECT_EQ(error.rfind("test.toml:19" + key + "no face is drained", 0), 0u) << error;
  const std::string at = "test.toml:20" + key;
  error = coupled_error_of(
      replaced(replaced(column, "y_min = \"fixed\"\n", "y_min = \"fixed\"\n" + drained),
               "gravity = [0.0, -9.81]", "gravity = [-9.81, 0.0]"));
  EXPECT_NE(error.find(at + "the far field's water is hydrostatic under gravity along -y"),
            std::string::npos)
      << error;
  error = coupled_error_of(
      replaced(replaced(column, "y_min = \"fixed\"\n", "y_min = \"fixed\"\n" + drained),
               "k0 = [{ body = \"column\", surface = 5, k0 = 0.5 }]\n", ""));
  EXPECT_NE(error.find(at + "body 'column' holds pore water but no phase gives it a K0 procedure"),
            std::string::npos)
      << error;
  EXPECT_EQ(
      coupled_error_of(replaced(column, "y_min = \"fixed\"\n", "y_min = \"fixed\"\n" + drained)),
      "accepted");
}

// A body given an initial velocity moves whole, its pore water with its grains: a saturated block
// thrown through empty space (no gravity, no support) keeps its momentum and kinetic energy, and
// Darcy's drag takes nothing (its water used to start at rest, and the drag then took part of the
// grains' momentum and energy).
void thrown_block(const std::string& solver);

TEST(CoupledSoil, ABodySetMovingMovesWithItsWater) {
  // With XPIC(2) too: its projection weighs the particles' masses, and must divide by the
  // mixture's node mass, not the skeleton's effective mass the node holds after the phases are
  // coupled (with that, the block lost 60 % of its kinetic energy in the 2 ms).
  for (const char* solver : {"", "[solver]\nxpic_order = 2\n"}) {
    SCOPED_TRACE(solver);
    thrown_block(solver);
  }
}

void thrown_block(const std::string& solver) {
  CaseRun run(std::string(R"(title = "thrown block"
geometry = "axisymmetric"
[grid]
r = [{ start = 0.0, end = 0.5, cells = 5 }]
y = [{ start = 0.0, end = 2.0, cells = 20 }]
[materials.sand]
type = "linear_elastic"
young_modulus = 100e6
poisson_ratio = 0.25
density = 1600.0
drainage = "coupled"
hydraulic_conductivity = 1e-5
[[bodies]]
name = "block"
material = "sand"
region = { r = [0.0, 0.4], y = [0.5, 1.0] }
velocity = [0.0, 1.0, 0.0]
[[phases]]
name = "flight"
duration = 0.002
gravity = false
)") + solver);
  const Particles& p = run.scene->particles;
  const LiquidPhase& water = *run.scene->materials.at(0)->liquid_phase();
  const auto stride = static_cast<std::size_t>(p.state_stride);
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_EQ(p.state[i * stride + static_cast<std::size_t>(water.velocity_slot) + 1], 1.0);
  }
  const double start = run.solver->energy_balance().kinetic;
  run.solver->advance_to(0.002);
  const EnergyBalance end = run.solver->energy_balance();
  // A rigid translation strains nothing and the phases move together: round-off only.
  EXPECT_NEAR(end.kinetic, start, 1e-9 * start);
  EXPECT_LT(std::abs(end.drag), 1e-9 * start);
  std::cout << "thrown block: kinetic energy change " << end.kinetic / start - 1.0 << ", drag "
            << end.drag / start << '\n';
}

// Darcy's drag takes energy and never gives it. The seed's torsion check in saturated soil (the
// pile turned back and forth at 60 Hz, 2 rad/s, for six cycles, the implicit pore pressure and the
// cell-mean pore pressure as the installation cases run): FLIP keeps each particle's relative flow
// apart from the grid's, and the drag relaxes it on the particle. Relaxing the water alone towards
// its skeleton's deviation made momentum and booked negative drag here, -0.0046, -0.0087 and
// -0.0060 J at k = 1e-3, 1e-4 and 1e-5 m/s (of 26.7 J of work); on 60 GDP cycles at k = 1e-4 that
// energy grew into an instability (-2.8 kJ of drag, the ledger 8.6 % off; 0.006 % now,
// docs/results.md). Relaxing the two phases against each other, their momentum kept, books
// +0.0046, +0.0009 and +0.0011 J (measured). The ledger closes within 0.5 % (measured 0.2 %).
TEST(CoupledSoil, TheDragOnTheParticlesRelativeFlowTakesEnergyAndNeverGivesIt) {
  for (const char* k : {"1e-3", "1e-4", "1e-5"}) {
    SCOPED_TRACE(k);
    std::string text = spun_pile_text(
        20, std::string("drainage = \"coupled\"\nhydraulic_conductivity = ") + k, 0.1);
    text =
        replaced(text, "angular_velocity = { type = \"constant\", value = 0.02 }",
                 "angular_velocity = { type = \"harmonic\", amplitude = 2.0, frequency = 60.0 }");
    text = replaced(text, "[solver]\n",
                    "[solver]\nimplicit_pore_pressure = true\ncell_mean_pore_pressure = true\n");
    CaseRun run(text);
    apply_k0(*run.scene, run.spec, run.spec.phases[0]);
    run.solver = std::make_unique<ExplicitSolver>(
        *run.scene, phase_settings(run.spec, run.spec.phases[0]), run.log);
    run.solver->advance_to(0.1);
    const EnergyBalance end = run.solver->energy_balance();
    EXPECT_GT(end.drag, 0.0);
    EXPECT_LT(std::abs(end.relative_residual), 0.005);
    std::cout << "k = " << k << " m/s: drag " << end.drag << " J of " << end.external_work
              << " J of work, residual " << end.relative_residual << '\n';
  }
}

// An absorbing face holds the water to the skeleton along its normal, so its dashpot takes the
// mixture's wave and no water leaves unbooked: the shipped absorbing column (a P pulse) with its
// soil coupled at k = 1e-5 m/s lets its pulse out (measured: under 0.01 % left, the drag 2.4 %, the
// dashpots 96 %) and its ledger closes to 1.1 %; with the water let through the released face as
// through a drained one, 3.9 % went unbooked. 2 %: the ledger's target.
TEST(CoupledSoil, AnAbsorbingFaceLetsTheSaturatedPulseOut) {
  CaseRun run(replaced(read_text(source / "cases/verification/absorbing_column.toml"),
                       "density = 2000.0",
                       "density = 2000.0\ndrainage = \"coupled\"\nhydraulic_conductivity = 1e-5"));
  const double start = run.solver->energy_balance().kinetic;
  run.run([] {});
  const EnergyBalance end = run.solver->energy_balance();
  EXPECT_LT(end.kinetic + end.elastic, 0.01 * start);
  EXPECT_LT(std::abs(end.relative_residual), 0.02);
  std::cout << "k = 1e-5: left " << (end.kinetic + end.elastic) / start << ", drag "
            << end.drag / start << ", dashpots " << end.radiated / start << ", residual "
            << end.relative_residual << '\n';
}

// Nearly incompressible soil (undrained, or coupled with so small a k that its water cannot move
// against the skeleton) under pure FLIP lets a mode the grid does not see grow after the pulse has
// left the same column: 1.9 % of the pulse is back by 0.049 s, the ledger 4.7 % off, and less so
// the smaller the step (Courant 0.25: none). XPIC(2) filters it: under 0.01 % left, the dashpots
// 99.1 % undrained and 99.2 % coupled (the water on its own field's XPIC(2); taken from its field
// by PIC, the transfer's smoothing took 4 % and the dashpots had 95.4 %), the ledger within 0.4 %
// (measured). 2 %: the ledger's target; 0.1 % left against FLIP's 1.9 %; 98 % through the
// dashpots: at k = 1e-9 the drag takes nothing, and the rest is the transfer's at the pulse's
// start. (The saturated installation cases take the implicit pore pressure instead, which
// absorbing faces refuse.)
TEST(CoupledSoil, XpicLetsTheNearlyIncompressiblePulseOut) {
  for (const std::string water :
       {"drainage = \"undrained\"", "drainage = \"coupled\"\nhydraulic_conductivity = 1e-9"}) {
    SCOPED_TRACE(water);
    CaseRun run(replaced(read_text(source / "cases/verification/absorbing_column.toml"),
                         "density = 2000.0", "density = 2000.0\n" + water) +
                "[solver]\nxpic_order = 2\n");
    const double start = run.solver->energy_balance().kinetic;
    run.run([] {});
    const EnergyBalance end = run.solver->energy_balance();
    EXPECT_LT(end.kinetic + end.elastic, 0.001 * start);
    EXPECT_GT(end.radiated, 0.98 * start);
    EXPECT_LT(std::abs(end.relative_residual), 0.02);
    std::cout << water.substr(0, water.find('\n')) << ": left "
              << (end.kinetic + end.elastic) / start << ", dashpots " << end.radiated / start
              << ", residual " << end.relative_residual << '\n';
  }
}

// Each refusal names the file, the line and the key.
TEST(CoupledSoil, BadWaterInputIsRefusedAtItsLine) {
  const std::string base =
      saturated_wave_column("drainage = \"coupled\"\nhydraulic_conductivity = 1e-4");
  struct Bad {
    const char* what;
    std::string from, to;
    const char* expected;
    const char* key;
  };
  const std::vector<Bad> bad{
      {"no k", "hydraulic_conductivity = 1e-4", "", "missing", "[materials.sand]"},
      {"k not positive", "hydraulic_conductivity = 1e-4", "hydraulic_conductivity = 0.0",
       "must be > 0", "hydraulic_conductivity ="},
      {"k for undrained soil", "drainage = \"coupled\"", "drainage = \"undrained\"",
       "does not flow", "hydraulic_conductivity ="},
      {"mass scaling", "name = \"wave\"", "name = \"wave\"\nmass_scaling = 10.0", "mass_scaling",
       ""},
      {"a free face drained", "r_max = \"roller\"", "r_max = \"roller\"\ndrained = [\"y_max\"]",
       "a free face", "drained ="},
  };
  for (const Bad& b : bad) {
    const std::string text = replaced(base, b.from, b.to);
    std::string message = "no error";
    try {
      CaseRun run(text);
    } catch (const CaseError& e) {
      message = e.what();
    } catch (const std::invalid_argument& e) {
      message = e.what();
    }
    EXPECT_NE(message.find(b.expected), std::string::npos) << b.what << ": " << message;
    if (std::string(b.key).empty()) {
      continue;
    }
    const auto at = text.find(b.key);
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
    EXPECT_NE(message.find("test.toml:" + std::to_string(line) + ":"), std::string::npos)
        << b.what << ": " << message;
  }
  // A drained face where no water flows.
  const std::string undrained =
      replaced(saturated_wave_column("drainage = \"undrained\""), "r_max = \"roller\"",
               "r_max = \"roller\"\ndrained = [\"r_max\"]");
  try {
    CaseRun run(undrained);
    ADD_FAILURE() << "a drained face without coupled soil was accepted";
  } catch (const CaseError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("drained: no material is coupled"), std::string::npos) << message;
  }
}

} // namespace
} // namespace mpile
