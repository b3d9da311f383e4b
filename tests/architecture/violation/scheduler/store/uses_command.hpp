#pragma once
// Fixture: the service including the command line above it.
#include "cli/a_command.hpp"
