// The subcommands of build/bin/rhabel. Each lives in its own <name>_command.cpp and registers
// itself on the application; main.cpp owns parsing and the exit-code policy:
//   0 success, 2 bad input (one line on stderr naming the parameter), 1 anything else.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <stdexcept>
#include <string>

namespace rhabel::cli {

/// Bad input found by a command after parsing: printed as one line, exit code 2.
struct input_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What a subcommand runs once the command line has been parsed; returns the exit code.
using command_action = std::function<int()>;

void add_rule_command(CLI::App& app, command_action& action);
void add_solve_command(CLI::App& app, command_action& action);

}  // namespace rhabel::cli
