// vsi slurm and vsi k8s refuse, before writing anything, the values that
// would give an array whose every task exits 2 (a --lease-s vsi work
// refuses) or a manifest a Kubernetes server rejects.
#include <filesystem>

#include <gtest/gtest.h>

#include "../scheduler/scheduler_test_support.hpp"

namespace railvsi::test {
namespace {

class ClusterArguments : public ServiceTest {
 protected:
  // Exit 2, the option named on stderr, and no shard directory.
  void expect_refused(std::vector<std::string> args, const std::string& option) const {
    const auto out = dir_ / "out";
    args.insert(args.end(), {"--out", out.string()});
    const VsiResult r = vsi(args);
    std::string command;
    for (const auto& a : args) command += a + " ";
    EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << command << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << command << ": wrote shards";
    std::filesystem::remove_all(out);
  }
};

TEST_F(ClusterArguments, LeasesThatVsiWorkRefusesAreRefused) {
  const std::string study = write_json("tiny.json", tiny_study()).string();
  for (const char* lease : {"0.1", "nan", "inf", "1e9"}) {
    expect_refused({"slurm", study, "--shards", "2", "--lease-s", lease}, "--lease-s");
    expect_refused({"k8s", study, "--shards", "2", "--image", "railvsi:1", "--lease-s", lease}, "--lease-s");
  }
}

TEST_F(ClusterArguments, ManifestValuesKubernetesRejectsAreRefused) {
  const std::string study = write_json("tiny.json", tiny_study()).string();
  const std::vector<std::string> k8s{"k8s", study, "--shards", "2"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = k8s;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  expect_refused(with({"--image", ""}), "--image");
  expect_refused(with({"--image", "rail vsi"}), "--image");
  for (const char* memory : {"lots", "2GB", "0", "-1Gi", ""})
    expect_refused(with({"--image", "railvsi:1", "--memory", memory}), "--memory");
  for (const char* claim : {"../../x", "Shards", "x_y", ""})
    expect_refused(with({"--image", "railvsi:1", "--claim", claim}), "--claim");
  expect_refused({"slurm", study, "--shards", "2", "--partition", ""}, "--partition");
}

TEST_F(ClusterArguments, ValidValuesAreAccepted) {
  const std::string study = write_json("tiny.json", tiny_study()).string();
  const auto out = dir_ / "k8s";
  const VsiResult r = vsi({"k8s", study, "--shards", "2", "--image", "registry.example:5000/railvsi:1.2", "--memory",
                           "1.5Gi", "--claim", "railvsi.shards-2", "--lease-s", "0.5", "--out", out.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(out / "k8s-shards-job.json"));
  for (const char* memory : {"3e9", "1500M", "512Mi", "0.5Gi"}) {
    const auto o = dir_ / (std::string("m-") + memory);
    EXPECT_EQ(vsi({"k8s", study, "--shards", "1", "--image", "r", "--memory", memory, "--out", o.string()}).exit_code, 0)
        << memory;
  }
}

}  // namespace
}  // namespace railvsi::test
