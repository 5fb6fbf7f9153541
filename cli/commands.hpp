// The subcommands of build/bin/rhabel. Each lives in its own <name>_command.cpp and registers
// itself on the application; main.cpp owns parsing and the exit-code policy (also printed by
// `rhabel --help` and documented in examples/README.md):
//   0  success: the result was written completely
//   1  internal error (a bug: please report it)
//   2  bad input (one line on stderr naming the parameter), a scene the solver cannot solve,
//      or an output that could not be written (stdout or a CSV file; no partial CSV is left)
//   3  `solve`: the result was written completely, but its status is not "ok" (the result's
//      "status" names why: not_converged, tension, load_mismatch, contacts_merge), or its
//      master-curve fit is not ok; `fit-material`: the fit's status is not ok; `sweep`: every
//      row was written, but some row's status is not ok
// Every message is one line on stderr, `rhabel: <command>: <message>`; control characters in
// echoed values are escaped (one_line).
#pragma once

#include <CLI/CLI.hpp>

#include <rhabel/materials/text_file.hpp>
#include <rhabel/scene.hpp>

#include <cstdlib>
#include <exception>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>

namespace rhabel::cli {

// The scene layer's names (rhabel/scene.hpp) are the command line's: input_error is bad input and
// write_error an output (stdout, a CSV file) not written completely (each printed as one line,
// exit code 2); one_line keeps an echoed value on one line.
using namespace rhabel::scene;


/// Exit codes of build/bin/rhabel (see the top of this file).
inline constexpr int exit_ok = 0;
inline constexpr int exit_internal_error = 1;
inline constexpr int exit_bad_input = 2;  ///< also: cannot solve, cannot write
inline constexpr int exit_not_ok = 3;     ///< solve: result written, its status is not "ok"

/// The exit code main() gives an exception leaving a command: exit_bad_input for input_error,
/// write_error and a library's rejection of a parameter (std::domain_error, std::invalid_argument),
/// exit_internal_error for anything else.
inline int exit_code_of(const std::exception& e) {
  if (dynamic_cast<const input_error*>(&e) || dynamic_cast<const write_error*>(&e) ||
      dynamic_cast<const std::domain_error*>(&e) || dynamic_cast<const std::invalid_argument*>(&e)) {
    return exit_bad_input;
  }
  return exit_internal_error;
}

/// The exit-code table as printed in the help texts.
inline constexpr const char* exit_code_help =
    "Exit codes:\n"
    "  0  ok: the result was written completely\n"
    "  1  internal error (please report it)\n"
    "  2  bad input, a scene that cannot be solved, or an output that could not be written\n"
    "     (stdout or a CSV file); one line on stderr, no partial CSV file is left\n"
    "  3  solve: the result was written completely, but its status is not ok (see its \"status\");\n"
    "     fit-material: the fit is not ok; sweep: all rows written, some row is not ok";

/// The check of a floating-point option: a number in [lo, hi] (with lo_open, in (lo, hi]). Unlike
/// CLI::Range and CLI::PositiveNumber it refuses NaN (every comparison with NaN is false, so those
/// let it through to the solver, where it surfaced as a non-ok result or an internal parameter's
/// message); CLI11 reports the failure naming the option (exit code 2).
inline CLI::Validator number_in(double lo, double hi, bool lo_open = false) {
  const bool bounded = hi < std::numeric_limits<double>::max();
  const std::string range = bounded ? (lo_open ? "(" : "[") + CLI::detail::to_string(lo) + ", " +
                                          CLI::detail::to_string(hi) + "]"
                                    : std::string(lo_open ? "> " : ">= ") + CLI::detail::to_string(lo);
  return CLI::Validator(
      [lo, hi, lo_open, bounded, range](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') return "Value " + text + " is not a number";
        const bool above_lo = lo_open ? v > lo : v >= lo;
        if (!(above_lo && v <= hi)) return "Value " + text + (bounded ? " not in " : " not ") + range;
        return {};
      },
      bounded ? "FLOAT in " + range : "FLOAT " + range);
}

/// --acceptance of `solve` and `sweep`: punch::solve_options::acceptance, the bar of status "ok";
/// left at 0 when not given (the solver's default: run_request::acceptance).
inline CLI::Option* add_acceptance_option(CLI::App* command, double& acceptance) {
  return command
      ->add_option("--acceptance", acceptance,
                   "the bar of status \"ok\": relative residual of (8), negative pressure, load defect and error "
                   "estimate (default 1e-9; 1e-4 for profile.solver boundary_element, a first-order method; a "
                   "sampled profile is worth ~1e-6)")
      ->check(number_in(1e-15, 0.1));
}

/// --tolerance of `solve` and `sweep`: punch::solve_options::tolerance, the relative tolerance of the
/// root finders and expansions (default 1e-12), in [min_tolerance, max_tolerance].
inline constexpr double min_tolerance = 1e-15;
inline constexpr double max_tolerance = 1e-2;
inline CLI::Option* add_tolerance_option(CLI::App* command, double& tolerance) {
  return command
      ->add_option("--tolerance", tolerance,
                   "relative tolerance of the root finders and expansions (default 1e-12): larger is faster and "
                   "less accurate (examples/README.md, work-precision table)")
      ->check(number_in(min_tolerance, max_tolerance));
}

/// What a subcommand runs once the command line has been parsed; returns the exit code.
using command_action = std::function<int()>;

void add_rule_command(CLI::App& app, command_action& action);
void add_solve_command(CLI::App& app, command_action& action);
void add_fit_material_command(CLI::App& app, command_action& action);
void add_sweep_command(CLI::App& app, command_action& action);

}  // namespace rhabel::cli
