// `mpile run --continue`: a run resubmitted as it is (a batch job after its time limit, a sweep
// after Ctrl-C or a lost machine) continues from its checkpoint to the whole run's result bit for
// bit, does nothing once complete, and starts afresh where what the directory holds is not its own.

#include "app/run_command.hpp"
#include "io/hdf5_file.hpp"
#include "tests/case_run.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace mpile {
namespace {

// V7, the block sliding down a rigid incline, cut to a third of its second: about 300 steps.
RunOptions block_on_incline(const std::filesystem::path& out) {
  RunOptions options;
  options.case_path = (source / "cases" / "verification" / "v7_block_on_incline.toml").string();
  options.output_directory = out.string();
  options.overrides = {"phases.0.duration=0.3"};
  options.threads = 1;
  return options;
}

int run(const RunOptions& options, std::string* printed = nullptr) {
  std::ostringstream out, err;
  const int status = run_case(options, out, err);
  if (printed != nullptr) {
    *printed = out.str() + err.str();
  }
  return status;
}

std::vector<double> series(const std::filesystem::path& out, const std::string& name) {
  return Hdf5File((out / "history.h5").string(), Hdf5File::Mode::read).read_doubles(name);
}

std::string status_of(const std::filesystem::path& out) {
  return Hdf5File((out / "history.h5").string(), Hdf5File::Mode::read)
      .string_attribute("/", "status");
}

void set_status(const std::filesystem::path& out, const std::string& status) {
  Hdf5File file((out / "history.h5").string(), Hdf5File::Mode::append);
  file.set_attribute("/", "status", status);
  file.close();
}

/// The whole run in DIRECTORY/whole, and the same run stopped after 40 steps in DIRECTORY/NAME.
void run_whole_and_interrupted(const std::filesystem::path& directory, const std::string& name) {
  ASSERT_EQ(run(block_on_incline(directory / "whole")), exit_success);
  RunOptions first = block_on_incline(directory / name);
  first.stop_after_steps = 40;
  ASSERT_EQ(run(first), exit_interrupted);
}

void expect_the_whole_runs_history(const std::filesystem::path& whole,
                                   const std::filesystem::path& continued) {
  for (const char* name : {"/time", "/dt", "/energy/kinetic", "/energy/external_work"}) {
    EXPECT_EQ(series(whole, name), series(continued, name)) << name;
  }
  EXPECT_EQ(status_of(whole), status_of(continued));
}

TEST(RunContinuation, AnInterruptedRunContinuesToTheWholeRunsResultThenHasNothingLeft) {
  const auto directory = fresh_directory("continue_interrupted");
  ASSERT_NO_FATAL_FAILURE(run_whole_and_interrupted(directory, "split"));
  RunOptions again = block_on_incline(directory / "split");
  again.continue_run = true;
  std::string printed;
  ASSERT_EQ(run(again, &printed), exit_success) << printed;
  EXPECT_NE(printed.find("stopped before its end (interrupted at t = "), std::string::npos)
      << printed;
  EXPECT_NE(printed.find("continuing "), std::string::npos) << printed;
  expect_the_whole_runs_history(directory / "whole", directory / "split");

  // Complete: resubmitted once more, it leaves the run as it is.
  const auto written = std::filesystem::last_write_time(directory / "split" / "history.h5");
  ASSERT_EQ(run(again, &printed), exit_success) << printed;
  EXPECT_NE(printed.find("holds this case's complete run; nothing to continue"), std::string::npos)
      << printed;
  EXPECT_EQ(std::filesystem::last_write_time(directory / "split" / "history.h5"), written);
}

TEST(RunContinuation, AKilledRunContinuesFromItsLastCheckpoint) {
  const auto directory = fresh_directory("continue_killed");
  ASSERT_NO_FATAL_FAILURE(run_whole_and_interrupted(directory, "killed"));
  // What a killed process leaves: its history still says running.
  set_status(directory / "killed", "running");

  RunOptions again = block_on_incline(directory / "killed");
  again.continue_run = true;
  std::string printed;
  ASSERT_EQ(run(again, &printed), exit_success) << printed;
  EXPECT_NE(printed.find("stopped before its end (running)"), std::string::npos) << printed;
  expect_the_whole_runs_history(directory / "whole", directory / "killed");
}

TEST(RunContinuation, NoRunAFailedRunOrOtherValuesStartAfresh) {
  const auto directory = fresh_directory("continue_afresh");
  ASSERT_EQ(run(block_on_incline(directory / "whole")), exit_success);

  RunOptions fresh = block_on_incline(directory / "run");
  fresh.continue_run = true;
  std::string printed;
  ASSERT_EQ(run(fresh, &printed), exit_success) << printed;
  EXPECT_NE(printed.find("no earlier run in "), std::string::npos) << printed;
  expect_the_whole_runs_history(directory / "whole", directory / "run");

  // A run that stopped on its own failure is run again from the start, not from its checkpoint.
  RunOptions first = block_on_incline(directory / "run");
  first.stop_after_steps = 40;
  ASSERT_EQ(run(first), exit_interrupted);
  set_status(directory / "run", "unstable: the Courant number reached 1.2");
  ASSERT_EQ(run(fresh, &printed), exit_success) << printed;
  EXPECT_NE(printed.find("ended without finishing (unstable: "), std::string::npos) << printed;
  EXPECT_NE(printed.find("the run starts from the beginning"), std::string::npos) << printed;
  expect_the_whole_runs_history(directory / "whole", directory / "run");

  // Interrupted with other values: that state is not this run's.
  RunOptions other = block_on_incline(directory / "run");
  other.overrides.push_back("contact.0.friction=0.2");
  other.stop_after_steps = 40;
  ASSERT_EQ(run(other), exit_interrupted);
  ASSERT_EQ(run(fresh, &printed), exit_success) << printed;
  EXPECT_NE(printed.find("holds a run of another case or other values"), std::string::npos)
      << printed;
  expect_the_whole_runs_history(directory / "whole", directory / "run");
}

} // namespace
} // namespace mpile
