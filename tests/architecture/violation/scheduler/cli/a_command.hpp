#pragma once
// Fixture: a command of the front end; the service must not include it.
