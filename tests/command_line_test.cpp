// The command line's own checks, through the program itself.
#include "tests/run_program.hpp"

#include <gtest/gtest.h>

#include <string>

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

} // namespace
} // namespace mpile
