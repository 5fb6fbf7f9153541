// rhabel/abel.hpp: umbrella header of the abel module (rhabel::abel).
#pragma once

#include "rhabel/quadrature.hpp"
