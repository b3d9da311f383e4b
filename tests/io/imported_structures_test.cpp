// ImportedStructures: a study's trains share one read of a model's files,
// and a model named differently (other files) is read anew.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "beam_files.hpp"
#include "core/input_error.hpp"
#include "io/imported_structures.hpp"
#include "io/structure_import.hpp"

namespace railvsi::test {
namespace {

nlohmann::json beam_import(const char* K, const char* M, const char* map) {
  return {{"import", {{"K", K}, {"M", M}, {"map", map}}}};
}

TEST(ImportedStructures, TheSameFilesAreReadOnceAndGiveTheModelOfAReadOfTheirOwn) {
  ASSERT_FALSE(beam_files_dir().empty()) << "write_beam_files.py failed (python3-scipy?)";
  const auto s = beam_import("beam_K_sym.mtx", "beam_M_sym.mtx", "map_index.json");
  const auto none = nlohmann::json::object();
  ImportedStructures imports;
  const auto first = imports.import(s, none, beam_files_dir());
  const auto again = imports.import(s, none, beam_files_dir());
  EXPECT_EQ(first.get(), again.get());
  EXPECT_EQ(imports.reads(), 1);
  // What import_structure reads by itself.
  const auto alone = import_structure(s, none, beam_files_dir());
  EXPECT_EQ(first->num_dofs(), alone->num_dofs());
  EXPECT_EQ((first->K() - alone->K()).norm(), 0.0);
  EXPECT_EQ((first->M() - alone->M()).norm(), 0.0);
}

TEST(ImportedStructures, OtherFilesAreAnotherModel) {
  ASSERT_FALSE(beam_files_dir().empty()) << "write_beam_files.py failed (python3-scipy?)";
  ImportedStructures imports;
  const auto none = nlohmann::json::object();
  const auto by_equation = imports.import(beam_import("beam_K_sym.mtx", "beam_M_sym.mtx", "map_index.json"), none,
                                          beam_files_dir());
  const auto abaqus =
      imports.import(beam_import("beam_K.abq", "beam_M.abq", "map_abaqus.json"), none, beam_files_dir());
  EXPECT_EQ(imports.reads(), 2);
  EXPECT_NE(by_equation.get(), abaqus.get());
  EXPECT_NE(abaqus->info().import_notes, by_equation->info().import_notes);
}

TEST(ImportedStructures, AFileThatCannotBeReadFailsOnEveryCall) {
  ASSERT_FALSE(beam_files_dir().empty()) << "write_beam_files.py failed (python3-scipy?)";
  const auto s = beam_import("missing_K.mtx", "beam_M_sym.mtx", "map_index.json");
  ImportedStructures imports;
  for (int call = 0; call < 2; ++call)
    EXPECT_THROW(imports.import(s, nlohmann::json::object(), beam_files_dir()), InputError);
  EXPECT_EQ(imports.reads(), 0);
}

TEST(ImportedStructures, AnotherContentKeyIsReadAgain) {
  ASSERT_FALSE(beam_files_dir().empty()) << "write_beam_files.py failed (python3-scipy?)";
  const auto s = beam_import("beam_K_sym.mtx", "beam_M_sym.mtx", "map_index.json");
  const auto none = nlohmann::json::object();
  ImportedStructures imports;
  const auto first = imports.import(s, none, beam_files_dir(), "operator key 1");
  const auto second = imports.import(s, none, beam_files_dir(), "operator key 2");
  EXPECT_EQ(imports.reads(), 2);
  EXPECT_NE(first.get(), second.get());
  EXPECT_EQ(imports.import(s, none, beam_files_dir(), "operator key 1").get(), first.get());
  EXPECT_EQ(imports.reads(), 2);
}

TEST(ImportedStructures, KeepsAtMostItsCapacityAndLetsTheOldestGo) {
  ASSERT_FALSE(beam_files_dir().empty()) << "write_beam_files.py failed (python3-scipy?)";
  const auto a = beam_import("beam_K_sym.mtx", "beam_M_sym.mtx", "map_index.json");
  const auto b = beam_import("beam_K.abq", "beam_M.abq", "map_abaqus.json");
  const auto none = nlohmann::json::object();
  ImportedStructures one(1);
  const auto first_a = one.import(a, none, beam_files_dir());
  EXPECT_EQ(one.import(a, none, beam_files_dir()).get(), first_a.get());
  one.import(b, none, beam_files_dir());  // a goes
  EXPECT_EQ(one.reads(), 2);
  EXPECT_NE(one.import(a, none, beam_files_dir()).get(), first_a.get());
  EXPECT_EQ(one.reads(), 3);
  ImportedStructures none_kept(0);
  none_kept.import(a, none, beam_files_dir());
  none_kept.import(a, none, beam_files_dir());
  EXPECT_EQ(none_kept.reads(), 2);
}

}  // namespace
}  // namespace railvsi::test
