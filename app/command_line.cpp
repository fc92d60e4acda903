// The command line's declarations: one function a subcommand, each option with its check.
#include "app/command_line.hpp"

#include "app/verify_command.hpp"
#include "cases/case_error.hpp"
#include "solver/solver_settings.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <ostream>
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

const char* const threads_help = "worker threads (default: all cores)";
const char* const set_help =
    "set one value of the case, key.path=value in TOML syntax (repeatable; "
    "recorded in history.h5), e.g. --set monopile.friction=0.3";
const char* const strict_help =
    "refuse the case (exit status 2) on any plausibility warning of units (a torque in kN m, a "
    "density in g/cm^3, ...) instead of printing it";

void add_threads(CLI::App& command, int& threads) {
  command.add_option("--threads", threads, threads_help)->check(count_within(1, max_threads));
}

CLI::App* declare_run(CLI::App& app, mpile::RunOptions& options, int& threads) {
  auto* run = app.add_subcommand("run", "run a case file");
  run->add_option("case", options.case_path, "the case file (TOML)")->required();
  add_threads(*run, threads);
  run->add_option("--out", options.output_directory,
                  "output directory (default: [output].directory, else out/<case name>)");
  auto* restart =
      run->add_option("--restart", options.restart, "continue from this checkpoint file");
  const char* continue_help =
      "continue the run in the output directory from its checkpoint if it stopped before its end "
      "(interrupted or killed), do nothing if it is complete, else start it afresh: a batch job "
      "or sweep resubmitted as it is";
  run->add_flag("--continue", options.continue_run, continue_help)->excludes(restart);
  run->add_option("--set", options.overrides, set_help)->allow_extra_args(false);
  run->add_option("--stop-after", options.stop_after_steps,
                  "stop after N steps as if interrupted, writing a checkpoint")
      ->check(count_within(1, std::numeric_limits<long>::max()));
  run->add_flag("--strict", options.strict, strict_help);
  return run;
}

CLI::App* declare_check(CLI::App& app, mpile::RunOptions& options, int& threads) {
  auto* check = app.add_subcommand("check", "validate a case and estimate its cost");
  check->add_option("case", options.case_path, "the case file (TOML)")->required();
  add_threads(*check, threads);
  check->add_option("--set", options.overrides, set_help)->allow_extra_args(false);
  check
      ->add_option("--pilot", options.pilot_seconds,
                   "run the case for this many seconds of wall time (in a temporary directory) "
                   "and estimate its run time from how far it got")
      ->check(finite_positive_seconds);
  check->add_flag("--strict", options.strict, strict_help);
  check->add_flag("--print-resolved", options.print_resolved,
                  "print the case as it runs (bases merged, --set values applied) as one TOML "
                  "file, once it is checked, instead of the summary");
  return check;
}

CLI::App* declare_sweep(CLI::App& app, mpile::SweepOptions& options) {
  auto* sweep = app.add_subcommand(
      "sweep", "run a case at every combination of listed values (a parameter study) through "
               "Snakemake and gather the results into one table");
  sweep->add_option("file", options.file, "the sweep file (TOML)")->required();
  sweep->add_option("--out", options.output_directory,
                    "output directory (default: out/sweeps/<sweep file name>)");
  sweep->add_option("--cores", options.cores, "cores to fill with runs (default: all)")
      ->check(count_within(1, max_threads));
  sweep->add_option("--profile", options.profile,
                    "a Snakemake profile directory (a cluster's submission settings)");
  sweep->add_flag("--strict", options.strict,
                  "refuse the sweep (exit status 2) on any variant's plausibility warning of units "
                  "instead of printing it");
  sweep->add_flag("--prepare", options.prepare,
                  "write the workflow and print the Snakemake command, run nothing");
  return sweep;
}

CLI::App* declare_element_test(CLI::App& app, mpile::ElementTestOptions& options) {
  auto* element = app.add_subcommand(
      "element-test", "drive one material point along a laboratory path and write a CSV");
  element->add_option("file", options.file, "the element-test file (TOML)")->required();
  element->add_option("--out", options.csv, "CSV file (default: out/<file name>.csv)");
  return element;
}

CLI::App* declare_describe(CLI::App& app, mpile::DescribeOptions& options) {
  auto* describe = app.add_subcommand(
      "describe", "print the case format: every table's keys with type, unit, default, range");
  describe->add_option("table", options.table,
                       "one table (solver, phases, phases.stop_at, [[bodies]], ...) or material "
                       "type (hardening_soil); default: all");
  describe->add_flag("--json-schema", options.json_schema,
                     "print a JSON Schema of case files (for TOML editors)");
  describe->add_option("--update-doc", options.update_doc,
                       "rewrite the generated key tables of a Markdown file "
                       "(docs/case-format.md)");
  describe->add_option("--check-doc", options.check_doc,
                       "exit 1 when a Markdown file's generated key tables are stale");
  return describe;
}

void declare_verify(CLI::App& app, mpile::VerifyRequest& request, int& threads) {
  auto* verify = app.add_subcommand("verify", "run verification cases against their references");
  mpile::verification::Options& options = request.options;
  verify->add_option("cases", request.ids, "case ids (V1, V2, ...), or all")->capture_default_str();
  add_threads(*verify, threads);
  verify->add_flag("--list", request.list, "list the cases and exit");
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
  verify->add_option("--scheme", request.scheme, "musl (default) or usl")
      ->check(CLI::IsMember({"musl", "usl"}));
  verify->add_flag("--implicit-pore-pressure", options.implicit_pore_pressure,
                   "saturated cases: the pore pressure solved on the grid each step");
  verify->add_flag("--csv", request.csv,
                   "one CSV row per check: case, quantity, measured, reference, unit, error, "
                   "tolerance, particles, steps, wall seconds");
}

int verify_command(mpile::VerifyRequest& request, int threads, std::ostream& out) {
  if (request.list) {
    for (const auto& c : mpile::verification::all_cases()) {
      out << c.id << "\t" << c.title << '\n';
    }
    return mpile::exit_success;
  }
  if (!request.scheme.empty()) {
    request.options.musl = request.scheme == "musl";
  }
  if (!request.csv) {
    out << "mpile verify on " << threads << " thread(s)\n";
  }
  return mpile::run_verification(request.ids, request.options, out, request.csv) == 0
             ? mpile::exit_success
             : mpile::exit_failure;
}

} // namespace

namespace mpile {

void declare_command_line(CLI::App& app, CommandLine& line) {
  app.require_subcommand(1);
  add_threads(app, line.threads);
  line.run_command = declare_run(app, line.run, line.threads);
  line.check_command = declare_check(app, line.run, line.threads);
  line.sweep_command = declare_sweep(app, line.sweep);
  line.element_test_command = declare_element_test(app, line.element_test);
  line.describe_command = declare_describe(app, line.describe);
  declare_verify(app, line.verify, line.threads);
}

int run_command_line(CommandLine& line, std::ostream& out, std::ostream& err) {
  try {
    if (line.run_command->parsed()) {
      return run_case(line.run, out, err);
    }
    if (line.check_command->parsed()) {
      return check_case(line.run, out, err);
    }
    if (line.sweep_command->parsed()) {
      return sweep_command(line.sweep, out, err);
    }
    if (line.describe_command->parsed()) {
      return describe_command(line.describe, out, err);
    }
    if (line.element_test_command->parsed()) {
      return element_test_command(line.element_test, out, err);
    }
    return verify_command(line.verify, line.run.threads, out);
  } catch (const CaseError& e) {
    // An unknown case id or a refinement the case format refuses: the command line is wrong.
    err << "mpile: " << e.what() << '\n';
    return exit_bad_input;
  } catch (const std::invalid_argument& e) {
    err << "mpile: " << e.what() << '\n';
    return exit_bad_input;
  } catch (const std::exception& e) {
    err << "mpile: " << e.what() << '\n';
    return exit_failure;
  }
}

} // namespace mpile
