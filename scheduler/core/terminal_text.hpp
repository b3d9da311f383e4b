#pragma once
// What vsi prints to a terminal: user strings (names, file names, error
// messages) with their control characters escaped, so that a name cannot
// move the cursor or recolour the screen, and the width of the terminal.
#include <string>
#include <string_view>

namespace railvsi::scheduler {

// Control characters (C0, DEL, C1 in UTF-8) as \n, \t, \x1b...; a
// backslash stays as it is. Other UTF-8 text passes unchanged.
std::string terminal_safe(std::string_view text);

// Columns of the terminal on `fd` (ioctl TIOCGWINSZ), else $COLUMNS when it
// is a positive number, else 80.
int terminal_columns(int fd);

}  // namespace railvsi::scheduler
