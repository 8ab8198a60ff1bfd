// The array as an Ansible inventory (`lfcam capture inventory`), read back by Ansible itself,
// and the playbook it is made for, checked by Ansible (deploy/ansible/lfcam-node.yml). Without
// Ansible (Debian's ansible-core) those checks skip, unless LFCAM_REQUIRE_ANSIBLE=1
// (scripts/test.sh, which installs it), where that fails.
#include "lfcam/capture/ansible_inventory.h"

#include <fmt/core.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

ArrayConfig SmallArray() {
  ArrayConfig a;
  a.rows = 2;
  a.cols = 2;
  a.key_file = "array.key";
  a.nodes = NodesFromPattern(2, 2, "10.0.0.{index1}:8470");
  a.nodes[3].address = "[fd00::4]:8471";
  return a;
}

bool AnsibleRequired() {
  const char* required = std::getenv("LFCAM_REQUIRE_ANSIBLE");
  return required != nullptr && std::string(required) == "1";
}

TEST(AnsibleInventory, NamesEveryNodeByItsGridPositionWithItsAddressAndPort) {
  const std::string text =
      AnsibleInventory(SmallArray(), "/arrays/a.json", {"pi", "10.0.0.254", ""});
  EXPECT_NE(text.find("lfcam_nodes:"), std::string::npos);
  EXPECT_NE(text.find("lfcam_key_file: \"/arrays/array.key\""), std::string::npos) << text;
  EXPECT_NE(text.find("lfcam_chrony_server: \"10.0.0.254\""), std::string::npos);
  EXPECT_NE(text.find("ansible_user: \"pi\""), std::string::npos);
  EXPECT_NE(
      text.find("node-r00-c00:\n          ansible_host: \"10.0.0.1\"\n          lfcam_port: 8470"),
      std::string::npos)
      << text;
  EXPECT_NE(
      text.find("node-r01-c01:\n          ansible_host: \"fd00::4\"\n          lfcam_port: 8471"),
      std::string::npos)
      << text;
  ArrayConfig bad = SmallArray();
  bad.nodes[2].address = "10.0.0.3";
  EXPECT_NE(testing::ErrorOf([&] {
              AnsibleInventory(bad, "a.json", {});
            }).find("a.json: node (1, 0): address '10.0.0.3' is not HOST:PORT"),
            std::string::npos);
}

TEST(AnsibleInventory, AnsibleReadsItAndTheCommandWritesIt) {
  const fs::path dir = testing::MakeScratchDir("ansible_inventory");
  WriteArrayFile(dir / "array.json", SmallArray());
  std::ofstream(dir / "node.deb") << "not really a package";
  const auto run = testing::Lfcam(
      fmt::format("capture inventory {} --package {} --chrony-server 10.0.0.254 --out {}",
                  (dir / "array.json").string(), (dir / "node.deb").string(),
                  (dir / "inventory.yml").string()));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("4 nodes"), std::string::npos) << run.output;
  // Bad input: a missing package, an array file that does not parse, each named.
  auto bad = testing::Lfcam(fmt::format("capture inventory {} --package {}/nothing.deb",
                                        (dir / "array.json").string(), dir.string()));
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("nothing.deb: no such file"), std::string::npos) << bad.output;
  std::ofstream(dir / "broken.json") << "{\"format\": \"lfcam-array\", ";
  bad = testing::Lfcam(fmt::format("capture inventory {}", (dir / "broken.json").string()));
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.output.find("broken.json"), std::string::npos) << bad.output;

  if (testing::RunOnce("command -v ansible-inventory >/dev/null 2>&1").status != 0) {
    if (AnsibleRequired()) FAIL() << "LFCAM_REQUIRE_ANSIBLE=1 but ansible-inventory is missing";
    GTEST_SKIP() << "Ansible is not installed (Debian's ansible-core)";
  }
  const auto listed = testing::RunOnce(fmt::format(
      "ANSIBLE_LOCAL_TEMP={0} ANSIBLE_HOME={0} ansible-inventory -i {1} --list 2>/dev/null",
      dir.string(), (dir / "inventory.yml").string()));
  ASSERT_EQ(listed.status, 0) << listed.output;
  const auto inventory = nlohmann::json::parse(listed.output);
  EXPECT_EQ(inventory["lfcam_nodes"]["hosts"].size(), 4u) << listed.output;
  const auto& vars = inventory["_meta"]["hostvars"];
  EXPECT_EQ(vars["node-r00-c01"]["ansible_host"], "10.0.0.2");
  EXPECT_EQ(vars["node-r01-c01"]["lfcam_port"], 8471);
  EXPECT_EQ(vars["node-r01-c01"]["lfcam_row"], 1);
  EXPECT_EQ(vars["node-r00-c00"]["lfcam_key_file"], (dir / "array.key").string());
  EXPECT_EQ(vars["node-r00-c00"]["lfcam_node_package"], (dir / "node.deb").string());
  EXPECT_EQ(vars["node-r00-c00"]["lfcam_chrony_server"], "10.0.0.254");
  // The playbook parses, against this inventory.
  const auto syntax = testing::RunOnce(
      fmt::format("ANSIBLE_LOCAL_TEMP={0} ANSIBLE_HOME={0} ansible-playbook --syntax-check -i {1} "
                  "{2}/deploy/ansible/lfcam-node.yml 2>&1",
                  dir.string(), (dir / "inventory.yml").string(), LFCAM_SOURCE_DIR));
  EXPECT_EQ(syntax.status, 0) << syntax.output;
}

}  // namespace
}  // namespace lfcam
