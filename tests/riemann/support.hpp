// tests/riemann/support.hpp: helpers shared by the riemann test suites (not part of the library).
#pragma once

#include <stdexcept>
#include <string>

namespace rhabel::riemann::test {

/// The message of the std::domain_error thrown by f(), or "" if f() throws none: the tests
/// check that bad input is reported naming the function, the parameter and its value.
template <class F>
std::string domain_error_message(F&& f) {
  try {
    f();
  } catch (const std::domain_error& e) {
    return std::string(e.what());
  }
  return std::string();
}

}  // namespace rhabel::riemann::test
