// rhabel solve SCENE.json: placeholder until the punch layer lands.
#include "commands.hpp"

namespace rhabel::cli {
void add_solve_command(CLI::App& app, command_action& action) {
  auto* solve = app.add_subcommand("solve", "Solve a scene (not available yet)");
  solve->callback([&action] { action = [] { throw input_error("solve: not implemented yet"); return 1; }; });
}
}  // namespace rhabel::cli
