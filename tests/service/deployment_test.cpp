// The deployment recipes of vsi serve, without Docker or Kubernetes (neither
// runs on the machine this was written on): the command lines they hold
// start a real server, with the token their environment gives, and the
// ports and paths they name agree with each other.
#include <filesystem>
#include <regex>

#include <nlohmann/json.hpp>

#include "../cli/vsi_test_support.hpp"
#include "serve_process.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
const std::filesystem::path kDocker = std::filesystem::path(RAILVSI_SOURCE_DIR) / "docker";

class DeploymentTest : public VsiCliTest {
 protected:
  // `command` with its /data paths moved to this test's folder and --port
  // set to 0 (a free port); the port it named in *port.
  std::vector<std::string> local(std::vector<std::string> command, std::string* port) const {
    for (std::size_t i = 0; i < command.size(); ++i) {
      if (command[i].starts_with("/data/")) command[i] = (dir_ / command[i].substr(6)).string();
      if (command[i] == "--port" && i + 1 < command.size()) {
        *port = command[i + 1];
        command[i + 1] = "0";
      }
    }
    return command;
  }
  // Starts `command`; checks that it listens off loopback, that the API
  // wants the token and takes it, and that `probe` answers 200.
  void expect_serves(const std::vector<std::string>& command, const std::string& probe) const {
    ServeProcess server(command, dir_, {"RAILVSI_TOKEN=deploy-test-token"}, true);
    ASSERT_TRUE(server.running()) << server.log();
    EXPECT_NE(server.log().find("listening on http://0.0.0.0:"), std::string::npos) << server.log();
    const auto c = server.client();
    const auto probed = c->Get(probe.c_str());
    ASSERT_TRUE(probed);
    EXPECT_EQ(probed->status, 200);
    EXPECT_EQ(token_statuses(*c, "deploy-test-token"), (std::vector<int>{401, 401, 200}));
    EXPECT_TRUE(std::filesystem::exists(dir_ / "vsi-results.sqlite"));  // the store in the volume
    // Without the token the same command refuses to start (exit 2).
    ServeProcess refused(command, dir_, {}, true);
    EXPECT_FALSE(refused.running());
    EXPECT_EQ(refused.exit_code(), 2) << refused.log();
  }
};

TEST_F(DeploymentTest, KubernetesDeploymentRunsServeAndItsServiceReachesIt) {
  const json list = json::parse(read_text(kDocker / "k8s-serve.json"));
  json deployment, service, claim;
  for (const json& item : list.at("items")) {
    if (item["kind"] == "Deployment") deployment = item;
    if (item["kind"] == "Service") service = item;
    if (item["kind"] == "PersistentVolumeClaim") claim = item;
  }
  ASSERT_TRUE(deployment.is_object() && service.is_object() && claim.is_object());
  const json pod = deployment["spec"]["template"]["spec"];
  const json container = pod["containers"][0];
  // The Service selects the pods and targets the container's named port.
  EXPECT_EQ(service["spec"]["selector"], deployment["spec"]["template"]["metadata"]["labels"]);
  EXPECT_EQ(service["spec"]["ports"][0]["targetPort"], container["ports"][0]["name"]);
  // The store is on the claim, mounted where --db points.
  EXPECT_EQ(pod["volumes"][0]["persistentVolumeClaim"]["claimName"], claim["metadata"]["name"]);
  EXPECT_EQ(container["volumeMounts"][0]["mountPath"], "/data");
  // One writer of the SQLite store at a time.
  EXPECT_EQ(deployment["spec"]["replicas"], 1);
  EXPECT_EQ(deployment["spec"]["strategy"]["type"], "Recreate");
  // The token comes from a Secret into RAILVSI_TOKEN.
  bool token_from_secret = false;
  for (const json& e : container["env"])
    token_from_secret |= e["name"] == "RAILVSI_TOKEN" && e.contains("valueFrom");
  EXPECT_TRUE(token_from_secret);

  std::vector<std::string> command = container["command"].get<std::vector<std::string>>();
  for (const json& a : container["args"]) command.push_back(a.get<std::string>());
  ASSERT_EQ(command.front(), "vsi");
  command.erase(command.begin());
  std::string port;
  command = local(command, &port);
  EXPECT_EQ(port, std::to_string(container["ports"][0]["containerPort"].get<int>()));
  expect_serves(command, container["readinessProbe"]["httpGet"]["path"]);
}

TEST_F(DeploymentTest, DockerImageRunsServeByDefault) {
  const std::string dockerfile = read_text(kDocker / "Dockerfile");
  std::smatch entry, cmd, expose;
  ASSERT_TRUE(std::regex_search(dockerfile, entry, std::regex(R"(\nENTRYPOINT (\[.*\]))")));
  ASSERT_TRUE(std::regex_search(dockerfile, cmd, std::regex(R"(\nCMD (\[.*\]))")));
  ASSERT_TRUE(std::regex_search(dockerfile, expose, std::regex(R"(\nEXPOSE ([0-9]+))")));
  std::vector<std::string> command = json::parse(entry[1].str()).get<std::vector<std::string>>();
  for (const json& a : json::parse(cmd[1].str())) command.push_back(a.get<std::string>());
  ASSERT_EQ(command.front(), "vsi");
  command.erase(command.begin());
  EXPECT_EQ(command.front(), "serve");
  std::string port;
  command = local(command, &port);
  EXPECT_EQ(port, expose[1].str());
  expect_serves(command, "/");
}

}  // namespace
}  // namespace railvsi::test
