#pragma once
// The host's side of the node API (node/node_agent.h): signed requests to one node, and
// downloads that resume, verify and only then take their final name.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "lfcam/core/error.h"
#include "lfcam/node/request_signature.h"

namespace httplib {
class Client;
}

namespace lfcam {

// A request that failed. `status` is the HTTP status, 0 when the node could not be reached or
// did not answer in time; `reason` is "unreachable", "unauthorized", "corrupt", or the node's
// own reason for refusing ("settings", "clock", "disk", "late", ...).
class NodeError : public Error {
 public:
  NodeError(int status, std::string reason, const std::string& message)
      : Error(message), status_(status), reason_(std::move(reason)) {}
  int status() const { return status_; }
  const std::string& reason() const { return reason_; }

 private:
  int status_;
  std::string reason_;
};

struct NodeTimeouts {
  double connect_s = 2.0;
  double read_s = 10.0;
};

struct TimedReply {
  nlohmann::json body;
  std::int64_t sent_unix_ns = 0, received_unix_ns = 0;  // the host's clock
};

class NodeClient {
 public:
  NodeClient(std::string address, SharedKey key, NodeTimeouts timeouts = {});
  ~NodeClient();
  NodeClient(const NodeClient&) = delete;
  NodeClient& operator=(const NodeClient&) = delete;

  const std::string& address() const { return address_; }

  TimedReply Get(const std::string& target);
  TimedReply Post(const std::string& target, const nlohmann::json& body,
                  double read_timeout_s = 0);  // 0: the default
  TimedReply Delete(const std::string& target);
  std::string GetBytes(const std::string& target);

  // Downloads capture `id` into `destination`: the bytes go to DESTINATION.partial (kept across
  // failures, so that the next try asks only for the rest with a Range request), are checked
  // against `size` and `sha256`, and only then renamed to `destination`. A partial file that
  // fails the checksum is deleted. Returns the bytes received in this call. Throws NodeError.
  std::uint64_t Download(const std::string& id, const std::filesystem::path& destination,
                         std::uint64_t size, const std::string& sha256);

 private:
  std::string address_;
  SharedKey key_;
  NodeTimeouts timeouts_;
  std::unique_ptr<httplib::Client> client_;
};

std::filesystem::path PartialPath(const std::filesystem::path& destination);
std::int64_t HostClockUnixNs();

}  // namespace lfcam
