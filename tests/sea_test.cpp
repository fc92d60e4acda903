// The sea above a saturated seabed and the pore water's cavitation ([water]; physics.md section
// 9c). The sea's pressure on the seabed is uniform over the soil and its free surfaces, so it moves
// nothing: the soil must run bitwise as without it, the outputs add it to every pore pressure and
// total stress, and a structure through the seabed takes it on its cross-section there. Past the
// cavitation stress the water carries no more tension, and a tension wave then splits in two with
// speeds and amplitudes that follow from the two phases' stiffnesses alone.
#include "app/run_command.hpp"
#include "cases/case_error.hpp"
#include "io/monitor_points.hpp"
#include "tests/bitwise.hpp"
#include "tests/case_run.hpp"
#include "tests/saturated_column.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace mpile {
namespace {

const std::string undrained_sand =
    "type = \"mohr_coulomb\"\ndrainage = \"undrained\"\nyoung_modulus = 50e6\n"
    "poisson_ratio = 0.3\ndensity = 1600.0\ncohesion = 0.0\nfriction_angle = 35.0\n";

std::unique_ptr<CaseRun> column_at_rest(const std::string& text, double until) {
  auto run = std::make_unique<CaseRun>(text);
  apply_k0(*run->scene, run->spec, run->spec.phases[0]);
  run->solver = std::make_unique<ExplicitSolver>(
      *run->scene, phase_settings(run->spec, run->spec.phases[0]), run->log);
  run->solver->advance_to(until);
  return run;
}

double monitored(const Scene& scene, std::size_t i, const std::string& quantity) {
  const auto names = monitor_quantities(scene, scene.particles.material[i]);
  const auto at = std::find_if(names.begin(), names.end(),
                               [&](const MonitorQuantity& q) { return q.name == quantity; });
  EXPECT_NE(at, names.end()) << quantity;
  return monitor_values(scene, scene.particles.id[i],
                        scene.particles.material[i])[static_cast<std::size_t>(at - names.begin())];
}

// 20 m of sea over a 10 m saturated column at rest: the column runs bitwise as without the sea
// (its pore pressures are kept relative to the sea's 196.2 kPa on the seabed, which pushes on the
// seabed as on every pore), and what is written is relative to the atmosphere: the pore pressure
// -rho_w g (level - y), the vertical total stress the sea's weight plus the saturated soil's. The
// particles have moved by rounding only (the column's own test: 1e-12 m/s), hence 1e-9 of the
// stresses.
TEST(Sea, AboveTheSeabedItMovesNothingAndIsAddedToWhatIsWritten) {
  const std::string text = saturated_column(10.0, 40, 0.05, undrained_sand);
  const auto dry = column_at_rest(text, 0.05);
  const auto sea = column_at_rest(text + "[water]\nlevel = 30.0\n", 0.05);
  expect_particles_identical(dry->scene->particles, sea->scene->particles);
  EXPECT_TRUE(bitwise_equal(dry->scene->particles.state, sea->scene->particles.state));
  ASSERT_TRUE(sea->spec.water.has_value());
  EXPECT_DOUBLE_EQ(sea->spec.water->column_pressure, 1000.0 * 9.81 * 20.0);

  const double n = 1.0 - 1600.0 / 2650.0;
  const double rho_sat = 1600.0 + n * 1000.0;
  const Particles& p = sea->scene->particles;
  for (std::size_t i = 0; i < p.size(); i += 7) {
    const double pore = -1000.0 * 9.81 * (30.0 - p.y[i]);
    const double vertical = -rho_sat * 9.81 * (10.0 - p.y[i]) - 1000.0 * 9.81 * 20.0;
    EXPECT_NEAR(monitored(*sea->scene, i, "pore_pressure"), pore, 1e-9 * 3e5) << i;
    EXPECT_NEAR(monitored(*sea->scene, i, "sigma_yy"), vertical, 1e-9 * 4e5) << i;
    // The excess over hydrostatic is the same whatever the sea.
    EXPECT_EQ(monitored(*sea->scene, i, "excess_pore_pressure"),
              monitored(*dry->scene, i, "excess_pore_pressure"));
  }
}

// A rigid open pile wall (r = 0.4 to 0.6 m) through the seabed of a saturated column under 20 m of
// sea: the soil's pore pressures the contact sees leave the sea's pressure out, so the body takes
// it on its cross-section at the seabed, (0.6^2 - 0.4^2) / 2 = 0.1 m^2/rad, as an uplift of
// 196.2 kPa x 0.1 = 19 620 N/rad. The pile is held (velocity 0), so the force its drive needs
// is the dry run's less the uplift, to rounding: the soil runs bitwise the same.
TEST(Sea, LiftsAPileThroughTheSeabedByItsPressureOnTheCrossSection) {
  // The grid and the pile 0.2 m taller: the pile stands through the seabed at y = 1 m.
  std::string text = replaced(spun_pile_text(20, "drainage = \"undrained\"", 0.02),
                              "y = [{ start = 0.0, end = 1.0, cells = 20 }]",
                              "y = [{ start = 0.0, end = 1.2, cells = 24 }]");
  text = replaced(text, "region = { r = [0.4, 0.6], y = [0.5, 1.0] }",
                  "region = { r = [0.4, 0.6], y = [0.5, 1.2] }");
  const auto dry = column_at_rest(text, 0.02);
  const auto sea = column_at_rest(text + "[water]\nlevel = 21.0\n", 0.02);
  const double uplift = 1000.0 * 9.81 * 20.0 * 0.1;
  const RigidBody& held = sea->scene->rigid_bodies.at(0);
  EXPECT_NEAR(held.water_load[RIGID_Y], uplift, 1e-12 * uplift);
  expect_particles_identical(dry->scene->particles, sea->scene->particles);
  const double dry_drive = dry->scene->rigid_bodies.at(0).driving[RIGID_Y];
  EXPECT_NEAR(held.driving[RIGID_Y], dry_drive - uplift, 1e-9 * uplift);
}

/// The particles' mean velocity along y with y in [from, to].
double mean_velocity(const Particles& p, double from, double to) {
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.y[i] >= from && p.y[i] <= to) {
      sum += p.v_y[i];
      ++count;
    }
  }
  return sum / count;
}

// The saturated wave column pulled down at its base at 0.01 m/s: without a cut-off the undrained
// tension wave carries the whole piston velocity at c_u = sqrt((M + K_w / n) / rho_sat) = 1 686
// m/s, its pore water in 32.6 kPa of tension. With the water cavitating at 10 kPa the wave splits:
// a precursor at c_u in which the water just reaches the cut-off, strain eps_1 = p_cav n / K_w =
// 1.80e-6 and velocity c_u eps_1 = 3.04e-3 m/s, then the skeleton alone (the water at the cut-off)
// at its own speed sqrt(M / rho_sat) = 245 m/s carrying the rest. At 12 ms the precursor has run
// 20 m and the skeleton's wave 2.9 m: between 6 and 16 m the particles move at the precursor's
// velocity (measured 0.4 % fast, both drainages; 1 % allows for the fronts' ringing, as the
// uncut wave's plateau is 0.05 % off its piston's); no pore pressure exceeds the cut-off but by
// rounding, and the ledger closes within 2 % (measured 1.1 % and 0.16 %) with the cavitation's
// dissipation booked. Undrained soil and coupled
// soil whose water cannot move against the skeleton (k = 1e-9 m/s) alike.
TEST(Sea, CavitationCapsTheWatersTensionAndSplitsTheWave) {
  const double n = 1.0 - 1600.0 / 2650.0;
  const double rho_sat = 1600.0 + n * 1000.0;
  const double m = 100e6 * 0.75 / (1.25 * 0.5);
  const double c_u = std::sqrt((m + 2.2e9 / n) / rho_sat);
  const double precursor = c_u * 10e3 * n / 2.2e9;
  for (const std::string water :
       {"drainage = \"undrained\"", "drainage = \"coupled\"\nhydraulic_conductivity = 1e-9"}) {
    SCOPED_TRACE(water);
    const std::string pulled =
        replaced(saturated_wave_column(water), "velocity_y = 0.01", "velocity_y = -0.01");
    CaseRun free(pulled);
    free.solver->advance_to(0.012);
    EXPECT_NEAR(mean_velocity(free.scene->particles, 6.0, 16.0), -0.01, 0.01 * 0.01);

    CaseRun cut(pulled + "[water]\ncavitation_stress = 10e3\n");
    cut.solver->advance_to(0.012);
    const Particles& p = cut.scene->particles;
    EXPECT_NEAR(mean_velocity(p, 6.0, 16.0), -precursor, 0.01 * precursor);
    const auto slot = static_cast<std::size_t>(cut.scene->materials[0]->pore_pressure_index());
    double highest = -1e300;
    for (std::size_t i = 0; i < p.size(); ++i) {
      highest = std::max(highest, p.state[i * static_cast<std::size_t>(p.state_stride) + slot]);
    }
    EXPECT_NEAR(highest, 10e3, 1e-9 * 10e3);
    EXPECT_LT(std::abs(cut.solver->energy_balance().relative_residual), 0.02);
    std::cout << water.substr(0, water.find('\n')) << ": precursor " << -mean_velocity(p, 6.0, 16.0)
              << " m/s against " << precursor << ", residual "
              << cut.solver->energy_balance().relative_residual << '\n';
  }
}

// `mpile check` says what the sea does: its pressure on the seabed (20 m of sea, 196.2 kPa) and the
// cut-off.
TEST(Sea, CheckPrintsTheSeasPressureAndTheCutOff) {
  const auto directory = fresh_directory("sea_check");
  const auto path = directory / "case.toml";
  std::ofstream(path) << saturated_column(2.0, 8, 0.01, undrained_sand)
                      << "[water]\nlevel = 22.0\ncavitation_stress = 100e3\n";
  RunOptions options;
  options.case_path = path.string();
  std::ostringstream out, err;
  ASSERT_EQ(check_case(options, out, err), 0) << err.str();
  EXPECT_NE(
      out.str().find("sea: level 22 m over the seabed at 2 m, its pressure there 1.962e+05 Pa"),
      std::string::npos)
      << out.str();
  EXPECT_NE(out.str().find("cavitates at 1e+05 Pa of tension"), std::string::npos) << out.str();
}

// A water table inside the soil ([water] table): 2 m of dry sand (1600 kg/m^3) over 3 m of the same
// sand saturated (n = 1 - 1600 / 2650, rho_sat = 1996 kg/m^3), coupled, the table at the
// boundary. The K0 procedure weighs both layers: sigma_yy = -(rho_d g 2 m + rho_sat g (3 m - y))
// below the table, the pore water -rho_w g (3 m - y), and nothing in the dry layer's pores. Both
// to rounding (the closed form's sums are the procedure's). The column then stays at rest (its
// velocities and its water's at rounding). Without the table the saturated layer took its water
// hydrostatic from its own K0 surface, the ground's, 2 m too high: 19.6 kPa more pressure at
// every depth, which the table's start must not carry.
TEST(Sea, AWaterTableInsideTheSoilStartsLayeredAndTheColumnStaysAtRest) {
  const std::string layer =
      "type = \"linear_elastic\"\nyoung_modulus = 50e6\npoisson_ratio = 0.3\ndensity = 1600.0\n";
  const std::string text = std::string("title = \"water table\"\n[grid]\n") +
                           "r = [{ start = 0.0, end = 0.5, cells = 2 }]\n"
                           "y = [{ start = 0.0, end = 5.0, cells = 20 }]\n"
                           "[materials.dry]\n" +
                           layer + "[materials.wet]\n" + layer +
                           "drainage = \"coupled\"\nhydraulic_conductivity = 1e-3\n"
                           "[[bodies]]\nname = \"above\"\nmaterial = \"dry\"\n"
                           "region = { r = [0.0, 0.5], y = [3.0, 5.0] }\n"
                           "[[bodies]]\nname = \"below\"\nmaterial = \"wet\"\n"
                           "region = { r = [0.0, 0.5], y = [0.0, 3.0] }\n"
                           "[boundaries]\nr_max = \"roller\"\ny_min = \"fixed\"\n"
                           "[solver]\ngravity = [0.0, -9.81]\n[water]\ntable = 3.0\n"
                           "[[phases]]\nname = \"rest\"\nduration = 0.5\n"
                           "k0 = [{ body = \"above\", surface = 5.0, k0 = 0.5 }, "
                           "{ body = \"below\", surface = 5.0, k0 = 0.5 }]\n";
  auto run = column_at_rest(text, 0.0);
  const Particles& p = run->scene->particles;
  const double g = 9.81, rho_d = 1600.0, rho_w = 1000.0;
  const double rho_sat = rho_d + (1.0 - rho_d / 2650.0) * rho_w;
  const auto stride = static_cast<std::size_t>(p.state_stride);
  double worst_stress = 0.0, worst_pore = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool below = p.y[i] < 3.0;
    const double vertical =
        below ? -(rho_d * g * 2.0 + rho_sat * g * (3.0 - p.y[i])) : -rho_d * g * (5.0 - p.y[i]);
    worst_stress = std::max(worst_stress, std::abs(p.stress[i][YY] - vertical));
    if (below) {
      const Material& wet = *run->scene->materials[p.material[i]];
      const double pore = p.state[i * stride + static_cast<std::size_t>(wet.pore_pressure_index())];
      worst_pore = std::max(worst_pore, std::abs(pore + rho_w * g * (3.0 - p.y[i])));
    }
  }
  EXPECT_LT(worst_stress, 1e-9 * rho_sat * g * 5.0) << "Pa";
  EXPECT_LT(worst_pore, 1e-9 * rho_w * g * 3.0) << "Pa";
  run->solver->advance_to(0.5);
  double fastest = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    fastest = std::max({fastest, std::abs(p.v_r[i]), std::abs(p.v_y[i])});
  }
  EXPECT_LT(fastest, 1e-12) << "m/s after 0.5 s at rest";
  // No note of dry soil over saturated soil: the table says where the water stands.
  for (const CaseWarning& w : run->spec.warnings) {
    EXPECT_EQ(w.text.find("rests on saturated"), std::string::npos) << w.text;
  }
}

// `mpile check` says where a water table stands instead of a sea.
TEST(Sea, CheckPrintsTheWaterTable) {
  const auto directory = fresh_directory("water_table_check");
  const auto path = directory / "case.toml";
  std::ofstream(path) << saturated_column(2.0, 8, 0.01, undrained_sand) << "[water]\ntable = 2.0\n";
  RunOptions options;
  options.case_path = path.string();
  std::ostringstream out, err;
  ASSERT_EQ(check_case(options, out, err), 0) << err.str();
  EXPECT_NE(out.str().find("water table: at 2 m, the soil dry above it"), std::string::npos)
      << out.str();
  EXPECT_EQ(out.str().find("sea: level"), std::string::npos) << out.str();
}

// Each refusal names the file, the line and the key.
TEST(Sea, BadWaterTableIsRefusedAtItsLine) {
  const std::string column = saturated_column(10.0, 20, 0.01, undrained_sand);
  struct Bad {
    const char* what;
    std::string text;
    const char* expected;
    const char* key;
  };
  const std::vector<Bad> bad{
      {"below the grid", column + "[water]\nlevel = -1.0\n", "lies below the grid", "level ="},
      {"below the seabed", column + "[water]\nlevel = 9.0\n", "lies below the seabed", "level ="},
      // An overflowing sea: an infinite pressure on the seabed, then inf and NaN in every
      // reported stress.
      {"an overflowing sea", column + "[water]\nlevel = 1e308\n", "a pressure of inf Pa",
       "level ="},
      {"a level in mm", column + "[water]\nlevel = 30000.0\n", "(a length in mm?)", "level ="},
      {"negative cavitation stress", column + "[water]\ncavitation_stress = -1.0\n", "must be >= 0",
       "cavitation_stress ="},
      {"no saturated soil",
       replaced(column, "drainage = \"undrained\"\n", "") + "[water]\nlevel = 12.0\n",
       "no material holds pore water", "level ="},
      {"a table and a sea", column + "[water]\nlevel = 12.0\ntable = 8.0\n",
       "a water table inside the soil and a sea's level above it exclude each other", "table ="},
      {"saturated above the table", column + "[water]\ntable = 8.0\n",
       "body 'column' is saturated but reaches y = 10 m, above the table at 8 m", "table ="},
      {"dry below the table",
       replaced(column, "drainage = \"undrained\"\n", "") + "[materials.wet]\n" + undrained_sand +
           "[water]\ntable = 12.0\n",
       "body 'column' is dry but reaches y = 0 m, below the table at 12 m", "table ="},
      {"no K0 procedure",
       replaced(column, "k0 = [{ body = \"column\", surface = 10, k0 = 0.5 }]\n", "") +
           "[water]\nlevel = 12.0\n",
       "no phase gives it a K0 procedure", "level ="},
  };
  for (const Bad& b : bad) {
    std::string message = "no error";
    try {
      CaseRun run(b.text);
    } catch (const CaseError& e) {
      message = e.what();
    }
    EXPECT_NE(message.find(b.expected), std::string::npos) << b.what << ": " << message;
    const auto at = b.text.find(b.key);
    const auto line = 1 + std::count(b.text.begin(), b.text.begin() + static_cast<long>(at), '\n');
    EXPECT_NE(message.find("test.toml:" + std::to_string(line) + ":"), std::string::npos)
        << b.what << ": " << message;
  }
}

} // namespace
} // namespace mpile
