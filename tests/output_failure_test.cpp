// A run whose outputs cannot be written: `mpile run` in a child process under a file-size limit
// (ulimit -f; mpile ignores SIGXFSZ, so a write past it fails with EFBIG as on a full disk); and
// files damaged on disk after they were written.
#include "io/hdf5_file.hpp"
#include "tests/case_run.hpp"
#include "tests/run_program.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

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

TEST(RunCommand, AHistoryThatCannotBeCreatedIsNotLeftBehindHalfWritten) {
  // 1 KiB has room for HDF5's superblock but not for the series: the run left an 800-byte
  // history.h5 without /time, which a reader took for a run that had written nothing yet.
  const auto directory = fresh_directory("history_not_created");
  const auto out = directory / "out";
  const Finished run = run_mpile({"run", (source / "cases/verification/single_point.toml").string(),
                                  "--out", out.string(), "--threads", "1"},
                                 1024, directory / "err.txt");
  ASSERT_TRUE(run.exited) << "signal " << run.status << "\n" << run.err;
  EXPECT_EQ(run.status, 1) << run.err;
  const std::string history_path = (out / "history.h5").string();
  EXPECT_NE(run.err.find("mpile: cannot write " + history_path + ": File too large"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(std::filesystem::exists(history_path));
  // The log beside the outputs says why the run did not start.
  EXPECT_NE(read_text(out / "run.log").find("cannot write " + history_path), std::string::npos)
      << read_text(out / "run.log");
}

// The file offset of the first chunk of `dataset` in the HDF5 file at `path`.
haddr_t first_chunk_offset(const std::string& path, const std::string& dataset) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t set = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
  const hid_t space = H5Dget_space(set);
  hsize_t offset[1] = {0};
  unsigned filters = 0;
  haddr_t address = HADDR_UNDEF;
  hsize_t size = 0;
  const herr_t found = H5Dget_chunk_info(set, space, 0, offset, &filters, &address, &size);
  H5Sclose(space);
  H5Dclose(set);
  H5Fclose(file);
  EXPECT_GE(found, 0) << dataset;
  return address;
}

// Flips the bits of one byte, `into` bytes past `offset`.
void damage_byte(const std::filesystem::path& path, haddr_t offset, std::size_t into) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekg(static_cast<std::streamoff>(offset + into));
  char byte = 0;
  file.get(byte);
  file.seekp(static_cast<std::streamoff>(offset + into));
  file.put(static_cast<char>(~byte));
}

TEST(Hdf5Output, DataDamagedOnDiskIsRefusedWhenReadNotReadBackAsOtherNumbers) {
  // Every chunk carries a Fletcher32 checksum. Without it the damaged /time read back with one
  // value changed and no error.
  const auto path = fresh_directory("damaged_hdf5") / "history.h5";
  {
    Hdf5File file(path.string(), Hdf5File::Mode::create);
    Hdf5Series time(file, "/time", "s");
    for (int i = 0; i < 100; ++i) {
      time.append(0.01 * i);
    }
    time.flush(file);
    file.write("/array", std::vector<double>{1.0, 2.0, 3.0}, "m");
  }
  damage_byte(path, first_chunk_offset(path.string(), "/time"), 8 * 50 + 3);
  damage_byte(path, first_chunk_offset(path.string(), "/array"), 8 + 3);
  Hdf5File file(path.string(), Hdf5File::Mode::read);
  for (const char* dataset : {"/time", "/array"}) {
    try {
      file.read_doubles(dataset);
      ADD_FAILURE() << dataset << " was read back though damaged";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("cannot read ") + dataset + " in " +
                                           path.string()),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(RunCommand, ACheckpointThatCannotBeReadIsRefusedSayingWhatToDo) {
  // A checkpoint cut short, and one with a byte of its particles' radii flipped: both were refused
  // with HDF5's words alone ("HDF5: cannot open ...", blamed on the case file), and the flipped
  // one was not refused at all.
  const auto directory = fresh_directory("damaged_checkpoint");
  const auto out = directory / "out";
  const std::string case_path = (source / "cases/verification/single_point.toml").string();
  ASSERT_EQ(run_mpile({"run", case_path, "--out", out.string(), "--threads", "1"}, 0,
                      directory / "err.txt")
                .status,
            0);
  const auto checkpoint = out / "checkpoint.h5";
  const auto cut = directory / "cut.h5";
  const auto flipped = directory / "flipped.h5";
  std::filesystem::copy_file(checkpoint, flipped);
  const std::string whole = read_text(checkpoint);
  std::ofstream(cut, std::ios::binary) << whole.substr(0, whole.size() / 2);
  damage_byte(flipped, first_chunk_offset(flipped.string(), "/particles/r"), 5);
  for (const auto& damaged : {cut, flipped}) {
    const Finished restart = run_mpile(
        {"run", case_path, "--out", out.string(), "--threads", "1", "--restart", damaged.string()},
        0, directory / "err_restart.txt");
    ASSERT_TRUE(restart.exited) << restart.err;
    EXPECT_EQ(restart.status, 2) << restart.err;
    EXPECT_NE(restart.err.find("mpile: " + damaged.string() +
                               ": cannot restart: the checkpoint cannot be read ("),
              std::string::npos)
        << restart.err;
    EXPECT_NE(restart.err.find("it was cut short or damaged. Restart from another checkpoint, or "
                               "run the case afresh without --restart or --continue"),
              std::string::npos)
        << restart.err;
  }
}

} // namespace
} // namespace mpile
