// A run whose outputs cannot be written: `mpile run` in a child process under a file-size limit
// (ulimit -f; mpile ignores SIGXFSZ, so a write past it fails with EFBIG as on a full disk).
#include "io/hdf5_file.hpp"
#include "tests/case_run.hpp"
#include "tests/run_program.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace mpile {
namespace {

TEST(RunCommand, AFullDiskStopsTheRunNamingTheFileAndLeavesWhatItWroteReadable) {
  // The single point for 100 s with a row every step (6 300 rows): the history's series take a
  // new chunk of 4 096 rows each once it passes them, which a 1.2 MB limit has no room for. The
  // run crashed in HDF5 (SIGSEGV) and left a history that could not be read; under `ulimit -f`
  // without SIGXFSZ ignored (the child here keeps its default) it was killed by the signal.
  const auto directory = fresh_directory("full_disk");
  const auto path = directory / "point.toml";
  std::ofstream(path) << replaced(read_text(source / "cases/verification/single_point.toml"),
                                  "duration = 3.0", "duration = 100.0")
                      << "\n[output]\nhistory_interval = 0.0\ncheckpoint_interval = 10.0\n"
                         "snapshot_interval = 40.0\n";
  const auto out = directory / "out";
  const Finished run = run_mpile({"run", path.string(), "--out", out.string(), "--threads", "1"},
                                 1200 * 1024, directory / "err.txt");
  ASSERT_TRUE(run.exited) << "signal " << run.status << "\n" << run.err;
  EXPECT_EQ(run.status, 1) << run.err;
  const std::string history_path = (out / "history.h5").string();
  EXPECT_NE(run.err.find("mpile: cannot write " + history_path +
                         ": File too large; the run "
                         "stopped at t = "),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("continue with --restart " + (out / "checkpoint.h5").string()),
            std::string::npos)
      << run.err;

  // Every series holds the same whole rows, in order; the checkpoint counts no more of them.
  std::size_t rows = 0;
  {
    Hdf5File history(history_path, Hdf5File::Mode::read);
    const std::vector<double> time = history.read_doubles("/time");
    rows = time.size();
    EXPECT_GT(rows, 1000u);
    EXPECT_LE(rows, 4096u);
    for (std::size_t k = 1; k < rows; ++k) {
      ASSERT_GT(time[k], time[k - 1]) << k;
    }
    for (const char* series : {"/step", "/energy/kinetic", "/energy/relative_residual",
                               "/boundaries/r_min/F_r", "/boundaries/y_max/F_y"}) {
      EXPECT_EQ(history.read_doubles(series).size(), rows) << series;
    }
    // Closed as failed, with the reason: the buffered rows had no room, the status had.
    EXPECT_EQ(history.string_attribute("/", "status")
                  .rfind("failed: cannot write " + history_path + ": File too large", 0),
              0u)
        << history.string_attribute("/", "status");
    Hdf5File checkpoint((out / "checkpoint.h5").string(), Hdf5File::Mode::read);
    EXPECT_LE(checkpoint.read_doubles("/run/counters").at(1), static_cast<double>(rows));
  }
  // Every snapshot the index lists is there, and no half-written file is left.
  const std::string index = read_text(out / "particles.pvd");
  const std::regex listed("file=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(index.begin(), index.end(), listed);
       it != std::sregex_iterator(); ++it) {
    EXPECT_TRUE(std::filesystem::exists(out / (*it)[1].str())) << (*it)[1].str();
  }
  for (const auto& entry : std::filesystem::directory_iterator(out)) {
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
  }

  // A restart with no more room is refused as a run that cannot write (status 1), not as a
  // checkpoint that does not fit its history (status 2).
  const Finished cramped = run_mpile({"run", path.string(), "--out", out.string(), "--threads", "1",
                                      "--restart", (out / "checkpoint.h5").string()},
                                     1200 * 1024, directory / "err_cramped.txt");
  ASSERT_TRUE(cramped.exited) << cramped.err;
  EXPECT_EQ(cramped.status, 1) << cramped.err;
  EXPECT_NE(cramped.err.find("cannot write " + history_path + ": File too large"),
            std::string::npos)
      << cramped.err;

  // With room again, the run continues from its checkpoint to the end.
  const Finished resumed = run_mpile({"run", path.string(), "--out", out.string(), "--threads", "1",
                                      "--restart", (out / "checkpoint.h5").string()},
                                     0, directory / "err_resumed.txt");
  ASSERT_TRUE(resumed.exited) << resumed.err;
  EXPECT_EQ(resumed.status, 0) << resumed.err;
  Hdf5File history(history_path, Hdf5File::Mode::read);
  // (The single point's energy balance drifts over 100 s: "complete, but ..." as uninterrupted.)
  EXPECT_EQ(history.string_attribute("/", "status").rfind("complete", 0), 0u);
  EXPECT_GT(history.read_doubles("/time").back(), 99.9);
}

} // namespace
} // namespace mpile
