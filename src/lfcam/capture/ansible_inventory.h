#pragma once
// `lfcam capture inventory ARRAY`: the array file as an Ansible inventory (YAML), for the
// playbook that installs lfcam-node on every node (deploy/ansible/lfcam-node.yml,
// docs/hardware.md): one host a node, named by its grid position (node-r00-c00), with its
// address and port, in the group `lfcam_nodes`, whose variables say where the array's key is
// and, when given, the package to install, the time server and the SSH user.
#include <filesystem>
#include <string>

#include "lfcam/capture/array_file.h"

namespace lfcam {

struct InventoryOptions {
  std::string ssh_user;                // ansible_user (empty: Ansible's default)
  std::string chrony_server;           // the nodes' time server (empty: the playbook's default)
  std::filesystem::path node_package;  // the lfcam-node .deb (absolute)
};

// Throws lfcam::Error naming the node whose address has no HOST:PORT form.
std::string AnsibleInventory(const ArrayConfig& array, const std::filesystem::path& array_file,
                             const InventoryOptions& options);

}  // namespace lfcam
