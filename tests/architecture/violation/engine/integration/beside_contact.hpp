#pragma once
// A fixture for include_layers.sh: a header of the contact/integration layer.
