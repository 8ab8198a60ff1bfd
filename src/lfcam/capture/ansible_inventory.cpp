#include "lfcam/capture/ansible_inventory.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

// A YAML scalar that reads back as exactly `text` (a JSON string is a YAML double-quoted one).
std::string Quoted(const std::string& text) { return nlohmann::json(text).dump(); }

}  // namespace

std::string AnsibleInventory(const ArrayConfig& array, const std::filesystem::path& array_file,
                             const InventoryOptions& options) {
  std::string out = fmt::format(
      "# Ansible inventory of the lfcam array {} (`lfcam capture inventory`), for\n"
      "# deploy/ansible/lfcam-node.yml (docs/hardware.md): one host a node.\n"
      "all:\n  children:\n    lfcam_nodes:\n      vars:\n        lfcam_key_file: {}\n",
      array_file.string(),
      Quoted(std::filesystem::absolute(KeyFilePath(array, array_file)).string()));
  if (!options.node_package.empty())
    out += fmt::format("        lfcam_node_package: {}\n",
                       Quoted(std::filesystem::absolute(options.node_package).string()));
  if (!options.chrony_server.empty())
    out += fmt::format("        lfcam_chrony_server: {}\n", Quoted(options.chrony_server));
  if (!options.ssh_user.empty())
    out += fmt::format("        ansible_user: {}\n", Quoted(options.ssh_user));
  out += "      hosts:\n";
  for (const ArrayNode& node : array.nodes) {
    const std::size_t colon = node.address.rfind(':');
    std::string host = colon == std::string::npos ? "" : node.address.substr(0, colon);
    const std::string port = colon == std::string::npos ? "" : node.address.substr(colon + 1);
    if (host.size() > 2 && host.front() == '[' && host.back() == ']')  // [IPv6]:port
      host = host.substr(1, host.size() - 2);
    int port_number = 0;
    try {
      port_number = std::stoi(port);
    } catch (const std::exception&) {
    }
    if (host.empty() || port_number < 1 || port_number > 65535 ||
        port.find_first_not_of("0123456789") != std::string::npos)
      throw Error(fmt::format("{}: node ({}, {}): address '{}' is not HOST:PORT",
                              array_file.string(), node.row, node.col, node.address));
    out += fmt::format(
        "        node-r{:02}-c{:02}:\n          ansible_host: {}\n          lfcam_port: {}\n"
        "          lfcam_row: {}\n          lfcam_col: {}\n",
        node.row, node.col, Quoted(host), port_number, node.row, node.col);
  }
  return out;
}

}  // namespace lfcam
