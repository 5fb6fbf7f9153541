// rhabel/punch.hpp: umbrella header of the punch module (rhabel::punch).
// Rigid indentors (parabolic, wedge, flat, general profile) sliding over a power-law viscoelastic
// half-space: contact intervals, pressure, hysteretic friction, surface displacement; sampled
// profiles with an unknown set of contacts (rhabel/punch/profile.hpp).
// See rhabel/punch/contact.hpp for the theory, the regimes and the accuracy of every output.
#pragma once

#include "rhabel/abel.hpp"
#include "rhabel/riemann.hpp"
#include "rhabel/punch/contact.hpp"
#include "rhabel/punch/profile.hpp"
#include "rhabel/punch/profile_bem.hpp"
