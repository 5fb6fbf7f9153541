// build/bin/rhabel: the command-line front end of rhabel. Exit codes: commands.hpp.
#include "commands.hpp"

#include <exception>
#include <iostream>
#include <string>
#include <string_view>

namespace {

// The command named in messages: "rule gauss-jacobi", "rule", "solve", or "" before one is known.
std::string command_label(int argc, char** argv) {
  if (argc < 2) return {};
  const std::string_view first = argv[1];
  if (first == "solve" || first == "sweep" || first == "fit-material") return std::string(first);
  if (first == "rule") return argc > 2 && std::string_view(argv[2]) == "gauss-jacobi" ? "rule gauss-jacobi" : "rule";
  return {};
}

// One line on stderr: "rhabel: <message>", control characters escaped.
int report(const std::string& message, int code) {
  std::cerr << "rhabel: " << rhabel::cli::one_line(message) << '\n';
  return code;
}

// "<command>: <kind><message>": a message from a command already starts with its name (not
// repeated), a library message gets it prepended.
std::string with_label(const std::string& label, std::string_view message, std::string_view kind = {}) {
  if (label.empty()) return std::string(kind) + std::string(message);
  const std::string prefix = label + ": ";
  if (message.starts_with(prefix)) message.remove_prefix(prefix.size());
  return prefix + std::string(kind) + std::string(message);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace rhabel::cli;
  CLI::App app{"rhabel: generalized Abel equations and viscoelastic sliding contact", "rhabel"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "rhabel 0.1.0");
  app.footer(exit_code_help);
  command_action action;
  add_rule_command(app, action);
  add_solve_command(app, action);
  add_fit_material_command(app, action);
  add_sweep_command(app, action);
  const std::string label = command_label(argc, argv);
  // CLI11 would report an unknown first word as "a subcommand is required": name it instead.
  if (argc > 1 && argv[1][0] != '-') {
    try {
      app.get_subcommand(argv[1]);
    } catch (const CLI::OptionNotFound&) {
      return report(std::string("unknown command '") + argv[1] + "' (valid: rule, solve, fit-material, sweep; see rhabel --help)",
                    exit_bad_input);
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return report(with_label(label, e.what()) + " (see rhabel " + (label.empty() ? "" : label + " ") + "--help)",
                  exit_bad_input);
  }
  try {
    return action ? action() : exit_bad_input;
  } catch (const input_error& e) {  // already "<command>: ..."
    return report(e.what(), exit_bad_input);
  } catch (const write_error& e) {  // already "<command>: ..."
    return report(e.what(), exit_bad_input);
  } catch (const std::domain_error& e) {  // a library routine rejected a parameter
    return report(with_label(label, e.what()), exit_bad_input);
  } catch (const std::invalid_argument& e) {
    return report(with_label(label, e.what()), exit_bad_input);
  } catch (const std::exception& e) {
    return report(with_label(label, e.what(), "internal error: "), exit_internal_error);
  }
}
