#pragma once
// A fixture for include_layers.sh: a header of the simulation layer, which
// may include core.
#include "core/uses_simulation.hpp"
