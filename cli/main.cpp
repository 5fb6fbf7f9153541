// build/bin/rhabel: the command-line front end of rhabel.
#include "commands.hpp"

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"rhabel: generalized Abel equations and viscoelastic sliding contact", "rhabel"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "rhabel 0.1.0");
  rhabel::cli::command_action action;
  rhabel::cli::add_rule_command(app, action);
  rhabel::cli::add_solve_command(app, action);
  // CLI11 would report an unknown first word as "a subcommand is required": name it instead.
  if (argc > 1 && argv[1][0] != '-') {
    try {
      app.get_subcommand(argv[1]);
    } catch (const CLI::OptionNotFound&) {
      std::cerr << "rhabel: unknown command '" << argv[1] << "' (valid: rule, solve; see rhabel --help)\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "rhabel: " << e.what() << " (see rhabel --help)\n";
    return 2;
  }
  try {
    return action ? action() : 2;
  } catch (const rhabel::cli::input_error& e) {
    std::cerr << "rhabel: " << e.what() << '\n';
    return 2;
  } catch (const std::domain_error& e) {  // a library routine rejected a parameter
    std::cerr << "rhabel: " << e.what() << '\n';
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "rhabel: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "rhabel: internal error: " << e.what() << '\n';
    return 1;
  }
}
