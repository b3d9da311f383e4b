#include <iostream>

#include "cli/commands.hpp"
#include "io/document_kind.hpp"

namespace railvsi::cli {

int validate_command(const std::string& file) {
  const DocumentKind kind = validate_document(file);
  std::cout << file << ": ok (" << document_kind_name(kind) << ")\n";
  return kExitOk;
}

}  // namespace railvsi::cli
