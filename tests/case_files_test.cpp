// Every case file shipped under cases/ must stay valid, every element-test file under
// cases/element_tests/ must run, and a verification case file must reproduce its reference when run
// through the whole command path (reader, builder, phases, checkpoint).
#include "app/element_test_command.hpp"
#include "app/run_command.hpp"
#include "cases/case_spec.hpp"
#include "cases/sweep_file.hpp"
#include "io/hdf5_file.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

namespace mpile {
namespace {

const std::filesystem::path source = MPILE_SOURCE_DIR;

// Element-test files (cases/element_tests/) are not case files; they are run below instead.
bool is_element_test(const std::filesystem::path& path) {
  return path.parent_path().filename() == "element_tests";
}

// Sweep files (cases/sweeps/) describe studies of cases: checked with the sweep reader below.
bool is_sweep(const std::filesystem::path& path) {
  return path.parent_path().filename() == "sweeps";
}

// Base files (cases/*/base/) are parts of cases: read through the cases that name them.
bool is_base(const std::filesystem::path& path) {
  return path.parent_path().filename() == "base";
}

TEST(CaseFiles, EveryShippedCaseFileIsValid) {
  int files = 0;
  std::set<std::filesystem::path> bases, used;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(source / "cases")) {
    if (entry.path().extension() != ".toml" || is_element_test(entry.path()) ||
        is_sweep(entry.path())) {
      continue;
    }
    if (is_base(entry.path())) {
      bases.insert(std::filesystem::canonical(entry.path()));
      continue;
    }
    ++files;
    RunOptions options;
    options.case_path = entry.path().string();
    std::ostringstream out, err;
    EXPECT_EQ(check_case(options, out, err), exit_success) << entry.path() << ": " << err.str();
    for (const std::string& base : read_case_file(entry.path().string()).bases) {
      // A case may build on another case (cases/monopile/capacity/); only base files must all
      // be used.
      if (is_base(base)) {
        used.insert(std::filesystem::canonical(base));
      }
    }
  }
  EXPECT_GE(files, 8);
  // No base file lies unused (it would go unchecked).
  EXPECT_EQ(bases, used);
  EXPECT_EQ(bases.size(), 6u);
}

// Tests that edit a monopile case's text use flat copies (tests/data/); the shipped cases build
// on base files. Equal resolved trees mean the copies are the very cases that ship.
TEST(CaseFiles, EveryShippedSweepFileIsValid) {
  // Read as `mpile sweep` reads it: the sweep file, then every variant's case with its values.
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(source / "cases/sweeps")) {
    if (entry.path().extension() == ".toml") {
      ++files;
      EXPECT_NO_THROW(validate_sweep(read_sweep_file(entry.path().string()))) << entry.path();
    }
  }
  EXPECT_GE(files, 1);
}

TEST(CaseFiles, TheMonopileCasesComposeToTheirFlatCopies) {
  for (const char* name : {"gdp_quick", "gdp_paper", "jacked_quick"}) {
    const CaseSpec shipped =
        read_case_file((source / "cases/monopile" / (std::string(name) + ".toml")).string());
    const CaseSpec flat =
        read_case_file((source / "tests/data" / (std::string(name) + "_flat.toml")).string());
    EXPECT_FALSE(shipped.bases.empty()) << name;
    EXPECT_EQ(shipped.resolved, flat.resolved) << name;
  }
}

// `check` says how each phase ends, and bounds the run by the phases' durations.
TEST(CaseFiles, CheckSaysHowEachPhaseStops) {
  RunOptions options;
  options.case_path = (source / "cases/monopile/impact_quick.toml").string();
  options.overrides = {"phases.1.duration=3.0"};
  std::ostringstream out, err;
  ASSERT_EQ(check_case(options, out, err), exit_success) << err.str();
  EXPECT_NE(
      out.str().find("phases: 2, 5 s of simulated time at most\n"
                     "  geostatic: at equilibrium (out-of-balance force and kinetic energy "
                     "ratios below 0.01), else after 2 s\n"
                     "  installation: at pile penetration 0.1 m once at rest, else after 3 s\n"
                     "steps at most: "),
      std::string::npos)
      << out.str();
}

// `check --pilot` runs the case through the run's own path in a temporary directory; a case the
// pilot finishes is its own measurement, phase by phase, and the directory is removed.
TEST(CaseFiles, CheckWithAPilotRunEstimatesTheRunTime) {
  RunOptions options;
  options.case_path = (source / "cases/verification/single_point.toml").string();
  options.pilot_seconds = 60.0;
  options.threads = 1;
  std::ostringstream out, err;
  ASSERT_EQ(check_case(options, out, err), exit_success) << err.str();
  const std::string text = out.str();
  EXPECT_NE(text.find(" (the whole run)\nestimated run time: "), std::string::npos) << text;
  EXPECT_NE(text.find(", measured in the pilot ("), std::string::npos) << text;
  EXPECT_EQ(text.find("at most "), std::string::npos) << text;
  EXPECT_NE(text.find("\n  start-up and final output: "), std::string::npos) << text;
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::temp_directory_path() /
                                       ("mpile-pilot-" + std::to_string(::getpid()))));
}

TEST(CaseFiles, EveryElementTestFileRuns) {
  const auto directory = std::filesystem::temp_directory_path() / "mpile_test_element_files";
  std::filesystem::create_directories(directory);
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(source / "cases/element_tests")) {
    if (entry.path().extension() != ".toml") {
      continue;
    }
    ++files;
    ElementTestOptions options;
    options.file = entry.path().string();
    options.csv = (directory / (entry.path().stem().string() + ".csv")).string();
    std::ostringstream out, err;
    EXPECT_EQ(element_test_command(options, out, err), exit_success)
        << entry.path() << ": " << err.str();
    EXPECT_TRUE(std::filesystem::exists(options.csv)) << options.csv;
  }
  EXPECT_GE(files, 1);
}

TEST(CaseFiles, LameCylinderCaseFileMatchesTheClosedForm) {
  const auto directory = std::filesystem::temp_directory_path() / "mpile_test_lame_file";
  std::filesystem::remove_all(directory);
  RunOptions options;
  options.case_path = (source / "cases/verification/lame_cylinder.toml").string();
  options.output_directory = directory.string();
  std::ostringstream out, err;
  ASSERT_EQ(run_case(options, out, err), exit_success) << err.str();
  Hdf5File checkpoint((directory / "checkpoint.h5").string(), Hdf5File::Mode::read);
  const auto r0 = checkpoint.read_doubles("/particles/r0");
  const auto r = checkpoint.read_doubles("/particles/r");
  const auto stress = checkpoint.read_doubles("/particles/stress");
  // u_r = (1 + nu)/E [(1 - 2 nu) A r + B / r], sigma_thth = A + B / r^2 (docs/verification.md V3).
  const double A = 12.5e3, B = 4.5e3, nu = 0.3, E = 100e6;
  double worst_u = 0.0, worst_hoop = 0.0;
  for (std::size_t i = 0; i < r0.size(); ++i) {
    const double exact_u = (1.0 + nu) / E * ((1.0 - 2.0 * nu) * A * r0[i] + B / r0[i]);
    worst_u = std::max(worst_u, std::abs((r[i] - r0[i]) / exact_u - 1.0));
    if (r0[i] >= 0.3 && r0[i] <= 0.5) {
      const double exact_hoop = A + B / (r0[i] * r0[i]);
      worst_hoop = std::max(worst_hoop, std::abs(stress[6 * i + 2] / exact_hoop - 1.0));
    }
  }
  // V3 tolerance 2 %; measured 0.26 % (u_r) and 1.2 % (hoop stress, constant strain per cell).
  EXPECT_LT(worst_u, 0.02);
  EXPECT_LT(worst_hoop, 0.02);
}

} // namespace
} // namespace mpile
