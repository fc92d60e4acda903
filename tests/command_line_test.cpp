// The command line's own checks, through the program itself.
#include "io/hdf5_file.hpp"
#include "tests/run_program.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <thread>
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

TEST(CommandLine, VerifyBbarIsZeroOrOne) {
  // Read as a bool, --bbar took 7 and -1 for "on" although the help says 0 or 1.
  const auto directory = fresh_directory("verify_bbar");
  for (const std::string value : {"7", "-1", "on"}) {
    const Finished verify = run_mpile({"verify", "V2", "--bbar", value}, 0, directory / "err.txt");
    ASSERT_TRUE(verify.exited) << value;
    EXPECT_EQ(verify.status, 2) << value;
    EXPECT_EQ(verify.err.rfind("--bbar: " + value + " not in {0,1}", 0), 0u) << verify.err;
  }
}

TEST(CommandLine, ARunHasTheWorkersAskedForEvenAboveTheCores) {
  // The default arena holds one thread a core whatever max_allowed_parallelism allows: `--threads
  // 6` on two cores ran on two while the log and the history said six. One thread more than the
  // machine's cores must be what the run has and records.
  const int asked = static_cast<int>(std::max(1u, std::thread::hardware_concurrency())) + 1;
  const auto directory = fresh_directory("threads_above_cores");
  const std::string path = (source / "cases/verification/single_point.toml").string();
  const Finished run =
      run_mpile({"--threads", std::to_string(asked), "run", path, "--out", directory.string()}, 0,
                directory / "err.txt");
  ASSERT_TRUE(run.exited);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.err.find("mpile: note: " + std::to_string(asked) + " threads on "),
            std::string::npos)
      << run.err;
  const std::string log = read_text(directory / "run.log");
  EXPECT_NE(log.find(" on " + std::to_string(asked) + " threads\n"), std::string::npos) << log;
  const Hdf5File history((directory / "history.h5").string(), Hdf5File::Mode::read);
  EXPECT_EQ(history.number_attribute("/", "threads"), asked);
}

TEST(CommandLine, CountsOutOfRangeAreRefusedWithTheirRange) {
  // CLI::PositiveNumber refused 0 naming the largest double as the bound; `verify --ppc 100000`
  // filled memory for a minute before anything was said; an unknown verification case exited 1.
  const auto directory = fresh_directory("count_options");
  const std::string path = (source / "cases/verification/single_point.toml").string();
  for (const auto& [arguments, start] :
       std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--threads", "0", "check", path},
            "--threads: expected a whole number from 1 to 1024, got 0"},
           {{"check", path, "--threads", "2000"},
            "--threads: expected a whole number from 1 to 1024, got 2000"},
           {{"verify", "V3", "--ppc", "100000"},
            "--ppc: expected a whole number from 1 to 8, got 100000"},
           {{"verify", "V3", "--refinement", "1.5"},
            "--refinement: expected a whole number from 1 to 1000, got 1.5"},
           {{"run", path, "--stop-after", "-3"},
            "--stop-after: expected a whole number from 1 to "},
           {{"verify", "V99"}, "mpile: unknown verification case 'V99'"}}) {
    const Finished command = run_mpile(arguments, 0, directory / "err.txt");
    ASSERT_TRUE(command.exited) << start;
    EXPECT_EQ(command.status, 2) << command.err;
    EXPECT_EQ(command.err.rfind(start, 0), 0u) << command.err;
  }
}

TEST(CommandLine, DescribeReadsOnlyARegularFileAsItsPage) {
  // `describe --check-doc /dev/zero` read without end.
  const auto directory = fresh_directory("describe_page");
  for (const std::string& page : std::vector<std::string>{"/dev/zero", directory.string()}) {
    const Finished describe =
        run_mpile({"describe", "--check-doc", page}, 0, directory / "err.txt");
    ASSERT_TRUE(describe.exited) << page;
    EXPECT_EQ(describe.status, 2) << describe.err;
    EXPECT_EQ(describe.err, "mpile describe: " + page + ": not a regular file (a Markdown page)\n");
  }
}

TEST(CommandLine, DescribeNamesItselfInEveryError) {
  // A page without the generated blocks, and an unknown table: the page's errors began with the
  // page's name alone, unlike every other describe error.
  const auto directory = fresh_directory("describe_errors");
  std::ofstream(directory / "page.md") << "# A page\n\nNo generated block.\n";
  const std::string page = (directory / "page.md").string();
  for (const auto& [arguments, start] :
       std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"describe", "--check-doc", page}, "mpile describe: " + page + ": no generated block"},
           {{"describe", "nosuch"}, "mpile describe: no table or material type 'nosuch'"}}) {
    const Finished describe = run_mpile(arguments, 0, directory / "err.txt");
    ASSERT_TRUE(describe.exited);
    EXPECT_EQ(describe.status, 2) << describe.err;
    EXPECT_EQ(describe.err.rfind(start, 0), 0u) << describe.err;
  }
}

} // namespace
} // namespace mpile
