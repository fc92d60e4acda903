// The implicit pore pressure ([solver] implicit_pore_pressure; physics.md section 9d): the same
// closed forms as the explicit water (Terzaghi's consolidation, the undrained P-wave), met with
// the step the skeleton alone sets; the pressure following the volume as K_w / n; the ledger
// closing with backward Euler's damping booked; the same bits on one, two and three threads; and
// the setting refused where it cannot work.
#include "app/run_command.hpp"
#include "cases/case_error.hpp"
#include "cases/verification/verification_cases.hpp"
#include "io/hdf5_file.hpp"
#include "solver/conjugate_gradients.hpp"
#include "tests/bitwise.hpp"
#include "tests/case_run.hpp"
#include "tests/eigen_reference_solve.hpp"
#include "tests/saturated_column.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace mpile {
namespace {

std::string implicit(std::string text) {
  return text + "[solver]\nimplicit_pore_pressure = true\n";
}

/// The case's sand saturated, its water flowing at k = 1e-4 m/s, the pore pressure solved on the
/// grid and shared per cell; then `more`.
std::vector<std::string> coupled_sand_with(std::initializer_list<std::string> more) {
  std::vector<std::string> overrides{
      "materials.sand.drainage=\"coupled\"", "materials.sand.grain_density=2650.0",
      "materials.sand.hydraulic_conductivity=1e-4", "solver.implicit_pore_pressure=true",
      "solver.cell_mean_pore_pressure=true"};
  overrides.insert(overrides.end(), more);
  return overrides;
}

// V10's checks, unchanged (each with its reason in cases/verification/terzaghi_consolidation.cpp),
// with the step the skeleton sets: 0.8 h / sqrt(E_oed / rho_sat) = 0.8 x 0.025 / 70.8 = 2.83e-4
// s, 1 787 steps to T_v = 1 against the explicit water's 42 000 (its step follows the undrained
// P-wave, 1 669 m/s). 10 % above 1 787: the skeleton's wave speed changes a little as it strains.
TEST(ImplicitPorePressure, TerzaghiConsolidationAtTheSkeletonsStep) {
  verification::Options options;
  options.implicit_pore_pressure = true;
  const verification::Report report = verification::run_terzaghi_consolidation(options);
  ASSERT_EQ(report.checks.size(), 7u);
  for (const verification::Check& check : report.checks) {
    EXPECT_LE(check.error(), check.tolerance)
        << check.quantity << " = " << check.measured << ", reference " << check.reference;
  }
  const double skeleton_step = 0.8 * 0.025 / std::sqrt(10e6 / (1600.0 + 0.3962 * 1000.0));
  EXPECT_LT(static_cast<double>(report.steps), 1.1 * 0.505 / skeleton_step);
}

// Mass scaling multiplies both phases' inertia and leaves Darcy's drag: the water drains as fast
// as unscaled while the skeleton's scaled wave stays quick against the drainage. V10 at beta = 10:
// the wave's period 4 H / c (c = 70.8 / sqrt(10) m/s) is 0.36 of the consolidation time H^2 /
// c_v, against 0.11 unscaled: from T_v = 0.5 on the degree of consolidation is within 0.5 % of
// Terzaghi's (measured 0.17 % and 0.19 %; unscaled 0.04 and 0.01 %), in 566 steps against 1 787.
// Early on the inertia shows, as mass scaling's does (U at T_v = 0.01 is 4 % off, beyond V10's
// 2 %; at beta = 100, where the period is 1.1 times the consolidation time, 53 %). Scaling the
// drag with the inertia would divide c_v by beta: U at T_v = 0.5 would be Terzaghi's at 0.05, 0.25.
TEST(ImplicitPorePressure, MassScalingKeepsTheConsolidationTime) {
  verification::Options options;
  options.implicit_pore_pressure = true;
  options.mass_scaling = 10.0;
  const verification::Report report = verification::run_terzaghi_consolidation(options);
  ASSERT_EQ(report.checks.size(), 7u);
  int late = 0;
  for (const verification::Check& check : report.checks) {
    std::cout << check.quantity << " = " << check.measured << ", error " << check.error() << '\n';
    if (check.quantity.find("degree of consolidation U at T_v = 0.5") == 0 ||
        check.quantity.find("degree of consolidation U at T_v = 1") == 0) {
      EXPECT_LT(check.error(), 0.005) << check.quantity << " = " << check.measured;
      ++late;
    }
  }
  EXPECT_EQ(late, 2);
  EXPECT_LT(report.steps, 1787 / 2); // the step grows by sqrt(10)
  std::cout << "mass scaling x10: " << report.steps << " steps\n";
}

// The undrained P-wave at sqrt((M + K_w / n) / rho_sat) = 1 685.7 m/s within 2 % (the front
// between 6 and 12 ms, as the explicit water's test measures it), though each step is 5.3 times
// longer than the time the wave takes to cross a cell: the pressure is implicit. The ledger
// closes within 2 % (the target) with backward Euler's S dp^2 / 2 booked as damping (1.95 %
// undrained at 586f9aa; 1.5 % when the correction's kinetic energy was booked too, which put slow
// consolidation 30 % out; 5.2 % with nothing booked). Undrained, and coupled with a k too small
// for the water to move.
TEST(ImplicitPorePressure, UndrainedPWaveAtTheSkeletonsStep) {
  for (const std::string water :
       {"drainage = \"undrained\"", "drainage = \"coupled\"\nhydraulic_conductivity = 1e-9"}) {
    CaseRun run(implicit(saturated_wave_column(water)));
    const double n = 1.0 - 1600.0 / 2650.0;
    const double skeleton_speed = std::sqrt(100e6 * 0.75 / (1.25 * 0.5) / (1600.0 + n * 1000.0));
    EXPECT_NEAR(run.solver->stable_time_step(), 0.8 * 0.05 / skeleton_speed, 1e-9) << water;
    expect_undrained_p_wave(run);
    EXPECT_LT(run.solver->energy_balance().relative_residual, 0.02) << water;
    EXPECT_GT(run.solver->energy_balance().damping, 0.0) << water;
    std::cout << water.substr(0, water.find('\n')) << ": " << run.solver->step_count()
              << " steps, residual " << run.solver->energy_balance().relative_residual << '\n';
  }
}

// The cavitation cut-off inside the solve: the saturated wave column pulled down at its base at
// 0.01 m/s with the water cavitating at 10 kPa (the explicit water's test, Sea.Cavitation...).
// The wave splits: a precursor at c_u = 1 686 m/s carrying the velocity c_u p_cav n / K_w = 3.04e-3
// m/s, in which the water just reaches the cut-off, then the skeleton alone at 245 m/s. Held at the
// limit in the solve, the cells' velocities take the 10 kPa the water carries: at 8 ms, between 4
// and 10 m (behind the precursor's front at 13.5 m, its backward-Euler spread a few metres, ahead
// of the skeleton's at 2 m) the particles move at the precursor's velocity within 1 %, as the
// explicit water's (measured 0.20 % slow); no pore pressure passes the cut-off but by rounding, and
// the ledger closes within 1 % with the vapour's work booked (measured 0.03 and 0.24 %). With the
// cut-off applied to the particles after an uncut solve, the solve's correction pushed with the
// tension the water no longer carried: at 12 ms the precursor ran 4.5 % fast and the ledger ended
// 10.4 % off. Undrained, and coupled with a k too small for the water to move; the coupled run on
// one, two and three threads bitwise the same (the held cells are found on one thread from sums
// each block makes for its own cells).
TEST(ImplicitPorePressure, CavitationHoldsTheWaterAtItsLimitInTheSolve) {
  const double n = 1.0 - 1600.0 / 2650.0;
  const double rho_sat = 1600.0 + n * 1000.0;
  const double c_u = std::sqrt((100e6 * 0.75 / (1.25 * 0.5) + 2.2e9 / n) / rho_sat);
  const double precursor = c_u * 10e3 * n / 2.2e9;
  for (const std::string water :
       {"drainage = \"undrained\"", "drainage = \"coupled\"\nhydraulic_conductivity = 1e-9"}) {
    SCOPED_TRACE(water);
    const std::string text = implicit(replaced(saturated_wave_column(water), "velocity_y = 0.01",
                                               "velocity_y = -0.01")) +
                             "[water]\ncavitation_stress = 10e3\n";
    CaseRun run(text);
    run.solver->advance_to(0.008);
    const Particles& p = run.scene->particles;
    if (water.find("coupled") != std::string::npos) {
      // The coupled path on one thread and on the most compared (this run took the default
      // arena's).
      for (const int threads : {1, threads_compared_with_one().back()}) {
        with_threads(threads, [&] {
          CaseRun other(text);
          other.solver->advance_to(0.008);
          expect_particles_identical(p, other.scene->particles);
          EXPECT_TRUE(bitwise_equal(p.state, other.scene->particles.state));
          EXPECT_EQ(run.solver->energy_balance().residual, other.solver->energy_balance().residual);
        });
      }
    }
    double sum = 0.0;
    int count = 0;
    double highest = -1e300;
    const auto slot = static_cast<std::size_t>(run.scene->materials[0]->pore_pressure_index());
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.y[i] >= 4.0 && p.y[i] <= 10.0) {
        sum += p.v_y[i];
        ++count;
      }
      highest = std::max(highest, p.state[i * static_cast<std::size_t>(p.state_stride) + slot]);
    }
    EXPECT_NEAR(sum / count, -precursor, 0.01 * precursor);
    EXPECT_NEAR(highest, 10e3, 1e-9 * 10e3);
    EXPECT_LT(std::abs(run.solver->energy_balance().relative_residual), 0.01);
    std::cout << water.substr(0, water.find('\n')) << ": precursor "
              << -sum / count / precursor - 1.0 << " off, residual "
              << run.solver->energy_balance().relative_residual << '\n';
  }
}

// Undrained, the pore pressure is K_w / n times the volumetric strain at every particle: the
// solve's increment and the strain the stress pass takes come from the same corrected velocities
// and the same cell-mean divergence. The pressure sums the increments d eps while the volume
// multiplies 1 + d eps, so the two differ at second order: within (K_w / n) eps^2 / 2 (the wave
// front compresses a particle within a step or two). Measured: 0.08 Pa of 33 kPa, as the explicit
// water's 0.10 Pa; the bound (K_w / n) eps^2 is 0.18 Pa. The solve's tolerance, 1e-10 of its
// right-hand side, is far below.
TEST(ImplicitPorePressure, PorePressureFollowsTheVolumeAsKwOverN) {
  CaseRun run(implicit(saturated_wave_column("drainage = \"undrained\"")));
  run.solver->advance_to(0.012);
  const Particles& p = run.scene->particles;
  const Material& sand = *run.scene->materials.at(0);
  const auto slot = static_cast<std::size_t>(sand.pore_pressure_index());
  const double stiffness = 2.2e9 / (1.0 - 1600.0 / 2650.0);
  double largest = 0.0, worst = 0.0, strain_bound = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double pore = p.state[i * static_cast<std::size_t>(p.state_stride) + slot];
    const double strain = p.volume[i] * sand.density() / p.mass[i] - 1.0;
    largest = std::max(largest, std::abs(pore));
    worst = std::max(worst, std::abs(pore - stiffness * strain));
    strain_bound = std::max(strain_bound, stiffness * strain * strain);
  }
  ASSERT_GT(largest, 3e4); // the wave has compressed the water: rho_sat c v_piston B = 33 kPa
  EXPECT_LT(worst, strain_bound);
  std::cout << "p against (K_w / n) eps_vol: worst " << worst << " Pa of " << largest << ", bound "
            << strain_bound << '\n';
}

// The solve's sums are per cell in the block that holds it and the conjugate gradients' product
// sums each row alone: Terzaghi's column (its first 20 ms) is bitwise the same on one, two and
// three threads, the water's state and the ledger included.
TEST(ImplicitPorePressure, ResultsAreBitwiseIdenticalForOneTwoAndThreeThreads) {
  const std::string text =
      implicit(replaced(read_text(source / "cases/verification/terzaghi_consolidation.toml"),
                        "duration = 0.505", "duration = 0.02"));
  std::vector<Particles> runs;
  std::vector<double> ledger;
  for (const int threads : compared_thread_counts()) {
    with_threads(threads, [&] {
      CaseRun run(text);
      run.solver->advance_to(0.02);
      runs.push_back(run.scene->particles);
      const EnergyBalance balance = run.solver->energy_balance();
      ledger.insert(ledger.end(), {balance.drag, balance.damping, balance.residual});
    });
  }
  ASSERT_GT(ledger[1], 0.0);
  const std::vector<double> first(ledger.begin(), ledger.begin() + 3);
  for (std::size_t k = 1; k < runs.size(); ++k) {
    expect_particles_identical(runs[0], runs[k]);
    EXPECT_TRUE(bitwise_equal(runs[0].state, runs[k].state));
    const auto begin = ledger.begin() + static_cast<std::ptrdiff_t>(3 * k);
    EXPECT_TRUE(bitwise_equal(first, std::vector<double>(begin, begin + 3)));
  }
}

// The conjugate gradients' product runs in parallel over the rows, each row summed in the order
// Eigen's own row-major product sums it: on a system of the pressure solve's shape (a cell
// coupled to the 7 x 7 cells whose GIMP nodes it shares, G W G^T with positive weights, plus the
// storage on the diagonal; 60 x 60 cells, so the rows span many of the loop's chunks) the solution
// and the iteration count are bitwise Eigen's, on one, two and three threads.
TEST(ImplicitPorePressure, ParallelConjugateGradientsAreBitwiseEigensOwnOnAnyThreadCount) {
  constexpr int cells = 60;
  constexpr int unknowns = cells * cells;
  std::vector<Eigen::Triplet<double>> entries;
  std::uint64_t seed = 20261207;
  const auto uniform = [&seed] { // a fixed sequence on every platform (Knuth's MMIX LCG)
    seed = 6364136223846793005ULL * seed + 1442695040888963407ULL;
    return static_cast<double>(seed >> 11) * 0x1.0p-53;
  };
  for (int i = 0; i < unknowns; ++i) {
    const int ci = i % cells;
    const int cj = i / cells;
    for (int dj = -3; dj <= 3; ++dj) {
      for (int di = -3; di <= 3; ++di) {
        const int ni = ci + di;
        const int nj = cj + dj;
        const int k = ni + cells * nj;
        if (ni < 0 || ni >= cells || nj < 0 || nj >= cells || k <= i) {
          continue;
        }
        const double coupling = -(0.1 + uniform()) / (1.0 + di * di + dj * dj);
        entries.emplace_back(i, k, coupling);
        entries.emplace_back(k, i, coupling);
        entries.emplace_back(i, i, -coupling); // diagonally dominant: positive definite
        entries.emplace_back(k, k, -coupling);
      }
    }
    entries.emplace_back(i, i, 1e-3 * (1.0 + uniform())); // the storage
  }
  Eigen::SparseMatrix<double> a(unknowns, unknowns);
  a.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd b(unknowns);
  for (int i = 0; i < unknowns; ++i) {
    b[i] = uniform() - 0.5;
  }

  int iterations = 0;
  const Eigen::VectorXd expected = eigen_conjugate_gradients(a, b, 1e-10, iterations);
  ASSERT_GT(iterations, 20); // enough products for a summation order to show

  for (const int threads : compared_thread_counts()) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(unknowns);
    passes::ConjugateGradientResult result;
    with_threads(threads, [&] { result = passes::solve_conjugate_gradients(a, b, x, 1e-10); });
    EXPECT_TRUE(result.converged) << threads << " threads";
    EXPECT_EQ(result.iterations, iterations) << threads << " threads";
    EXPECT_EQ(std::memcmp(x.data(), expected.data(), sizeof(double) * unknowns), 0)
        << threads << " threads: max difference " << (x - expected).cwiseAbs().maxCoeff();
  }
}

// The soil at a structure's wall moves with the pressure: held there for the contact's sake (as it
// was), it took the water's stiffness explicitly, and in the coarse CPT chamber, undrained, the
// pore water under the cone's tip ran away in tension (37 MPa by the seventh step, the run stopped
// with a Courant number of 1.3 at the skeleton's step). Over the chamber's first 50 steps (1.8 ms)
// the step at Courant 0.8 holds and the excess pore pressure stays below the 50 kPa surcharge:
// measured 32 kPa under the cone's tip, where the explicit water's transient reaches 38 kPa at the
// same time (the soil beside the rod, free of the surcharge, moves at first).
TEST(ImplicitPorePressure, SoilAtAStructuresWallStaysStable) {
  const std::string text =
      replaced(read_text(source / "cases/cpt/cpt_coarse.toml"), "density = 1656.25",
               "density = 1656.25\ndrainage = \"undrained\"\ngrain_density = 2650.0");
  CaseRun run(replaced(text, "courant_number = 0.8",
                       "courant_number = 0.8\nimplicit_pore_pressure = true\n"
                       "cell_mean_pore_pressure = true"));
  apply_k0(*run.scene, run.spec, run.spec.phases[0]);
  // The step from the K0 state, as a run's first phase starts from it.
  run.solver = std::make_unique<ExplicitSolver>(
      *run.scene, phase_settings(run.spec, run.spec.phases[0]), run.log);
  for (int k = 0; k < 50; ++k) {
    run.solver->step(std::numeric_limits<double>::infinity());
  }
  const Particles& p = run.scene->particles;
  const Material& sand = *run.scene->materials.at(0);
  const auto slot = static_cast<std::size_t>(sand.pore_pressure_index() + 1);
  double largest = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] == 0) {
      largest =
          std::max(largest, std::abs(p.state[i * static_cast<std::size_t>(p.state_stride) + slot]));
    }
  }
  EXPECT_LT(largest, 50e3) << run.solver->time();
  std::cout << "largest excess pore pressure after 50 steps (" << run.solver->time()
            << " s): " << largest << " Pa\n";
}

// Darcy's drag is booked at the velocities the pore pressure's work is booked at, the corrected
// ones. Booked at the predictor's, driven by p^n alone, it took in a relative flow that the remap
// and the correction do not keep (and whose pressure work is booked nowhere): in the coarse CPT
// chamber, coupled at k = 1e-4 m/s, the ledger was 3.1 % off at 1 mm of penetration (16 % at its
// worst, in the first centimetre), 0.41 % with the drag at the corrected velocities; the
// explicit water closes it to 0.21 % there, with a seventh of the step. Within 1 %.
TEST(ImplicitPorePressure, CoupledConeLedgerBooksTheDragWhereThePressureWorks) {
  const auto directory = fresh_directory("implicit_cone_ledger");
  RunOptions options;
  options.case_path = (source / "cases/cpt/cpt_coarse.toml").string();
  options.output_directory = directory.string();
  options.overrides =
      coupled_sand_with({"phases.1.mass_scaling=1.0", "phases.1.stop_at.penetration=0.001",
                         "output.snapshot_penetrations=[]"});
  std::ostringstream out, err;
  ASSERT_EQ(run_case(options, out, err), 0) << err.str();
  Hdf5File history((directory / "history.h5").string(), Hdf5File::Mode::read);
  const std::vector<double> residual = history.read_doubles("/energy/relative_residual");
  const std::vector<double> drag = history.read_doubles("/energy/drag");
  ASSERT_FALSE(residual.empty());
  EXPECT_GT(drag.back(), 0.0);
  double worst = 0.0;
  for (const double r : residual) {
    worst = std::max(worst, std::abs(r));
  }
  EXPECT_LT(worst, 0.01);
  std::cout << "coupled cone to 1 mm: worst ledger residual " << worst << '\n';
}

// [solver] hold_wall_cells (docs/saturated.md, "Holding the wall cells"): the quick jacked pile in
// saturated sand at k = 1e-4 m/s with the 100 kPa cut-off, whose water cavitates in the tip's wall
// cells from about 2 cm on. Capped after the solve, the velocities take suction the capped stress
// does not keep, and at 4 cm the ledger is 0.722 % off; held in the solve, 0.244 % (measured at
// 57b859a; without the cut-off it closes to 0.02 to 0.05 % in the quick runs). Within 0.4 %: a
// third of the way from the held run's to the capped one's, so that capping fails it. Held is the
// default: the run sets nothing.
TEST(ImplicitPorePressure, HeldWallCellsCloseTheJackedPilesLedger) {
  const auto directory = fresh_directory("implicit_held_wall_cells");
  RunOptions options;
  options.case_path = (source / "cases/monopile/jacked_quick.toml").string();
  options.output_directory = directory.string();
  options.overrides = coupled_sand_with(
      {"water.cavitation_stress=100e3", "phases.installation.stop_at.penetration=0.04"});
  std::ostringstream out, err;
  ASSERT_EQ(run_case(options, out, err), 0) << err.str();
  Hdf5File history((directory / "history.h5").string(), Hdf5File::Mode::read);
  const std::vector<double> residual = history.read_doubles("/energy/relative_residual");
  ASSERT_FALSE(residual.empty());
  EXPECT_LT(std::abs(residual.back()), 0.004);
  std::cout << "jacked to 4 cm, wall cells held: ledger residual " << residual.back() << '\n';
}

// `mpile check` says the pore pressure is solved on the grid and gives the skeleton's step:
// 0.8 h / sqrt(M' / rho_sat) = 1.631e-4 s for the wave column (4 digits, as printed), against the
// undrained P-wave's 2.373e-5 s without it.
TEST(ImplicitPorePressure, CheckSaysTheStepFollowsTheSkeleton) {
  const auto directory = fresh_directory("implicit_check");
  const auto path = directory / "case.toml";
  for (const bool on : {true, false}) {
    const std::string text = saturated_wave_column("drainage = \"undrained\"");
    std::ofstream(path) << (on ? implicit(text) : text);
    RunOptions options;
    options.case_path = path.string();
    std::ostringstream out, err;
    ASSERT_EQ(check_case(options, out, err), 0) << err.str();
    const double n = 1.0 - 1600.0 / 2650.0;
    const double modulus = 100e6 * 0.75 / (1.25 * 0.5) + (on ? 0.0 : 2.2e9 / n);
    std::ostringstream step;
    step << "time step: " << std::setprecision(4)
         << 0.8 * 0.05 / std::sqrt(modulus / (1600.0 + n * 1000.0)) << " s";
    EXPECT_NE(out.str().find(step.str()), std::string::npos) << step.str() << "\n" << out.str();
    EXPECT_EQ(out.str().find("its pore pressure solved on the grid") != std::string::npos, on)
        << out.str();
  }
}

// hold_wall_cells acts in the implicit pore pressure's solve; without it the key would do nothing,
// held or capped.
TEST(ImplicitPorePressure, HoldingWallCellsWithoutItIsRefusedAtTheKey) {
  for (const char* value : {"true", "false"}) {
    const std::string text = saturated_wave_column("drainage = \"undrained\"") +
                             "[solver]\nhold_wall_cells = " + value + "\n";
    std::string message = "no error";
    try {
      CaseRun run(text);
    } catch (const CaseError& e) {
      message = e.what();
    }
    const auto line =
        1 + std::count(text.begin(), text.begin() + static_cast<long>(text.find("hold_wall_cells")),
                       '\n');
    EXPECT_NE(
        message.find("test.toml:" + std::to_string(line) +
                     ": solver.hold_wall_cells: the wall cells are held or capped in the "
                     "implicit pore pressure's solve: it needs implicit_pore_pressure = true; "
                     "remove it"),
        std::string::npos)
        << message;
  }
}

// The refusals name the file, the line and the key: USL (the solve corrects the remapped
// velocities), a scene without pore water, and absorbing faces (their dashpots would take the
// skeleton's impedance: a saturated pulse came back and 15 % of its energy went unbooked).
TEST(ImplicitPorePressure, IsRefusedWhereItCannotWork) {
  const struct {
    std::string text;
    const char* expected;
  } bad[] = {
      {implicit(saturated_wave_column("drainage = \"undrained\"")) + "scheme = \"usl\"\n",
       "needs scheme = \"musl\""},
      {implicit(saturated_wave_column("")), "no material is undrained or coupled"},
      {implicit(replaced(read_text(source / "cases/verification/absorbing_column.toml"),
                         "density = 2000.0", "density = 2000.0\ndrainage = \"undrained\"")),
       "absorbing faces are not built for the implicit pore pressure"},
  };
  for (const auto& b : bad) {
    std::string message = "no error";
    try {
      CaseRun run(b.text);
    } catch (const CaseError& e) {
      message = e.what();
    }
    EXPECT_NE(message.find(b.expected), std::string::npos) << message;
    const auto at = b.text.find("implicit_pore_pressure");
    const auto line = 1 + std::count(b.text.begin(), b.text.begin() + static_cast<long>(at), '\n');
    EXPECT_NE(message.find("test.toml:" + std::to_string(line) + ": solver.implicit_pore_pressure"),
              std::string::npos)
        << message;
  }
}

} // namespace
} // namespace mpile
