// vsi report --pdf without headless Chromium on PATH: a clear error, exit
// 2, before the database is opened, and no file written.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "vsi_test_support.hpp"

namespace railvsi::test {
namespace {

namespace fs = std::filesystem;

TEST(ReportPdf, WithoutChromiumItExitsTwoAndWritesNothing) {
  const fs::path dir = fs::temp_directory_path() / ("vsi-report-pdf-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path pdf = dir / "r.pdf", err = dir / "err.txt";
  const std::string command = "env PATH=/nonexistent " + std::string(VSI_BINARY) + " report --db '" +
                              (dir / "none.sqlite").string() + "' --study 0123456789ab --pdf '" + pdf.string() +
                              "' 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(read_text(err).find("headless Chromium: none found on PATH"), std::string::npos) << read_text(err);
  EXPECT_FALSE(fs::exists(pdf));
  EXPECT_FALSE(fs::exists(dir / "none.sqlite"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace railvsi::test
