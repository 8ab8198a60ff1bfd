#include "lfcam/capture/node_client.h"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>

#include "lfcam/core/json_input.h"

// After Eigen (through json_input.h): <resolv.h>, which httplib includes, defines a macro _res.
#include <httplib.h>

namespace lfcam {

namespace fs = std::filesystem;

fs::path PartialPath(const fs::path& destination) { return destination.string() + ".partial"; }

std::int64_t HostClockUnixNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

namespace {

void SetTimeout(httplib::Client& client, double seconds,
                void (httplib::Client::*set)(time_t, time_t)) {
  const auto whole = time_t(seconds);
  (client.*set)(whole, time_t((seconds - double(whole)) * 1e6));
}

httplib::Headers SignedHeaders(const SharedKey& key, const std::string& method,
                               const std::string& target, const std::string& body) {
  const RequestSignature s = SignNow(key, method, target, body);
  return {
      {kTimestampHeader, s.timestamp}, {kNonceHeader, s.nonce}, {kSignatureHeader, s.signature}};
}

std::string ErrorText(httplib::Error e) {
  switch (e) {
    case httplib::Error::Connection:
      return "connection refused or no route";
    case httplib::Error::ConnectionTimeout:
      return "connection timed out";
    case httplib::Error::Read:
      return "the connection broke while reading";
    case httplib::Error::Write:
      return "the connection broke while writing";
    case httplib::Error::Canceled:
      return "cancelled";
    default:
      return httplib::to_string(e);
  }
}

}  // namespace

NodeClient::NodeClient(std::string address, SharedKey key, NodeTimeouts timeouts)
    : address_(std::move(address)),
      key_(std::move(key)),
      timeouts_(timeouts),
      client_(std::make_unique<httplib::Client>("http://" + address_)) {
  SetTimeout(*client_, timeouts_.connect_s, &httplib::Client::set_connection_timeout);
  SetTimeout(*client_, timeouts_.read_s, &httplib::Client::set_read_timeout);
  SetTimeout(*client_, timeouts_.read_s, &httplib::Client::set_write_timeout);
  client_->set_keep_alive(true);
  client_->set_tcp_nodelay(true);
}

NodeClient::~NodeClient() = default;

namespace {

TimedReply Interpret(const std::string& address, const std::string& what, httplib::Result& result,
                     std::int64_t sent) {
  if (!result)
    throw NodeError(0, "unreachable",
                    fmt::format("{}: {}: {}", address, what, ErrorText(result.error())));
  TimedReply reply;
  reply.sent_unix_ns = sent;
  reply.received_unix_ns = HostClockUnixNs();
  nlohmann::json body;
  try {
    body = ParseJsonBounded(result->body, address);
  } catch (const Error&) {
    body = nlohmann::json();
  }
  if (result->status / 100 != 2) {
    std::string reason = result->status == 401 ? "unauthorized" : "refused";
    std::string message = fmt::format("HTTP {}", result->status);
    if (body.is_object() && body.contains("error") && body["error"].is_string())
      message = body["error"].get<std::string>();
    if (body.is_object() && body.contains("reason") && body["reason"].is_string() &&
        result->status != 401)
      reason = body["reason"].get<std::string>();
    throw NodeError(result->status, reason, fmt::format("{}: {}: {}", address, what, message));
  }
  if (body.is_null())
    throw NodeError(result->status, "protocol",
                    fmt::format("{}: {}: the answer is not JSON", address, what));
  reply.body = std::move(body);
  return reply;
}

}  // namespace

TimedReply NodeClient::Get(const std::string& target) {
  const auto sent = HostClockUnixNs();
  auto result = client_->Get(target, SignedHeaders(key_, "GET", target, ""));
  return Interpret(address_, "GET " + target, result, sent);
}

TimedReply NodeClient::Post(const std::string& target, const nlohmann::json& body,
                            double read_timeout_s) {
  const std::string text = body.dump();
  if (read_timeout_s > 0) SetTimeout(*client_, read_timeout_s, &httplib::Client::set_read_timeout);
  const auto sent = HostClockUnixNs();
  auto result =
      client_->Post(target, SignedHeaders(key_, "POST", target, text), text, "application/json");
  if (read_timeout_s > 0)
    SetTimeout(*client_, timeouts_.read_s, &httplib::Client::set_read_timeout);
  return Interpret(address_, "POST " + target, result, sent);
}

TimedReply NodeClient::Delete(const std::string& target) {
  const auto sent = HostClockUnixNs();
  auto result = client_->Delete(target, SignedHeaders(key_, "DELETE", target, ""));
  return Interpret(address_, "DELETE " + target, result, sent);
}

std::string NodeClient::GetBytes(const std::string& target) {
  auto result = client_->Get(target, SignedHeaders(key_, "GET", target, ""));
  if (!result)
    throw NodeError(0, "unreachable",
                    fmt::format("{}: GET {}: {}", address_, target, ErrorText(result.error())));
  if (result->status != 200) {
    const auto sent = HostClockUnixNs();
    Interpret(address_, "GET " + target, result, sent);
  }
  return result->body;
}

std::uint64_t NodeClient::Download(const std::string& id, const fs::path& destination,
                                   std::uint64_t size, const std::string& sha256) {
  const fs::path partial = PartialPath(destination);
  const std::string what = fmt::format("{}: capture '{}'", address_, id);
  std::error_code ec;
  std::uint64_t have = fs::is_regular_file(partial, ec) ? fs::file_size(partial, ec) : 0;
  if (ec || have > size) {
    fs::remove(partial, ec);
    have = 0;
  }
  Sha256 sha;
  std::FILE* file = std::fopen(partial.c_str(), have > 0 ? "r+b" : "wb");
  if (file == nullptr)
    throw Error(fmt::format("{}: cannot write: {}", partial.string(), std::strerror(errno)));
  struct Closer {
    std::FILE*& f;
    ~Closer() {
      if (f) std::fclose(f);
    }
  } closer{file};
  // The bytes already here count toward the checksum.
  if (have > 0) {
    std::vector<char> buffer(1 << 16);
    std::uint64_t left = have;
    while (left > 0) {
      const std::size_t n =
          std::fread(buffer.data(), 1, std::min<std::uint64_t>(left, buffer.size()), file);
      if (n == 0) throw Error(fmt::format("{}: read error", partial.string()));
      sha.update(buffer.data(), n);
      left -= n;
    }
    std::fseek(file, long(have), SEEK_SET);
  }
  std::uint64_t received = 0;
  bool write_failed = false;
  if (have < size) {
    const std::string target = "/v1/captures/" + id;
    httplib::Headers headers = SignedHeaders(key_, "GET", target, "");
    if (have > 0) headers.emplace("Range", fmt::format("bytes={}-", have));
    int status = 0;
    std::string node_sha;
    auto result = client_->Get(
        target, headers,
        [&](const httplib::Response& response) {
          status = response.status;
          node_sha = response.get_header_value("X-Lfcam-Sha256");
          return status == (have > 0 ? 206 : 200);
        },
        [&](const char* data, std::size_t length) {
          if (have + received + length > size) return false;
          if (std::fwrite(data, 1, length, file) != length) {
            write_failed = true;
            return false;
          }
          sha.update(data, length);
          received += length;
          return true;
        });
    std::fflush(file);
    if (write_failed)
      throw Error(fmt::format("{}: write error: {}", partial.string(), std::strerror(errno)));
    if (status != 0 && status != (have > 0 ? 206 : 200)) {
      if (status == 404)
        throw NodeError(404, "gone", fmt::format("{}: the node no longer holds it", what));
      throw NodeError(status, "refused", fmt::format("{}: HTTP {}", what, status));
    }
    if (!result && have + received < size)
      throw NodeError(0, "unreachable",
                      fmt::format("{}: {} after {} of {} bytes", what, ErrorText(result.error()),
                                  have + received, size));
    if (!node_sha.empty() && node_sha != sha256)
      throw NodeError(0, "protocol", fmt::format("{}: the node's checksum changed", what));
  }
  if (have + received != size)
    throw NodeError(0, "unreachable",
                    fmt::format("{}: {} of {} bytes arrived", what, have + received, size));
  if (::fsync(::fileno(file)) != 0 || std::fclose(file) != 0) {
    file = nullptr;
    throw Error(fmt::format("{}: cannot flush to disk", partial.string()));
  }
  file = nullptr;
  if (const std::string got = sha.hex(); got != sha256) {
    fs::remove(partial, ec);
    throw NodeError(0, "corrupt",
                    fmt::format("{}: checksum mismatch (SHA-256 {} expected, {} received); "
                                "deleted, will be fetched again",
                                what, sha256.substr(0, 12), got.substr(0, 12)));
  }
  fs::rename(partial, destination, ec);
  if (ec)
    throw Error(
        fmt::format("{}: cannot rename into place: {}", destination.string(), ec.message()));
  return received;
}

}  // namespace lfcam
