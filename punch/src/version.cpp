#include "rhabel/punch.hpp"

namespace rhabel::punch {
/// The library version, "major.minor.patch".
const char* version() { return "0.1.0"; }
}  // namespace rhabel::punch
