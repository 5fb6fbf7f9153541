// rhabel/punch.hpp: umbrella header of the punch module (rhabel::punch).
#pragma once

#include "rhabel/abel.hpp"
#include "rhabel/riemann.hpp"
