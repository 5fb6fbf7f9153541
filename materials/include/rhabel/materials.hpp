// rhabel/materials.hpp: umbrella header of rhabel::materials (power-law fits of master curves).
#pragma once

#include "rhabel/materials/master_curve.hpp"
#include "rhabel/materials/text_file.hpp"
