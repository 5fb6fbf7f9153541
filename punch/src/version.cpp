#include "rhabel/punch.hpp"

// RHABEL_VERSION is the project's version, project(rhabel VERSION ...) in the top CMakeLists.txt
// (the one place it is written; the Python package's metadata reads it from there too).
#ifndef RHABEL_VERSION
#error "RHABEL_VERSION is defined by punch/CMakeLists.txt"
#endif

namespace rhabel::punch {
/// The library version, "major.minor.patch".
const char* version() { return RHABEL_VERSION; }
}  // namespace rhabel::punch
