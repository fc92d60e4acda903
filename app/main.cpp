// mpile: the command line (app/command_line.hpp declares its subcommands).
#include "app/command_line.hpp"
#include "io/source_commit.hpp"

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <csignal>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  // Under a file-size limit (ulimit -f) a write past it raises SIGXFSZ, which kills the process
  // between two datasets of a history row. Ignored, the write fails with EFBIG instead, and the
  // run stops as on a full disk: its history whole and readable, its status saying why.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"mpile: axisymmetric explicit MPM with a rotational DOF, for monopile installation"};
  app.set_version_flag("--version",
                       std::string("mpile ") + MPILE_VERSION + " (" + mpile::source_commit() + ")");
  mpile::CommandLine line;
  mpile::declare_command_line(app, line);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : mpile::exit_bad_input;
  }

  const int cores = tbb::info::default_concurrency();
  line.run.threads = line.threads > 0 ? line.threads : cores;
  if (line.run.threads > cores) {
    std::cerr << "mpile: note: " << line.run.threads << " threads on " << cores
              << " cores: they take turns, and the run is no faster than on " << cores << '\n';
  }
  // The commands run in an arena of exactly the threads asked for: the default arena holds one
  // thread a core whatever max_allowed_parallelism allows, so that `--threads 6` on two cores ran
  // on two while the run's log and history said six.
  const tbb::global_control thread_limit(tbb::global_control::max_allowed_parallelism,
                                         static_cast<std::size_t>(line.run.threads));
  tbb::task_arena arena(line.run.threads);
  return arena.execute(
      [&]() -> int { return mpile::run_command_line(line, std::cout, std::cerr); });
}
