#pragma once
// The one way a vsi command is registered: a group of subcommands adds
// itself to the app in its constructor and, after app.parse(), runs the one
// that was parsed. main() holds the groups and asks each in turn; there is
// no default command.
#include <optional>

namespace railvsi::cli {

class CommandGroup {
 public:
  CommandGroup() = default;
  CommandGroup(const CommandGroup&) = delete;  // the app keeps pointers to its members
  CommandGroup& operator=(const CommandGroup&) = delete;
  virtual ~CommandGroup() = default;
  // The exit code of the group's subcommand that was parsed; nullopt when
  // none of them was.
  virtual std::optional<int> run_parsed() const = 0;
};

}  // namespace railvsi::cli
