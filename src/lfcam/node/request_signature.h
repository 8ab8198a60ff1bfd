#pragma once
// How the host and a node trust each other (docs/hardware.md, "Security"): a pre-shared key of
// 32 random bytes, and every request signed with HMAC-SHA-256 over its method, target (path and
// query), timestamp, nonce and the SHA-256 of its body. A node refuses a request whose signature
// is missing or wrong, whose timestamp is outside a short window, or whose nonce it has seen.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace lfcam {

inline constexpr const char* kTimestampHeader = "X-Lfcam-Timestamp";  // Unix time, milliseconds
inline constexpr const char* kNonceHeader = "X-Lfcam-Nonce";          // 16..64 hex digits
inline constexpr const char* kSignatureHeader = "X-Lfcam-Signature";  // 64 hex digits
inline constexpr std::size_t kKeyBytes = 32;

using SharedKey = std::vector<std::uint8_t>;

// Reads a key file: 64 hex digits (whitespace around them ignored), as `lfcam capture keygen` or
// `openssl rand -hex 32` writes. Refuses a key file that others can read (mode & 077) unless
// `allow_shared_mode`. Throws lfcam::Error naming the file.
SharedKey ReadKeyFile(const std::filesystem::path& path, bool allow_shared_mode = false);
// 32 bytes from the operating system's random source, as hex.
std::string NewKeyHex();
std::string RandomHex(std::size_t bytes);

std::string HexEncode(std::span<const std::uint8_t> bytes);

// SHA-256 of bytes, as 64 lower-case hex digits.
std::string Sha256Hex(std::string_view bytes);

// Incremental SHA-256 (streamed downloads, files too large to hold).
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void update(const void* data, std::size_t size);
  std::string hex();  // finishes; call once

 private:
  void* context_;
};

// SHA-256 of a file's contents (streamed). Throws lfcam::Error naming the file.
std::string Sha256OfFile(const std::filesystem::path& path);

// The text that is signed: METHOD \n TARGET \n TIMESTAMP \n NONCE \n SHA256(BODY).
std::string SigningText(std::string_view method, std::string_view target, std::int64_t timestamp_ms,
                        std::string_view nonce, std::string_view body);
std::string SignRequest(const SharedKey& key, std::string_view method, std::string_view target,
                        std::int64_t timestamp_ms, std::string_view nonce, std::string_view body);

// The three headers of a signed request, made now.
struct RequestSignature {
  std::string timestamp, nonce, signature;
};
RequestSignature SignNow(const SharedKey& key, std::string_view method, std::string_view target,
                         std::string_view body);

// A node's side: checks signatures and remembers nonces for the length of the window. Safe to
// call from several threads.
class RequestVerifier {
 public:
  RequestVerifier(SharedKey key, std::chrono::milliseconds window);
  // nullopt when the request is good, else why it is refused (for the 401 body).
  std::optional<std::string> Verify(std::string_view method, std::string_view target,
                                    std::string_view timestamp, std::string_view nonce,
                                    std::string_view signature, std::string_view body,
                                    std::int64_t now_ms);

 private:
  SharedKey key_;
  std::chrono::milliseconds window_;
  std::mutex mutex_;
  std::map<std::string, std::int64_t, std::less<>> nonces_;  // nonce -> expiry (ms)
};

}  // namespace lfcam
