#pragma once

// The command line: every subcommand's options declared on one CLI11 app, and the dispatch to the
// command that was given.
#include "app/describe_command.hpp"
#include "app/element_test_command.hpp"
#include "app/run_command.hpp"
#include "app/sweep_command.hpp"
#include "cases/verification/verification_cases.hpp"

#include <CLI/CLI.hpp>

#include <iosfwd>
#include <string>
#include <vector>

namespace mpile {

/// What `mpile verify` was asked.
struct VerifyRequest {
  std::vector<std::string> ids{"all"};
  bool list = false;
  verification::Options options;
  std::string scheme; // musl or usl; empty: the options' default
  bool csv = false;
};

/// The options of every subcommand, filled in by parsing, and the subcommands themselves (to ask
/// which one was given).
struct CommandLine {
  int threads = 0; // --threads; 0: all cores
  RunOptions run;  // run and check
  SweepOptions sweep;
  ElementTestOptions element_test;
  DescribeOptions describe;
  VerifyRequest verify;
  CLI::App* run_command = nullptr;
  CLI::App* check_command = nullptr;
  CLI::App* sweep_command = nullptr;
  CLI::App* element_test_command = nullptr;
  CLI::App* describe_command = nullptr;
};

/// Declares mpile's subcommands and options on `app`, bound to `line`.
void declare_command_line(CLI::App& app, CommandLine& line);

/// Runs the subcommand `line` was parsed for, on the calling thread's task arena, and returns its
/// exit status (exit_bad_input for a case id or value a command refuses).
int run_command_line(CommandLine& line, std::ostream& out, std::ostream& err);

} // namespace mpile
