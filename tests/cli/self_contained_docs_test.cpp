// The product is self-contained: no file of the repository cites a document
// that is not in it (the design notes and the data notes of the authors'
// workspace). Every fact carries its primary source instead.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vsi_test_support.hpp"

namespace railvsi::test {
namespace {

namespace fs = std::filesystem;

// Spelled in pieces so that this file does not match itself.
const std::vector<std::string> kForeignDocuments = {std::string("DESIGN") + ".md", std::string("DATA") + ".md",
                                                    std::string("shared") + "/reference"};

bool skipped_directory(const fs::path& dir) {
  const std::string name = dir.filename().string();
  return name == ".git" || name.rfind("build", 0) == 0 || name == "Testing";
}

TEST(SelfContainedDocuments, NoTrackedFileCitesADocumentOutsideTheRepository) {
  const fs::path root(RAILVSI_SOURCE_DIR);
  std::vector<std::string> offenders;
  int files = 0;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
    if (it->is_directory()) {
      if (skipped_directory(it->path())) it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file()) continue;
    ++files;
    const std::string text = read_text(it->path());
    for (const auto& name : kForeignDocuments)
      if (text.find(name) != std::string::npos)
        offenders.push_back(fs::relative(it->path(), root).string() + " cites " + name);
  }
  EXPECT_GT(files, 100);
  for (const auto& o : offenders) ADD_FAILURE() << o;
}

}  // namespace
}  // namespace railvsi::test
