#pragma once
// Fixture: a folder the include check gives no rank.
