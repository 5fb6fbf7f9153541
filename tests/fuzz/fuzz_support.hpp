// tests/fuzz/fuzz_support.hpp: what the libFuzzer targets of tests/fuzz share.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>

namespace rhabel::fuzz {

/// Reports a finding of the target `target` on stderr and aborts (libFuzzer keeps the input).
[[noreturn]] inline void finding(const char* target, const char* what, const char* message = "") {
  std::fprintf(stderr, "%s: %s: %s\n", target, what, message);
  std::abort();
}

/// Runs `parse` (which stores what it parsed): true when it returned, false when it refused the
/// input with a `Refusal` (the command line's exit code 2). Any other exception is a finding naming
/// `what` (the parsing function).
template <class Refusal, class Parse>
bool accepted(const char* target, const char* what, Parse&& parse) {
  try {
    parse();
    return true;
  } catch (const Refusal&) {
    return false;
  } catch (const std::exception& e) {
    finding(target, what, e.what());
  }
}

}  // namespace rhabel::fuzz
