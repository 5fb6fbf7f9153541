// rhabel/scene.hpp: the scene layer between the physics (rhabel::punch, rhabel::materials) and the
// front ends (the command line `rhabel`, the Python package): the JSON scene parsed and validated
// (scene.hpp), solved and written as the result document (solve.hpp), a measured master curve's
// fixed point (material.hpp), sweeps of scenes (sweep.hpp), and its one error type (error.hpp).
#pragma once

#include "rhabel/scene/error.hpp"
#include "rhabel/scene/material.hpp"
#include "rhabel/scene/scene.hpp"
#include "rhabel/scene/solve.hpp"
#include "rhabel/scene/sweep.hpp"
