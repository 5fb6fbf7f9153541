// rhabel/riemann.hpp: umbrella header of the riemann module (rhabel::riemann).
#pragma once

#include "rhabel/quadrature.hpp"
