// File names in a study (imported matrices, CSV profiles) are relative to
// the study file's directory, whatever the directory vsi runs from: they are
// made absolute at submission, so that workers started anywhere find them.
#include <nlohmann/json.hpp>

#include "exported_beam.hpp"
#include "vsi_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

class StudyPaths : public VsiCliTest {
 protected:
  // d3/study.json over an imported beam (d3/K.mtx, d3/M.mtx, d3/map.json)
  // with a CSV profile d3/prof.csv: 2 jobs.
  void write_study_in_d3() const {
    std::filesystem::create_directories(dir_ / "d3");
    const ExportedBeam beam = exported_beam(8, 10.0, true);
    write("d3/K.mtx", matrix_market(beam.K, true));
    write("d3/M.mtx", matrix_market(beam.M, true));
    write_json("d3/map.json", beam.map);
    write("d3/prof.csv", "x_m,r_m\n-20,0\n0,0.0005\n10,0.001\n40,0\n");
    json study = imported_scene(small_scene());
    study.erase("speed_kmh");
    study.erase("train");
    study.erase("irregularity");
    study.erase("$schema");
    study.erase("description");
    study["name"] = "relative";
    study["trains"] = json::array({small_scene()["train"]});
    study["speeds_kmh"] = {100, 150};
    study["irregularities"] = json::array({{{"csv", "prof.csv"}}});
    write_json("d3/study.json", study);
  }

  // vsi with its working directory in `cwd` (relative to the test directory).
  VsiRun vsi_in(const std::string& cwd, const std::string& args) const {
    const auto out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    const std::string command = "cd '" + (dir_ / cwd).string() + "' && " + VSI_BINARY + " " + args + " >'" +
                                out.string() + "' 2>'" + err.string() + "'";
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(out), read_text(err)};
  }

};

// `vsi submit d3/study.json` used to resolve d3/K.mtx against d3 again:
// d3/d3/K.mtx: cannot open (exit 2).
TEST_F(StudyPaths, SubmitFromTheParentDirectoryFindsImportedMatricesAndProfiles) {
  write_study_in_d3();
  const VsiRun submitted = vsi_in(".", "submit d3/study.json --db r.sqlite");
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
  EXPECT_NE(submitted.out.find(": 2 jobs, 2 new"), std::string::npos) << submitted.out;
  // A worker started elsewhere (here: inside d3) runs every job.
  const VsiRun worked = vsi_in("d3", "work --db ../r.sqlite --threads 1");
  EXPECT_EQ(worked.exit_code, 0) << worked.err;
  const std::string sql = "sqlite3 '" + (dir_ / "r.sqlite").string() +
                          "' \"SELECT count(*) FROM job_records WHERE state = 'done' AND instr(scene, '" +
                          (dir_ / "d3" / "K.mtx").string() + "') > 0 AND instr(scene, '" +
                          (dir_ / "d3" / "prof.csv").string() + "') > 0\" > '" + (dir_ / "count.txt").string() + "'";
  ASSERT_EQ(std::system(sql.c_str()), 0);
  EXPECT_EQ(read_text(dir_ / "count.txt"), "2\n") << "both jobs done, their scenes naming the files absolutely";
}

// `cd d3; vsi run study.json` used to store "prof.csv" as it was; the jobs
// then failed at work time (/prof.csv: cannot open).
TEST_F(StudyPaths, RunFromTheStudysDirectoryStoresAbsoluteNamesAndFinishes) {
  write_study_in_d3();
  const VsiRun run = vsi_in("d3", "run study.json --db ../r.sqlite --threads 1");
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("2 jobs shown"), std::string::npos) << run.out;
  const std::string sql = "sqlite3 '" + (dir_ / "r.sqlite").string() +
                          "' \"SELECT count(*) FROM job_records WHERE state = 'done' AND instr(scene, '\\\"" +
                          (dir_ / "d3" / "prof.csv").string() + "\\\"') > 0\" > '" +
                          (dir_ / "count.txt").string() + "'";
  ASSERT_EQ(std::system(sql.c_str()), 0);
  EXPECT_EQ(read_text(dir_ / "count.txt"), "2\n");
}

}  // namespace
}  // namespace railvsi::test
