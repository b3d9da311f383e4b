#pragma once
// A fixture for include_layers.sh: core may not include simulation.
#include "simulation/above_core.hpp"
