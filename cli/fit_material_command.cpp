// rhabel fit-material CURVE.csv --speed U --length L [--temperature T --wlf C1,C2,T_ref] [--json]
//
// Prints the local power-law fit of a master curve at omega0 = U/L (rhabel/materials/master_curve.hpp):
// alpha, E1, omega0, the two alpha estimates (slope of |E*| over the window, and from tan delta at
// omega0), |E*(omega0)|, the frequency window and the status. With --json one object with the keys
// alpha, E1, omega0, alpha_slope, alpha_tan_delta, modulus, window, status, warning, master_curve,
// points (and temperature, log10_aT when shifted). Exit code 3 (result written) with a warning line
// on stderr when the status is not ok (poor_power_law, window_clipped); 2 for a bad curve or
// arguments (one line naming row and column), as every command.
#include "commands.hpp"

#include <rhabel/materials.hpp>
#include <rhabel/scene.hpp>

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace rhabel::cli {
namespace {

struct fit_arguments {
  std::string curve_path;
  double speed = 0, length = 0;
  std::vector<double> wlf;
  double temperature = 0;
  bool has_temperature = false;
  bool json = false;
  double window = 0.5, threshold = 0.05;
};

int run(const fit_arguments& args) {
  if (!args.wlf.empty() && args.wlf.size() != 3) {
    throw input_error("fit-material: --wlf needs three numbers C1,C2,T_ref, got " + std::to_string(args.wlf.size()));
  }
  if (args.wlf.empty() != !args.has_temperature) {
    throw input_error("fit-material: --temperature and --wlf go together (the WLF shift to that temperature)");
  }
  material_fit_request request;
  request.curve_path = args.curve_path;
  request.speed = args.speed;
  request.length = args.length;
  if (!args.wlf.empty()) request.wlf = materials::wlf_shift{args.wlf[0], args.wlf[1], args.wlf[2]};
  request.temperature = args.temperature;
  request.window_decades = args.window;
  request.threshold = args.threshold;
  const fitted_material fitted = fit_material(request);
  const auto& f = fitted.fit;
  const auto& curve = fitted.curve;
  const double log10_aT = fitted.log10_aT.value_or(0.0);
  std::string text;
  if (args.json) {
    const nlohmann::ordered_json doc = fitted_material_json(request, fitted);
    text = doc.dump(2) + "\n";
  } else {
    char buf[1024];
    std::snprintf(buf, sizeof buf,
                  "master curve     %s (%zu points, %.4g .. %.4g rad/s%s)\n"
                  "omega0 = U/L     %.10g rad/s\n"
                  "alpha            %.10g   (slope of |E*| over the window)\n"
                  "alpha_tan_delta  %.10g   ((2/pi) atan(tan delta) at omega0)\n"
                  "E1               %.10g Pa s^alpha\n"
                  "|E*(omega0)|     %.10g Pa\n"
                  "window           %.6g .. %.6g rad/s\n"
                  "status           %s\n",
                  one_line(args.curve_path).c_str(), curve.omega.size(), curve.omega.front(), curve.omega.back(),
                  args.wlf.empty() ? "" : (", shifted: log10 a_T = " + std::to_string(log10_aT)).c_str(), f.omega0,
                  f.alpha, f.alpha_tan_delta, f.E1, f.modulus, f.window_lo, f.window_hi, materials::to_string(f.status));
    text = buf;
  }
  errno = 0;
  std::fwrite(text.data(), 1, text.size(), stdout);
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    throw write_error(std::string("fit-material: cannot write to stdout: ") + std::strerror(errno));
  }
  if (!f.ok()) {
    std::cerr << "rhabel: fit-material: warning: " << one_line(std::string(materials::to_string(f.status)) + ": " + f.warning) << '\n';
    return exit_not_ok;
  }
  return exit_ok;
}

}  // namespace

void add_fit_material_command(CLI::App& app, command_action& action) {
  auto args = std::make_shared<fit_arguments>();
  auto* cmd = app.add_subcommand(
      "fit-material",
      "Fit the local power law E(t) = E1 t^-alpha of a master curve (CSV: omega,E_storage,E_loss or\n"
      "f_hz,E_storage,E_loss or omega,E_abs,tan_delta) at omega0 = U/L.");
  cmd->footer(exit_code_help);
  cmd->add_option("CURVE", args->curve_path, "master curve (CSV)")->required();
  cmd->add_option("--speed", args->speed, "sliding speed U")->required()->check(number_in(0.0, std::numeric_limits<double>::max(), true));
  cmd->add_option("--length", args->length, "contact length L (omega0 = U/L)")->required()->check(number_in(0.0, std::numeric_limits<double>::max(), true));
  auto* temperature = cmd->add_option("--temperature", args->temperature, "temperature (needs --wlf)");
  cmd->add_option("--wlf", args->wlf, "WLF constants C1,C2,T_ref of the curve")->delimiter(',')->expected(3);
  cmd->add_option("--window-decades", args->window, "half width of the fit window in decades (default 0.5)")
      ->check(number_in(0.01, 5.0));
  cmd->add_option("--threshold", args->threshold, "warning threshold on |alpha_slope - alpha_tan_delta| (default 0.05)")
      ->check(number_in(1e-6, 1.0));
  cmd->add_flag("--json", args->json, "print JSON");
  cmd->callback([&action, args, temperature] {
    args->has_temperature = temperature->count() > 0;
    action = [args] { return run(*args); };
  });
}

}  // namespace rhabel::cli
