// The element-test driver: linear elasticity along the laboratory paths must give the elastic
// moduli exactly, Mohr-Coulomb must reach its closed-form failure states, and bad input must be
// rejected with file, line and key (exit status 2), as case files are.
#include "app/element_test_command.hpp"
#include "app/run_command.hpp"
#include "cases/case_error.hpp"
#include "cases/element_test_file.hpp"
#include "engine/materials/material_registry.hpp"
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

namespace mpile {
namespace {

int element_line_of(const std::string& text, const std::string& needle) {
  const auto at_position = text.find(needle);
  return at_position == std::string::npos
             ? -1
             : 1 + static_cast<int>(std::count(
                       text.begin(), text.begin() + static_cast<long>(at_position), '\n'));
}

/// What the element-test command did with `text`, written as `name`.toml in the temporary
/// directory (its CSV beside it): the exit status, the error output and the file's path.
struct CommandRun {
  int status;
  std::string err;
  std::string file;
};

CommandRun element_command_on(const std::string& text, const std::string& name) {
  const auto directory = std::filesystem::temp_directory_path();
  const auto file = directory / (name + ".toml");
  std::ofstream(file) << text;
  ElementTestOptions options;
  options.file = file.string();
  options.csv = (directory / (name + ".csv")).string();
  std::ostringstream out, err;
  const int status = element_test_command(options, out, err);
  return {status, err.str(), file.string()};
}

ElementTestTable run_element_text(const std::string& text) {
  return run_element_test(read_element_test_text(text, "test.toml"));
}

double at(const ElementTestTable& table, std::size_t row, const std::string& column) {
  return table.rows.at(row).at(table.column(column));
}

std::string linear_elastic(const std::string& initial, const std::string& path) {
  return "[material]\ntype = \"linear_elastic\"\nyoung_modulus = 20e6\npoisson_ratio = 0.3\n"
         "density = 1800.0\n\n[initial_stress]\n" +
         initial + "\n\n[path]\n" + path + "\n";
}

// Under stress control the driver meets the target to 1e-10 of the stress; for a linear material
// its Newton step is exact up to rounding, so moduli come out to rounding (1e-12 measured); 1e-9
// leaves room for the rounding of strain sums over a hundred increments.
constexpr double exact = 1e-9;

TEST(ElementTest, LinearElasticOedometerGivesTheConstrainedModulus) {
  const ElementTestTable t = run_element_text(
      linear_elastic("vertical = 50e3\nlateral = 25e3",
                     "type = \"oedometer\"\nvertical_stress = [200e3, 100e3]\nincrements = 50"));
  ASSERT_EQ(t.rows.size(), 101u);
  const double E = 20e6, nu = 0.3;
  const double oedometer = E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)); // 26.92 MPa
  double worst = 0.0;
  for (std::size_t k = 1; k < t.rows.size(); ++k) {
    const double modulus = (at(t, k, "sigma_1") - at(t, k - 1, "sigma_1")) /
                           (at(t, k, "eps_1") - at(t, k - 1, "eps_1"));
    worst = std::max(worst, std::abs(modulus / oedometer - 1.0));
    EXPECT_EQ(at(t, k, "eps_v"), at(t, k, "eps_1")); // no lateral strain
    // lateral stress changes by nu / (1 - nu) of the vertical one
    const double lateral = (at(t, k, "sigma_3") - 25e3) / (at(t, k, "sigma_1") - 50e3);
    EXPECT_NEAR(lateral, nu / (1.0 - nu), exact);
  }
  EXPECT_LT(worst, exact);
  EXPECT_NEAR(at(t, 50, "sigma_1"), 200e3, 1e-10 * 200e3);
  EXPECT_NEAR(at(t, 100, "sigma_1"), 100e3, 1e-10 * 200e3);
  std::cout << "oedometer modulus: worst relative error " << worst << '\n';
}

TEST(ElementTest, StressControlOfALinearMaterialNeedsAtMostTwoIterations) {
  const auto material = create_material(
      "linear_elastic", {{"young_modulus", 20e6}, {"poisson_ratio", 0.3}, {"density", 1800.0}});
  ElementPoint point(*material, Stress{-25e3, -50e3, -25e3, 0.0, 0.0, 0.0});
  int most = 0;
  for (int k = 1; k <= 50; ++k) {
    MixedIncrement increment; // oedometer: vertical stress target, no lateral strain
    increment.stress_controlled[YY] = true;
    increment.value[YY] = -50e3 - 3e3 * k;
    point.apply(increment);
    most = std::max(most, point.iterations());
  }
  EXPECT_LE(most, 2);
  EXPECT_NEAR(point.stress()[YY], -200e3, 1e-12 * 200e3);
}

TEST(ElementTest, LinearElasticTriaxialGivesYoungsModulus) {
  const ElementTestTable t = run_element_text(linear_elastic(
      "isotropic = 100e3", "type = \"triaxial\"\naxial_strain = 0.004\nincrements = 40"));
  ASSERT_EQ(t.rows.size(), 41u);
  double worst = 0.0;
  for (std::size_t k = 1; k < t.rows.size(); ++k) {
    const double modulus =
        (at(t, k, "q") - at(t, k - 1, "q")) / (at(t, k, "eps_1") - at(t, k - 1, "eps_1"));
    worst = std::max(worst, std::abs(modulus / 20e6 - 1.0));
    EXPECT_NEAR(at(t, k, "sigma_3"), 100e3, 1e-10 * 100e3);
    // eps_v = (1 - 2 nu) eps_1 under constant lateral stress
    EXPECT_NEAR(at(t, k, "eps_v"), 0.4 * at(t, k, "eps_1"), exact * at(t, k, "eps_1"));
  }
  EXPECT_LT(worst, exact);
  EXPECT_DOUBLE_EQ(at(t, 40, "eps_1"), 0.004);
  std::cout << "triaxial Young's modulus: worst relative error " << worst << '\n';
}

TEST(ElementTest, LinearElasticIsotropicGivesTheBulkModulus) {
  const ElementTestTable t = run_element_text(linear_elastic(
      "isotropic = 50e3", "type = \"isotropic\"\nmean_stress = 250e3\nincrements = 20"));
  const double bulk = 20e6 / (3.0 * (1.0 - 2.0 * 0.3));
  EXPECT_NEAR(at(t, 20, "eps_v"), 200e3 / bulk, exact * 200e3 / bulk);
  EXPECT_NEAR(at(t, 20, "eps_1"), at(t, 20, "eps_v") / 3.0, exact * 200e3 / bulk);
  EXPECT_NEAR(at(t, 20, "p"), 250e3, 1e-10 * 250e3);
  EXPECT_NEAR(at(t, 20, "q"), 0.0, 1e-9);
}

const std::string mohr_coulomb_triaxial = R"(title = "Mohr-Coulomb triaxial"
[material]
type = "mohr_coulomb"
young_modulus = 40e6
poisson_ratio = 0.3
density = 1800.0
cohesion = 5e3
friction_angle = 30.0
dilatancy_angle = 5.0

[initial_stress]
isotropic = 100e3

[path]
type = "triaxial"
axial_strain = 0.05
increments = 500
)";

TEST(ElementTest, MohrCoulombTriaxialCsvReachesTheFailureDeviator) {
  const auto directory = std::filesystem::temp_directory_path() / "mpile_element_test";
  std::filesystem::create_directories(directory);
  const auto input = directory / "triaxial.toml";
  std::ofstream(input) << mohr_coulomb_triaxial;
  ElementTestOptions options;
  options.file = input.string();
  options.csv = (directory / "triaxial.csv").string();
  std::ostringstream out, err;
  ASSERT_EQ(element_test_command(options, out, err), exit_success) << err.str();

  // Read the CSV back: the file itself must carry the result.
  std::ifstream csv(options.csv);
  std::string header, line, last;
  std::getline(csv, header);
  EXPECT_EQ(header, "eps_1,eps_v,sigma_1,sigma_3,p,q,plastic_shear_strain");
  int rows = 0;
  std::vector<double> first_values;
  while (std::getline(csv, line)) {
    last = line;
    ++rows;
  }
  EXPECT_EQ(rows, 501);
  std::vector<double> values;
  std::stringstream fields(last);
  for (std::string field; std::getline(fields, field, ',');) {
    values.push_back(std::stod(field));
  }
  ASSERT_EQ(values.size(), 7u);
  // q_f = sigma_3 (N_phi - 1) + 2 c sqrt(N_phi) with N_phi = 3: 200 + 17.32 kPa. The stress lies on
  // the surface to rounding and sigma_3 is held to 1e-10, so 1e-9 relative holds.
  const double q_failure = 100e3 * 2.0 + 2.0 * 5e3 * std::sqrt(3.0);
  EXPECT_NEAR(values[5], q_failure, 1e-9 * q_failure);
  EXPECT_NEAR(values[3], 100e3, 1e-10 * 100e3);
  EXPECT_NEAR(values[0], 0.05, 1e-15 * 500); // a sum of 500 increments
  EXPECT_GT(values[6], 0.04);                // plastic shear strain after failure at about 0.5 %
  EXPECT_NE(out.str().find("500 increments"), std::string::npos) << out.str();
  std::cout << "Mohr-Coulomb triaxial: q at 5 % = " << values[5] << " Pa, closed form " << q_failure
            << " Pa, relative difference " << std::abs(values[5] / q_failure - 1.0) << '\n';
}

TEST(ElementTest, AnOutputThatCannotBeWrittenIsNamedWithTheSystemsReason) {
  // Each gave "cannot write <path>" and no reason, or the library's "filesystem error".
  const auto directory = std::filesystem::temp_directory_path() / "mpile_element_test_out";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory / "a_directory.csv");
  std::ofstream(directory / "a_file") << "x";
  const auto input = directory / "triaxial.toml";
  std::ofstream(input) << mohr_coulomb_triaxial;
  const auto message = [&](const std::filesystem::path& csv) {
    ElementTestOptions options;
    options.file = input.string();
    options.csv = csv.string();
    std::ostringstream out, err;
    EXPECT_EQ(element_test_command(options, out, err), exit_failure) << csv;
    return err.str();
  };
  EXPECT_EQ(message(directory / "a_directory.csv"), "mpile: cannot write " +
                                                        (directory / "a_directory.csv").string() +
                                                        ": Is a directory\n");
  EXPECT_EQ(message(directory / "a_file" / "x.csv"),
            "mpile: cannot write " + (directory / "a_file" / "x.csv").string() +
                ": cannot make its directory " + (directory / "a_file").string() +
                ": Not a directory\n");
  if (geteuid() != 0) { // the superuser writes anywhere
    std::filesystem::create_directories(directory / "read_only");
    std::filesystem::permissions(directory / "read_only", std::filesystem::perms::owner_read |
                                                              std::filesystem::perms::owner_exec);
    EXPECT_EQ(message(directory / "read_only" / "x.csv"),
              "mpile: cannot write " + (directory / "read_only" / "x.csv").string() +
                  ": Permission denied\n");
  }
}

TEST(ElementTest, UnloadReloadReversesAtTheGivenDeviators) {
  std::string text = mohr_coulomb_triaxial;
  text.replace(text.find("type = \"triaxial\""), std::string("type = \"triaxial\"").size(),
               "type = \"unload_reload\"\ndeviator = 150e3\nunload_deviator = 30e3");
  text.replace(text.find("increments = 500"), std::string("increments = 500").size(),
               "increments = 1000");
  const ElementTestTable t = run_element_text(text);
  // Loading stops at the first increment at or past 150 kPa, unloading at or below 30 kPa; in
  // the elastic range an increment changes q by E d eps_1 = 40 MPa * 5e-5 = 2 kPa.
  std::size_t peak = 0, trough = 0;
  for (std::size_t k = 1; k < t.rows.size(); ++k) {
    if (peak == 0 && at(t, k, "eps_1") < at(t, k - 1, "eps_1")) {
      peak = k - 1;
    }
    if (peak > 0 && trough == 0 && at(t, k, "eps_1") > at(t, k - 1, "eps_1")) {
      trough = k - 1;
    }
  }
  ASSERT_GT(peak, 0u);
  ASSERT_GT(trough, peak);
  EXPECT_GE(at(t, peak, "q"), 150e3);
  EXPECT_LT(at(t, peak, "q"), 150e3 + 2.1e3);
  EXPECT_LE(at(t, trough, "q"), 30e3);
  EXPECT_GT(at(t, trough, "q"), 30e3 - 2.1e3);
  // Mohr-Coulomb: elastic below failure, so unloading and reloading retrace the loading line.
  EXPECT_EQ(at(t, trough, "plastic_shear_strain"), 0.0);
  const double q_failure = 100e3 * 2.0 + 2.0 * 5e3 * std::sqrt(3.0);
  EXPECT_NEAR(at(t, t.rows.size() - 1, "q"), q_failure, 1e-9 * q_failure);
  EXPECT_NEAR(at(t, t.rows.size() - 1, "eps_1"), 0.05, 1e-12);
}

TEST(ElementTest, CyclicTorsionRotatesThePrincipalAxesAndFailsOnTheEnvelope) {
  const ElementTestTable t = run_element_test(read_element_test_file(
      std::string(MPILE_SOURCE_DIR) + "/cases/element_tests/mohr_coulomb_cyclic_torsion.toml"));
  // Normal stresses held at sigma_yy = 100 kPa, sigma_rr = sigma_thth = 50 kPa; the Mohr circle of
  // the y-theta plane touches the envelope (phi = 35, c = 0) at
  //   tau_f = sqrt(((s_yy + s_tt) / 2)^2 sin^2 phi - ((s_yy - s_tt) / 2)^2).
  const double s = std::sin(35.0 * std::numbers::pi / 180.0);
  const double tau_failure = std::sqrt(75e3 * 75e3 * s * s - 25e3 * 25e3);
  double largest = 0.0, smallest = 0.0;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    largest = std::max(largest, at(t, k, "tau_ytheta"));
    smallest = std::min(smallest, at(t, k, "tau_ytheta"));
    EXPECT_NEAR(at(t, k, "sigma_1"), 100e3, 1e-10 * 100e3);
    EXPECT_NEAR(at(t, k, "p"), 200e3 / 3.0, 1e-9 * 100e3);
  }
  // The shear stress is bounded by the envelope to the driver's tolerance.
  EXPECT_NEAR(largest, tau_failure, 1e-8 * tau_failure);
  EXPECT_NEAR(smallest, -tau_failure, 1e-8 * tau_failure);
  EXPECT_GT(at(t, t.rows.size() - 1, "plastic_shear_strain"), 0.01);
}

TEST(ElementTest, StrainTableIsAppliedAsGiven) {
  const ElementTestTable t = run_element_text(linear_elastic(
      "isotropic = 100e3",
      "type = \"strain_table\"\nstrain_increments = [[1e-4, 2e-4, 3e-4, 0.0, 0.0, 0.0], "
      "[0.0, -1e-4, 0.0, 0.0, 0.0, 0.0]]\nrepeat = 3"));
  ASSERT_EQ(t.rows.size(), 7u);
  EXPECT_NEAR(at(t, 6, "eps_1"), 3.0 * (2e-4 - 1e-4), 1e-15);
  EXPECT_NEAR(at(t, 6, "eps_v"), 3.0 * 5e-4, 1e-15);
  // sigma_yy = 100 kPa + lambda eps_v + 2 mu eps_yy, compression positive
  const double lambda = 20e6 * 0.3 / (1.3 * 0.4), mu = 20e6 / 2.6;
  EXPECT_NEAR(at(t, 6, "sigma_1"), 100e3 + lambda * 1.5e-3 + 2.0 * mu * 3e-4, 1e-6);
}

TEST(ElementTest, TargetBeyondTheStrengthFailsWithTheLocation) {
  // Isotropic unloading into tension of a material with no tensile strength.
  const std::string text = R"([material]
type = "mohr_coulomb"
young_modulus = 40e6
poisson_ratio = 0.3
density = 1800.0
cohesion = 0.0
friction_angle = 30.0

[initial_stress]
isotropic = 20e3

[path]
type = "isotropic"
mean_stress = -10e3
increments = 10
)";
  const CommandRun run = element_command_on(text, "mpile_element_tension");
  EXPECT_EQ(run.status, exit_failure);
  const std::string location = run.file + ":" + std::to_string(element_line_of(text, "[path]"));
  EXPECT_NE(run.err.find(location + ": path: increment"), std::string::npos) << run.err;
}

// ---------------------------------------------------------------------------------------------
// Bad input

const std::string valid = R"(title = "reader test"

[material]
type = "mohr_coulomb"
young_modulus = 40e6
poisson_ratio = 0.3
density = 1800.0
cohesion = 5e3
friction_angle = 30.0

[initial_stress]
vertical = 100e3
lateral = 50e3

[path]
type = "triaxial"
axial_strain = 0.02
increments = 50
)";

struct BadElementInput {
  std::string from;
  std::string to;
  std::string key;
  std::string line_of; // text whose line the error must name (in the edited file)
  std::string reason;
};

TEST(ElementTest, BadInputIsRejectedWithFileLineAndKey) {
  const std::vector<BadElementInput> cases = {
      {"young_modulus = 40e6", "young_modulus = -40e6", "material.young_modulus", "young_modulus",
       "must be > 0 Pa, got -40000000"},
      {"friction_angle = 30.0", "friction_angle = 95.0", "material.friction_angle",
       "friction_angle", "[0, 90)"},
      {"cohesion = 5e3", "cohesion = 5e3\ndilatancy_angle = 40.0", "material.dilatancy_angle",
       "dilatancy_angle", "friction_angle"},
      {"cohesion = 5e3\n", "", "material.cohesion", "[material]", "missing (required)"},
      {"type = \"mohr_coulomb\"", "type = \"mohr_colomb\"", "material.type", "mohr_colomb",
       "must be \"linear_elastic\", \"mohr_coulomb\", \"hardening_soil\" or \"hypoplastic\", got "
       "\"mohr_colomb\""},
      {"density = 1800.0", "density = 1800.0\ncolour = 1", "material.colour", "colour",
       "unknown key"},
      {"lateral = 50e3", "lateral = \"50e3\"", "initial_stress.lateral", "lateral",
       "expected a number"},
      {"vertical = 100e3", "vertical = 100e3\nisotropic = 1e3", "initial_stress.isotropic",
       "isotropic", "either"},
      {"vertical = 100e3\nlateral = 50e3", "", "initial_stress", "[initial_stress]",
       "vertical = <Pa>"},
      {"vertical = 100e3", "vertical = 1000e3", "initial_stress.vertical", "vertical",
       "outside the yield surface"},
      {"type = \"triaxial\"", "type = \"triaxal\"", "path.type", "triaxal", "unknown path"},
      {"axial_strain = 0.02", "axial_strain = 0.0", "path.axial_strain", "axial_strain",
       "non-zero"},
      {"increments = 50", "increments = 0", "path.increments", "increments", "between 1"},
      {"increments = 50", "increments = 50.5", "path.increments", "increments",
       "expected an integer"},
      {"increments = 50", "increments = 50\nbogus = 1", "path.bogus", "bogus", "unknown key"},
      {"type = \"triaxial\"\naxial_strain = 0.02", "type = \"oedometer\"", "path.vertical_stress",
       "[path]", "missing (required)"},
      {"type = \"triaxial\"\naxial_strain = 0.02",
       "type = \"unload_reload\"\ndeviator = 40e3\nunload_deviator = 10e3\naxial_strain = 0.02",
       "path.deviator", "deviator", "initial deviator"},
      {"type = \"triaxial\"\naxial_strain = 0.02\nincrements = 50",
       "type = \"strain_table\"\nstrain_increments = [[0.0, 1e-3, 0.0]]", "path.strain_increments",
       "strain_increments", "rows of 6 numbers"},
      {"type = \"triaxial\"\naxial_strain = 0.02\nincrements = 50",
       "type = \"cyclic_torsion\"\nshear_strain_amplitude = 0.01\nincrements = 3",
       "path.increments", "increments", "between 4"},
      {"title = \"reader test\"", "title = \"reader test\"\nsteps = 3", "steps", "steps",
       "unknown key"},
      // Each count within its bound, their product (the increments in all) not.
      {"type = \"triaxial\"\naxial_strain = 0.02\nincrements = 50",
       "type = \"cyclic_torsion\"\nshear_strain_amplitude = 0.01\nincrements = 10000000\n"
       "cycles = 10000000",
       "path.cycles", "cycles", "the path takes 1e+14 increments in all (more than 1e+07)"},
  };
  for (const BadElementInput& c : cases) {
    std::string text = valid;
    const auto position = text.find(c.from);
    ASSERT_NE(position, std::string::npos) << c.from;
    text.replace(position, c.from.size(), c.to);
    const std::string expected =
        "test.toml:" + std::to_string(element_line_of(text, c.line_of)) + ": " + c.key + ": ";
    try {
      read_element_test_text(text, "test.toml");
      ADD_FAILURE() << "accepted: " << c.to;
    } catch (const CaseError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(expected, 0), 0u) << "expected " << expected << "\ngot " << message;
      EXPECT_NE(message.find(c.reason), std::string::npos) << message;
    }
  }
  // No [path] at all, and a file that is not TOML.
  const std::string no_path = valid.substr(0, valid.find("[path]"));
  EXPECT_THROW(read_element_test_text(no_path, "test.toml"), CaseError);
  try {
    read_element_test_text(no_path, "test.toml");
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find(": path: missing (required)"), std::string::npos);
  }
  EXPECT_THROW(read_element_test_text("[path\n", "test.toml"), CaseError);
}

TEST(ElementTest, CommandExitsWithStatusTwoOnBadInput) {
  const auto file = std::filesystem::temp_directory_path() / "mpile_element_bad.toml";
  std::string text = valid;
  text.replace(text.find("poisson_ratio = 0.3"), std::string("poisson_ratio = 0.3").size(),
               "poisson_ratio = 0.7");
  std::ofstream(file) << text;
  ElementTestOptions options;
  options.file = file.string();
  options.csv = (std::filesystem::temp_directory_path() / "mpile_element_bad.csv").string();
  std::ostringstream out, err;
  EXPECT_EQ(element_test_command(options, out, err), exit_bad_input);
  EXPECT_NE(err.str().find(file.string() + ":6: material.poisson_ratio: "), std::string::npos)
      << err.str();
  options.file = "/nonexistent/element.toml";
  std::ostringstream missing;
  EXPECT_EQ(element_test_command(options, out, missing), exit_bad_input);
  // With the system's reason, as a case file's (it gave none).
  EXPECT_NE(missing.str().find("/nonexistent/element.toml: cannot open the element-test file: No "
                               "such file or directory"),
            std::string::npos)
      << missing.str();
  // Read as a case file is: /dev/zero was read without end (a hang that filled memory), a
  // directory read as an empty file ("material: missing").
  for (const auto& [path, reason] : std::vector<std::pair<std::string, std::string>>{
           {"/dev/zero", ": is not a regular file (an element-test file is a TOML text file)"},
           {std::filesystem::temp_directory_path().string(),
            ": is a directory, not an element-test file"}}) {
    options.file = path;
    std::ostringstream refused;
    EXPECT_EQ(element_test_command(options, out, refused), exit_bad_input) << path;
    EXPECT_NE(refused.str().find(path + reason), std::string::npos) << refused.str();
  }
}

} // namespace
} // namespace mpile

namespace mpile {
namespace {

/// Linear interpolation of column y at the first row where column x reaches a value. A path that
/// ends at the value meets it only to the rounding of its stress control (1e-16 relative), so a
/// row within 1e-12 of it counts as reaching it.
double where_reaches(const ElementTestTable& t, const std::string& x, double value,
                     const std::string& y) {
  const std::size_t cx = t.column(x), cy = t.column(y);
  for (std::size_t k = 1; k < t.rows.size(); ++k) {
    if (t.rows[k][cx] >= value * (1.0 - 1e-12)) {
      const double w = (value - t.rows[k - 1][cx]) / (t.rows[k][cx] - t.rows[k - 1][cx]);
      return t.rows[k - 1][cy] + w * (t.rows[k][cy] - t.rows[k - 1][cy]);
    }
  }
  return std::nan("");
}

// The shipped Hardening Soil element tests reproduce hardening_soil.md section 3 through the tool
// a user runs (tolerances as suggested there: 0.5 % on strains, K0 within 0.002).
TEST(ElementTest, HardeningSoilTriaxialFileReproducesTheReferenceHyperbola) {
  const ElementTestTable t = run_element_test(read_element_test_file(
      std::string(MPILE_SOURCE_DIR) + "/cases/element_tests/hardening_soil_triaxial.toml"));
  const double qf = 311.197e3;
  EXPECT_NEAR(where_reaches(t, "q", 0.5 * qf, "eps_1") * 100, 0.3536, 0.005 * 0.3536);
  EXPECT_NEAR(where_reaches(t, "q", 0.9 * qf, "eps_1") * 100, 1.9167, 0.005 * 1.9167);
  EXPECT_NEAR(where_reaches(t, "q", 0.5 * qf, "eps_v") * 100, 0.0707, 0.005 * 0.0707);
  EXPECT_NEAR(t.rows.back()[t.column("q")], qf, 1e-3 * qf);
}

TEST(ElementTest, HardeningSoilOedometerFileGivesK0ncAndTheStrains) {
  const ElementTestTable t = run_element_test(read_element_test_file(
      std::string(MPILE_SOURCE_DIR) + "/cases/element_tests/hardening_soil_oedometer.toml"));
  const double rows[][2] = {{50e3, 0.2597}, {100e3, 0.3915}, {200e3, 0.5819}};
  for (const auto& row : rows) {
    EXPECT_NEAR(where_reaches(t, "sigma_1", row[0], "eps_1") * 100, row[1], 0.005 * row[1]);
    EXPECT_NEAR(where_reaches(t, "sigma_1", row[0], "sigma_3") / row[0], 0.5, 0.002);
  }
}

// A stiffness near the largest double (eur_ref = 1e308, a fuzzed mutant) overflows Hardening
// Soil's update: the path ran 27 s and wrote NaN stresses with exit status 0. It stops at the
// first increment, exit 1, naming it.
TEST(ElementTest, AStressThatIsNotFiniteStopsThePathNamingTheIncrement) {
  const std::string mutant =
      replaced(read_text(source / "cases/element_tests/hardening_soil_triaxial.toml"),
               "eur_ref = 132e6", "eur_ref = 1e308");
  const CommandRun run = element_command_on(mutant, "mpile_element_overflow");
  EXPECT_EQ(run.status, exit_failure);
  EXPECT_NE(run.err.find(": path: increment 1: the stress is not finite"), std::string::npos)
      << run.err;
}

} // namespace
} // namespace mpile
