// rhabel rule gauss-jacobi N A B
//   Prints the N-point Gauss-Jacobi rule for the weight (1-x)^A (1+x)^B on [-1, 1] as CSV,
//   header x,one_minus_x,one_plus_x,weight, one node a line in increasing x, 17 significant
//   digits (enough to round-trip a double).
#include "commands.hpp"

#include <rhabel/quadrature.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace rhabel::cli {
namespace {

constexpr unsigned long long max_rule_size = 100'000'000;  // 10^8 nodes: a few GB of output

unsigned long long parse_count(const std::string& text, const char* name) {
  char* end = nullptr;
  errno = 0;
  const bool digits_only = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
  const unsigned long long value = std::strtoull(text.c_str(), &end, 10);
  if (!digits_only || errno == ERANGE || *end != '\0' || value < 1 || value > max_rule_size) {
    throw input_error(std::string("rule gauss-jacobi: ") + name + " = '" + text +
                      "' is not an integer in the valid range [1, 100000000]");
  }
  return value;
}

double parse_exponent(const std::string& text, const char* name) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(value) || !(value > -1)) {
    throw input_error(std::string("rule gauss-jacobi: ") + name + " = '" + text +
                      "' is not a number in the valid range (-1, inf)");
  }
  return value;
}

}  // namespace

void add_rule_command(CLI::App& app, command_action& action) {
  auto* rule = app.add_subcommand("rule", "Print a quadrature rule as CSV");
  rule->require_subcommand(1);
  auto* jacobi = rule->add_subcommand(
      "gauss-jacobi", "N-point Gauss-Jacobi rule for (1-x)^A (1+x)^B on [-1,1]: x,one_minus_x,one_plus_x,weight");
  auto arguments = std::make_shared<std::array<std::string, 3>>();
  jacobi->add_option("N", (*arguments)[0], "number of nodes, 1 <= N <= 1e8")->required();
  jacobi->add_option("A", (*arguments)[1], "exponent of (1-x), A > -1")->required();
  jacobi->add_option("B", (*arguments)[2], "exponent of (1+x), B > -1")->required();
  jacobi->callback([&action, arguments] {
    action = [arguments] {
      const auto n = parse_count((*arguments)[0], "N");
      const double p = parse_exponent((*arguments)[1], "A");
      const double q = parse_exponent((*arguments)[2], "B");
      const auto rule = quadrature::gauss_jacobi<double>(static_cast<std::size_t>(n), p, q);
      std::puts("x,one_minus_x,one_plus_x,weight");
      for (std::size_t i = 0; i < rule.size(); ++i) {
        std::printf("%.17g,%.17g,%.17g,%.17g\n", rule.x[i], rule.hi_minus_x[i], rule.x_minus_lo[i], rule.weight[i]);
      }
      return std::fflush(stdout) == 0 ? 0 : 1;
    };
  });
}

}  // namespace rhabel::cli
