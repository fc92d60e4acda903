// mpile: the command line.
#include "io/verify_command.hpp"

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <iostream>
#include <memory>

int main(int argc, char** argv) {
  CLI::App app{"mpile: axisymmetric explicit MPM with a rotational DOF, for monopile installation"};
  app.set_version_flag("--version", std::string("mpile ") + MPILE_VERSION);
  app.require_subcommand(1);
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (default: all cores)")
      ->check(CLI::PositiveNumber);

  auto* verify = app.add_subcommand("verify", "run verification cases against their references");
  std::vector<std::string> ids{"all"};
  bool list = false;
  mpile::verification::Options options;
  verify->add_option("cases", ids, "case ids (V1, V2, ...), or all")->capture_default_str();
  verify->add_flag("--list", list, "list the cases and exit");
  verify->add_option("--refinement", options.refinement, "cells per direction multiplier")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  verify->add_option("--ppc", options.particles_per_direction, "particles per cell direction")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  verify->add_option("--bbar", options.bbar, "B-bar on (1) or off (0); default on");
  verify->add_option("--flip", options.flip_fraction, "FLIP fraction in [0, 1]")
      ->check(CLI::Range(0.0, 1.0));
  verify->add_option("--poisson", options.poisson_ratio, "Poisson ratio for V3 and V5")
      ->check(CLI::Range(-0.99, 0.4999));
  verify->add_option("--courant", options.courant_number, "Courant number");

  CLI11_PARSE(app, argc, argv);

  std::unique_ptr<tbb::global_control> thread_limit;
  const int cores = tbb::info::default_concurrency();
  thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                       threads > 0 ? threads : cores);

  try {
    if (verify->parsed()) {
      if (list) {
        for (const auto& c : mpile::verification::all_cases()) {
          std::cout << c.id << "\t" << c.title << '\n';
        }
        return 0;
      }
      std::cout << "mpile verify on " << (threads > 0 ? threads : cores) << " thread(s)\n";
      return mpile::run_verification(ids, options, std::cout) == 0 ? 0 : 1;
    }
  } catch (const std::exception& e) {
    std::cerr << "mpile: " << e.what() << '\n';
    return 2;
  }
  return 0;
}
