#pragma once
// A fixture for include_layers.sh: contact and integration are one layer
// (not reported), and simulation may include core (not reported).
#include "integration/beside_contact.hpp"
