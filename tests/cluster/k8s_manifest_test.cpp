// The manifests vsi k8s writes, validated by an independent validator: the
// npm package kubernetes-models (major 5), whose Job model carries a
// validator generated from the Kubernetes OpenAPI schema, run by
// validate_k8s_job.mjs beside this file. That script also rejects fields
// the schema does not know (the package has no strict option; see the
// script), as a server with strict field validation does. tests/setup
// installs the package into BUILD/npm; without node or the package the
// tests are skipped and say why. No cluster runs here.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "shards/cluster_recipes.hpp"
#include "slurm_cluster.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

// The validator's verdict on one manifest file.
struct Verdict {
  int exit_code = -1;  // 0 valid, 1 invalid, 77 validator not available
  std::string message;  // its stdout and stderr
};

class K8sManifests : public ServiceTest {
 protected:
  void SetUp() override {
    ServiceTest::SetUp();
    node_ = which("node");
    if (node_.empty()) GTEST_SKIP() << "node not found: the Kubernetes manifests are not validated (tests/setup installs nodejs)";
    const Verdict probe = validate(write_json("empty-object.json", json::object()));
    if (probe.exit_code == 77)
      GTEST_SKIP() << "the Kubernetes manifest validator is not available (tests/setup installs kubernetes-models@5 "
                      "with npm into " RAILVSI_NPM_PREFIX "): "
                   << probe.message;
  }

  Verdict validate(const fs::path& manifest) const {
    const std::string tag = "validate-" + manifest.stem().string();
    Child child({node_, RAILVSI_K8S_VALIDATOR, RAILVSI_NPM_PREFIX, manifest.string()}, dir_ / (tag + ".out"),
                dir_ / (tag + ".err"));
    Verdict v;
    v.exit_code = child.wait();
    v.message = read_text(dir_ / (tag + ".out")) + read_text(dir_ / (tag + ".err"));
    return v;
  }
  Verdict validate(const std::string& name, const json& manifest) const { return validate(write_json(name, manifest)); }

  std::string node_;
};

TEST_F(K8sManifests, WrittenManifestsAreValidKubernetesJobs) {
  const auto study = write_json("tiny.json", tiny_study());
  const auto out = dir_ / "k8s";
  const VsiResult r = vsi({"k8s", study.string(), "--shards", "3", "--image", "registry.example/railvsi:1", "--out",
                           out.string(), "--cpus-per-task", "2", "--memory", "3Gi"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream shards_in(out / "k8s-shards-job.json"), merge_in(out / "k8s-merge-job.json");
  const json shards = json::parse(shards_in), merge = json::parse(merge_in);
  for (const char* name : {"k8s-shards-job.json", "k8s-merge-job.json"}) {
    const Verdict v = validate(out / name);
    EXPECT_EQ(v.exit_code, 0) << v.message;
    EXPECT_NE(v.message.find("valid (kubernetes-models 5."), std::string::npos) << v.message;
  }

  // What the validator cannot say: completion index K works shard K of 3.
  const json& spec = shards["spec"];
  EXPECT_EQ(spec["completionMode"], "Indexed");
  EXPECT_EQ(spec["completions"], 3);
  EXPECT_EQ(spec["template"]["spec"]["restartPolicy"], "Never");  // needed by backoffLimitPerIndex
  EXPECT_EQ(spec["backoffLimitPerIndex"], 3);
  const json& worker = spec["template"]["spec"]["containers"][0];
  EXPECT_EQ(worker["image"], "registry.example/railvsi:1");
  EXPECT_EQ(worker["args"][2], "/shards/shard-$(JOB_COMPLETION_INDEX).sqlite");
  EXPECT_EQ(worker["env"][0]["name"], "JOB_COMPLETION_INDEX");
  EXPECT_EQ(worker["env"][0]["valueFrom"]["fieldRef"]["fieldPath"],
            "metadata.annotations['batch.kubernetes.io/job-completion-index']");
  EXPECT_EQ(worker["resources"]["requests"]["cpu"], "2");
  EXPECT_EQ(worker["resources"]["limits"]["memory"], "3Gi");
  EXPECT_EQ(worker["volumeMounts"][0]["mountPath"], "/shards");
  EXPECT_EQ(spec["template"]["spec"]["volumes"][0]["persistentVolumeClaim"]["claimName"], "railvsi-shards");
  const json& merge_args = merge["spec"]["template"]["spec"]["containers"][0]["args"];
  EXPECT_EQ(merge_args, json::array({"merge", "/shards/shard-0.sqlite", "/shards/shard-1.sqlite",
                                     "/shards/shard-2.sqlite", "--into", "/shards/results.sqlite"}));
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::filesystem::exists(out / ("shard-" + std::to_string(k) + ".sqlite")));
}

TEST_F(K8sManifests, TheValidatorRejectsWhatAServerWouldReject) {
  scheduler::K8sOptions o;
  o.study = {std::string(64, 'a'), "t", 4, 1, 60.0};
  o.image = "railvsi";
  const json good = scheduler::k8s_shard_job(o);
  const Verdict ok = validate("good.json", good);
  ASSERT_EQ(ok.exit_code, 0) << ok.message;

  // Each rejection is checked for the validator's reason, so that a crash
  // of the script cannot pass for a rejection.
  json misspelled = good;
  misspelled["spec"]["completionmode"] = misspelled["spec"]["completionMode"];
  misspelled["spec"].erase("completionMode");
  const Verdict unknown = validate("misspelled.json", misspelled);
  EXPECT_EQ(unknown.exit_code, 1) << unknown.message;
  EXPECT_NE(unknown.message.find("unknown field(s) /spec/completionmode"), std::string::npos) << unknown.message;

  json wrong_type = good;
  wrong_type["spec"]["completions"] = "4";
  const Verdict type = validate("wrong-type.json", wrong_type);
  EXPECT_EQ(type.exit_code, 1) << type.message;
  EXPECT_NE(type.message.find("data/spec/completions must be integer"), std::string::npos) << type.message;

  json no_name = good;
  no_name["spec"]["template"]["spec"]["containers"][0].erase("name");  // required by the schema
  const Verdict required = validate("no-name.json", no_name);
  EXPECT_EQ(required.exit_code, 1) << required.message;
  EXPECT_NE(required.message.find("containers/0 must have required property name"), std::string::npos)
      << required.message;
}

}  // namespace
}  // namespace railvsi::test
