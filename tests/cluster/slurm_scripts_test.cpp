// The scripts vsi slurm writes, read as text and checked by bash -n
// (the real Slurm run is slurm_test.cpp).
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "../scheduler/scheduler_test_support.hpp"
#include "shards/cluster_recipes.hpp"

namespace railvsi::test {
namespace {

scheduler::SlurmOptions options(const std::string& study_name) {
  scheduler::SlurmOptions o;
  o.study = {std::string(64, 'b'), study_name, 4, 2, 30.0};
  o.dir = "/shared/it's here";
  o.vsi = "/opt/vsi";
  o.partition = "compute";
  o.time_limit = "4:00:00";
  return o;
}

class SlurmScripts : public ServiceTest {
 protected:
  // bash -n: the script parses.
  int syntax_check(const std::string& script) const {
    const auto file = dir_ / "script.sh";
    std::ofstream(file) << script;
    return std::system(("bash -n " + file.string()).c_str());
  }
};

TEST_F(SlurmScripts, ArrayTaskKWorksShardKWithRequeueAndTheMergeWaitsForTheArray) {
  const scheduler::SlurmScripts s = scheduler::slurm_scripts(options("study"));
  const std::string& a = s.array_script;
  for (const char* line : {"#SBATCH --array=0-3\n", "#SBATCH --requeue\n", "#SBATCH --cpus-per-task=2\n",
                           "#SBATCH --partition=compute\n", "#SBATCH --time=4:00:00\n",
                           "shard='/shared/it'\\''s here'/shard-${SLURM_ARRAY_TASK_ID}.sqlite\n",
                           "'/opt/vsi' work --db \"$shard\" --threads \"${SLURM_CPUS_PER_TASK:-2}\" --lease-s 30\n",
                           "if [ \"${SLURM_RESTART_COUNT:-0}\" -lt 3 ]; then\n",
                           "  scontrol requeue \"${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}\"\n"})
    EXPECT_NE(a.find(line), std::string::npos) << line << "\n---\n" << a;
  EXPECT_NE(s.merge_script.find("exec '/opt/vsi' merge '/shared/it'\\''s here'/shard-*.sqlite --into "
                                "'/shared/it'\\''s here/results.sqlite'\n"),
            std::string::npos)
      << s.merge_script;
  EXPECT_EQ(syntax_check(a), 0);
  EXPECT_EQ(syntax_check(s.merge_script), 0);
}

TEST_F(SlurmScripts, AStudyNameCannotEndTheComment) {
  const scheduler::SlurmScripts s = scheduler::slurm_scripts(options("evil\ntouch /tmp/pwned\r"));
  EXPECT_EQ(s.array_script.find("\ntouch"), std::string::npos) << s.array_script;
  EXPECT_NE(s.array_script.find("(evil touch /tmp/pwned )"), std::string::npos) << s.array_script;
  EXPECT_EQ(s.merge_script.find("\ntouch"), std::string::npos);
}

}  // namespace
}  // namespace railvsi::test
