// The command line's own checks, through the program itself.
#include "tests/run_program.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace mpile {
namespace {

TEST(CommandLine, APilotOfNanOrInfiniteSecondsIsRefused) {
  // --pilot nan passed CLI::PositiveNumber (no comparison with nan is true) and `check` then ran
  // no pilot and exited 0 without a word; inf was refused naming the largest double.
  const auto directory = fresh_directory("pilot_seconds");
  const std::string path = (source / "cases/verification/single_point.toml").string();
  for (const std::string seconds : {"nan", "inf", "-nan", "0", "-1", "2s"}) {
    const Finished check = run_mpile({"check", path, "--pilot", seconds}, 0, directory / "err.txt");
    ASSERT_TRUE(check.exited) << seconds;
    EXPECT_EQ(check.status, 2) << seconds;
    EXPECT_EQ(check.err.rfind(
                  "--pilot: expected a finite number of seconds above 0, got " + seconds + "\n", 0),
              0u)
        << check.err;
  }
}

TEST(CommandLine, VerifyOptionsRefuseNanAndValuesOutOfRange) {
  // CLI::Range let nan through: `verify --poisson nan` ran, `--flip nan` failed later with exit 1,
  // and --courant had no check.
  const auto directory = fresh_directory("verify_options");
  for (const auto& [option, value] :
       std::vector<std::pair<std::string, std::string>>{{"--flip", "nan"},
                                                        {"--flip", "1.5"},
                                                        {"--poisson", "nan"},
                                                        {"--poisson", "0.5"},
                                                        {"--courant", "nan"},
                                                        {"--courant", "inf"},
                                                        {"--courant", "0"}}) {
    const Finished verify = run_mpile({"verify", "V2", option, value}, 0, directory / "err.txt");
    ASSERT_TRUE(verify.exited) << option << " " << value;
    EXPECT_EQ(verify.status, 2) << option << " " << value;
    EXPECT_EQ(verify.err.rfind(option + ": expected a finite number in [", 0), 0u) << verify.err;
  }
}

} // namespace
} // namespace mpile
