// mpile: the command line.
#include "app/describe_command.hpp"
#include "app/element_test_command.hpp"
#include "app/run_command.hpp"
#include "app/sweep_command.hpp"
#include "app/verify_command.hpp"
#include "cases/case_error.hpp"
#include "io/source_commit.hpp"
#include "solver/solver_settings.hpp"

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace {

// CLI::PositiveNumber lets nan through (no comparison with it is true), and a pilot of nan seconds
// then ran nothing without a word; it names the largest double when it refuses inf.
const CLI::Validator finite_positive_seconds(
    [](std::string& text) -> std::string {
      char* end = nullptr;
      const double x = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || !std::isfinite(x) || !(x > 0.0)) {
        return "expected a finite number of seconds above 0, got " + text;
      }
      return "";
    },
    "SECONDS");

/// A finite number in [low, high] (CLI::Range lets nan through, as CLI::PositiveNumber did).
CLI::Validator finite_within(double low, double high) {
  return CLI::Validator(
      [low, high](std::string& text) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(x) || !(x >= low && x <= high)) {
          std::ostringstream s;
          s << "expected a finite number in [" << low << ", " << high << "], got " << text;
          return s.str();
        }
        return "";
      },
      "NUMBER");
}

/// At most this many worker threads: more would only spend the memory of their stacks.
constexpr long long max_threads = 1024;

/// A whole number in [low, high]: CLI::PositiveNumber named the largest double as its bound
/// (`--threads 0`: "not in range 0.000000 to 1797...").
CLI::Validator count_within(long long low, long long high) {
  return CLI::Validator(
      [low, high](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const long long n = std::strtoll(text.c_str(), &end, 10);
        if (text.empty() || *end != '\0' || errno == ERANGE || n < low || n > high) {
          return "expected a whole number from " + std::to_string(low) + " to " +
                 std::to_string(high) + ", got " + text;
        }
        return "";
      },
      "INT");
}

} // namespace

int main(int argc, char** argv) {
  // Under a file-size limit (ulimit -f) a write past it raises SIGXFSZ, which kills the process
  // between two datasets of a history row. Ignored, the write fails with EFBIG instead, and the
  // run stops as on a full disk: its history whole and readable, its status saying why.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"mpile: axisymmetric explicit MPM with a rotational DOF, for monopile installation"};
  app.set_version_flag("--version",
                       std::string("mpile ") + MPILE_VERSION + " (" + mpile::source_commit() + ")");
  app.require_subcommand(1);
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (default: all cores)")
      ->check(count_within(1, max_threads));

  mpile::RunOptions run_options;
  auto* run = app.add_subcommand("run", "run a case file");
  run->add_option("case", run_options.case_path, "the case file (TOML)")->required();
  run->add_option("--threads", threads, "worker threads (default: all cores)")
      ->check(count_within(1, max_threads));
  run->add_option("--out", run_options.output_directory,
                  "output directory (default: [output].directory, else out/<case name>)");
  auto* restart =
      run->add_option("--restart", run_options.restart, "continue from this checkpoint file");
  const char* continue_help =
      "continue the run in the output directory from its checkpoint if it stopped before its end "
      "(interrupted or killed), do nothing if it is complete, else start it afresh: a batch job "
      "or sweep resubmitted as it is";
  run->add_flag("--continue", run_options.continue_run, continue_help)->excludes(restart);
  const char* set_help = "set one value of the case, key.path=value in TOML syntax (repeatable; "
                         "recorded in history.h5), e.g. --set monopile.friction=0.3";
  run->add_option("--set", run_options.overrides, set_help)->allow_extra_args(false);
  run->add_option("--stop-after", run_options.stop_after_steps,
                  "stop after N steps as if interrupted, writing a checkpoint")
      ->check(count_within(1, std::numeric_limits<long>::max()));
  const char* strict_help = "refuse the case (exit status 2) on any plausibility warning of units "
                            "(a torque in kN m, a density in g/cm^3, ...) instead of printing it";
  run->add_flag("--strict", run_options.strict, strict_help);

  auto* check = app.add_subcommand("check", "validate a case and estimate its cost");
  check->add_option("case", run_options.case_path, "the case file (TOML)")->required();
  check->add_option("--threads", threads, "worker threads (default: all cores)")
      ->check(count_within(1, max_threads));
  check->add_option("--set", run_options.overrides, set_help)->allow_extra_args(false);
  check
      ->add_option("--pilot", run_options.pilot_seconds,
                   "run the case for this many seconds of wall time (in a temporary directory) "
                   "and estimate its run time from how far it got")
      ->check(finite_positive_seconds);
  check->add_flag("--strict", run_options.strict, strict_help);
  check->add_flag("--print-resolved", run_options.print_resolved,
                  "print the case as it runs (bases merged, --set values applied) as one TOML "
                  "file, once it is checked, instead of the summary");

  mpile::SweepOptions sweep_options;
  auto* sweep = app.add_subcommand(
      "sweep", "run a case at every combination of listed values (a parameter study) through "
               "Snakemake and gather the results into one table");
  sweep->add_option("file", sweep_options.file, "the sweep file (TOML)")->required();
  sweep->add_option("--out", sweep_options.output_directory,
                    "output directory (default: out/sweeps/<sweep file name>)");
  sweep->add_option("--cores", sweep_options.cores, "cores to fill with runs (default: all)")
      ->check(count_within(1, max_threads));
  sweep->add_option("--profile", sweep_options.profile,
                    "a Snakemake profile directory (a cluster's submission settings)");
  sweep->add_flag("--strict", sweep_options.strict,
                  "refuse the sweep (exit status 2) on any variant's plausibility warning of units "
                  "instead of printing it");
  sweep->add_flag("--prepare", sweep_options.prepare,
                  "write the workflow and print the Snakemake command, run nothing");

  mpile::ElementTestOptions element_options;
  auto* element = app.add_subcommand(
      "element-test", "drive one material point along a laboratory path and write a CSV");
  element->add_option("file", element_options.file, "the element-test file (TOML)")->required();
  element->add_option("--out", element_options.csv, "CSV file (default: out/<file name>.csv)");

  mpile::DescribeOptions describe_options;
  auto* describe = app.add_subcommand(
      "describe", "print the case format: every table's keys with type, unit, default, range");
  describe->add_option("table", describe_options.table,
                       "one table (solver, phases, phases.stop_at, [[bodies]], ...) or material "
                       "type (hardening_soil); default: all");
  describe->add_flag("--json-schema", describe_options.json_schema,
                     "print a JSON Schema of case files (for TOML editors)");
  describe->add_option("--update-doc", describe_options.update_doc,
                       "rewrite the generated key tables of a Markdown file "
                       "(docs/case-format.md)");
  describe->add_option("--check-doc", describe_options.check_doc,
                       "exit 1 when a Markdown file's generated key tables are stale");

  auto* verify = app.add_subcommand("verify", "run verification cases against their references");
  std::vector<std::string> ids{"all"};
  bool list = false;
  mpile::verification::Options options;
  verify->add_option("cases", ids, "case ids (V1, V2, ...), or all")->capture_default_str();
  verify->add_option("--threads", threads, "worker threads (default: all cores)")
      ->check(count_within(1, max_threads));
  verify->add_flag("--list", list, "list the cases and exit");
  // A zone of the verification cases has at most a few hundred cells, so that the refined count
  // stays an int; the case format's own bound on a zone's cells then names the zone.
  verify->add_option("--refinement", options.refinement, "cells per direction multiplier")
      ->check(count_within(1, 1000))
      ->capture_default_str();
  verify
      ->add_option("--ppc", options.particles_per_direction,
                   "particles per cell direction (default: the case file's)")
      ->check(count_within(1, 8)); // as particles_per_cell in a case file: 100 000 filled memory
  verify->add_option("--bbar", options.bbar, "B-bar on (1) or off (0); default on")
      ->check(CLI::IsMember({"0", "1"})); // as a bool CLI11 takes 7 and -1 for on
  verify->add_option("--flip", options.flip_fraction, "FLIP fraction in [0, 1]")
      ->check(finite_within(0.0, 1.0));
  verify
      ->add_option("--xpic", options.xpic_order,
                   "XPIC order m (1 = PIC; replaces the FLIP/PIC blend)")
      ->check(CLI::Range(1, mpile::SolverSettings::max_xpic_order));
  verify->add_option("--poisson", options.poisson_ratio, "Poisson ratio for V3 and V5")
      ->check(finite_within(-0.99, 0.4999));
  // The solver settings bound the Courant number further; a non-finite one never reaches them.
  verify->add_option("--courant", options.courant_number, "Courant number")
      ->check(finite_within(1e-6, 2.0));
  std::string scheme;
  verify->add_option("--scheme", scheme, "musl (default) or usl")
      ->check(CLI::IsMember({"musl", "usl"}));
  verify->add_flag("--implicit-pore-pressure", options.implicit_pore_pressure,
                   "saturated cases: the pore pressure solved on the grid each step");
  bool csv = false;
  verify->add_flag("--csv", csv,
                   "one CSV row per check: case, quantity, measured, reference, unit, error, "
                   "tolerance, particles, steps, wall seconds");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : mpile::exit_bad_input;
  }

  const int cores = tbb::info::default_concurrency();
  run_options.threads = threads > 0 ? threads : cores;
  if (run_options.threads > cores) {
    std::cerr << "mpile: note: " << run_options.threads << " threads on " << cores
              << " cores: they take turns, and the run is no faster than on " << cores << '\n';
  }
  // The commands run in an arena of exactly the threads asked for: the default arena holds one
  // thread a core whatever max_allowed_parallelism allows, so that `--threads 6` on two cores ran
  // on two while the run's log and history said six.
  const tbb::global_control thread_limit(tbb::global_control::max_allowed_parallelism,
                                         static_cast<std::size_t>(run_options.threads));
  tbb::task_arena arena(run_options.threads);
  return arena.execute([&]() -> int {
    try {
      if (run->parsed()) {
        return mpile::run_case(run_options, std::cout, std::cerr);
      }
      if (check->parsed()) {
        return mpile::check_case(run_options, std::cout, std::cerr);
      }
      if (sweep->parsed()) {
        return mpile::sweep_command(sweep_options, std::cout, std::cerr);
      }
      if (describe->parsed()) {
        return mpile::describe_command(describe_options, std::cout, std::cerr);
      }
      if (element->parsed()) {
        return mpile::element_test_command(element_options, std::cout, std::cerr);
      }
      if (list) {
        for (const auto& c : mpile::verification::all_cases()) {
          std::cout << c.id << "\t" << c.title << '\n';
        }
        return 0;
      }
      if (!scheme.empty()) {
        options.musl = scheme == "musl";
      }
      if (!csv) {
        std::cout << "mpile verify on " << run_options.threads << " thread(s)\n";
      }
      return mpile::run_verification(ids, options, std::cout, csv) == 0 ? mpile::exit_success
                                                                        : mpile::exit_failure;
    } catch (const mpile::CaseError& e) {
      // An unknown case id or a refinement the case format refuses: the command line is wrong.
      std::cerr << "mpile: " << e.what() << '\n';
      return mpile::exit_bad_input;
    } catch (const std::invalid_argument& e) {
      std::cerr << "mpile: " << e.what() << '\n';
      return mpile::exit_bad_input;
    } catch (const std::exception& e) {
      std::cerr << "mpile: " << e.what() << '\n';
      return mpile::exit_failure;
    }
  });
}
