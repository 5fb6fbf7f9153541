// rhabel rule gauss-jacobi N A B
//   Prints the N-point Gauss-Jacobi rule for the weight (1-x)^A (1+x)^B on [-1, 1] as CSV,
//   header x,one_minus_x,one_plus_x,weight, one node a line in increasing x, 17 significant
//   digits (enough to round-trip a double).
//   A and B are limited to (-1, 30], the range of the accuracy contract of
//   rhabel::quadrature::gauss_jacobi (quadrature::gauss_jacobi_max_exponent); larger exponents
//   are refused (exit code 2) rather than answered with weights 0, inf or NaN (issue 14).
//   Numbers that underflow (1e-320, 1e-400) read as the subnormal or 0 they round to.
//   A failed write to stdout (a full disk, /dev/full, a closed descriptor) is exit code 2.
#include "commands.hpp"

#include <rhabel/quadrature.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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
  // strtod reports ERANGE also for a result that underflows to a subnormal or 0 (1e-320): that
  // value is in range; only an overflow (+-HUGE_VAL: 1e400) is refused.
  const bool syntax = !text.empty() && *end == '\0';
  const bool overflow = syntax && errno == ERANGE && !(std::fabs(value) < 1);
  const bool number = syntax && std::isfinite(value);
  if (overflow) {
    throw input_error(std::string("rule gauss-jacobi: ") + name + " = '" + text +
                      "' overflows a double; valid range (-1, 30]");
  }
  if (!number || !(value > -1)) {
    throw input_error(std::string("rule gauss-jacobi: ") + name + " = '" + text +
                      "' is not a number in the valid range (-1, 30]");
  }
  if (!(value <= quadrature::gauss_jacobi_max_exponent)) {
    throw input_error(std::string("rule gauss-jacobi: ") + name + " = '" + text +
                      "' is outside the valid range (-1, 30] (the limit 30 of the accuracy contract of "
                      "gauss_jacobi: larger exponents are not computed)");
  }
  return value;
}

[[noreturn]] void stdout_failed(int error) {
  throw write_error(std::string("rule gauss-jacobi: cannot write the rule to stdout: ") +
                    (error != 0 ? std::strerror(error) : "write error"));
}

}  // namespace

void add_rule_command(CLI::App& app, command_action& action) {
  auto* rule = app.add_subcommand("rule", "Print a quadrature rule as CSV");
  rule->require_subcommand(1);
  auto* jacobi = rule->add_subcommand(
      "gauss-jacobi", "N-point Gauss-Jacobi rule for (1-x)^A (1+x)^B on [-1,1]: x,one_minus_x,one_plus_x,weight");
  auto arguments = std::make_shared<std::array<std::string, 3>>();
  jacobi->add_option("N", (*arguments)[0], "number of nodes, 1 <= N <= 1e8")->required();
  jacobi->add_option("A", (*arguments)[1], "exponent of (1-x), -1 < A <= 30")->required();
  jacobi->add_option("B", (*arguments)[2], "exponent of (1+x), -1 < B <= 30")->required();
  jacobi->footer(exit_code_help);
  jacobi->callback([&action, arguments] {
    action = [arguments] {
      const auto n = parse_count((*arguments)[0], "N");
      const double p = parse_exponent((*arguments)[1], "A");
      const double q = parse_exponent((*arguments)[2], "B");
      const auto rule = quadrature::gauss_jacobi<double>(static_cast<std::size_t>(n), p, q);
      // A write error is sticky in the stream: test it every 4096 lines (a rule of 10^8 nodes
      // must not be formatted for nothing) and after the final flush.
      errno = 0;
      if (std::puts("x,one_minus_x,one_plus_x,weight") == EOF) stdout_failed(errno);
      for (std::size_t i = 0; i < rule.size(); ++i) {
        std::printf("%.17g,%.17g,%.17g,%.17g\n", rule.x[i], rule.hi_minus_x[i], rule.x_minus_lo[i], rule.weight[i]);
        if (i % 4096 == 4095 && std::ferror(stdout)) stdout_failed(errno);
      }
      if (std::fflush(stdout) != 0 || std::ferror(stdout)) stdout_failed(errno);
      return exit_ok;
    };
  });
}

}  // namespace rhabel::cli
