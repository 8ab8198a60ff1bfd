#include "lfcam/node/request_signature.h"

#include <fmt/format.h>
#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>
#include <sys/stat.h>

#include <algorithm>
#include <charconv>
#include <fstream>

#include "lfcam/core/error.h"
#include "lfcam/core/input_file.h"

namespace lfcam {

namespace {

std::optional<SharedKey> HexDecode(std::string_view hex) {
  if (hex.size() % 2 != 0) return std::nullopt;
  SharedKey out(hex.size() / 2);
  for (std::size_t i = 0; i < out.size(); ++i) {
    unsigned value = 0;
    const auto [end, ec] = std::from_chars(hex.data() + 2 * i, hex.data() + 2 * i + 2, value, 16);
    if (ec != std::errc() || end != hex.data() + 2 * i + 2) return std::nullopt;
    out[i] = std::uint8_t(value);
  }
  return out;
}

bool IsHex(std::string_view text) {
  return std::all_of(text.begin(), text.end(), [](char c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
  });
}

}  // namespace

SharedKey ReadKeyFile(const std::filesystem::path& path, bool allow_shared_mode) {
  const std::vector<std::uint8_t> bytes = ReadFileBytes(path, 4096, "key file");
  std::string text(bytes.begin(), bytes.end());
  const auto first = text.find_first_not_of(" \t\r\n");
  const auto last = text.find_last_not_of(" \t\r\n");
  text = first == std::string::npos ? "" : text.substr(first, last - first + 1);
  const auto key = HexDecode(text);
  if (!key || key->size() != kKeyBytes || !IsHex(text))
    throw Error(
        fmt::format("{}: not a key: expected {} hex digits (make one with `lfcam capture "
                    "keygen` or `openssl rand -hex 32`)",
                    path.string(), 2 * kKeyBytes));
  struct stat st {};
  if (!allow_shared_mode && ::stat(path.c_str(), &st) == 0 && (st.st_mode & 077) != 0)
    throw Error(fmt::format("{}: the key file can be read by others (mode {:o}); chmod 600 it",
                            path.string(), st.st_mode & 0777));
  return *key;
}

std::string HexEncode(std::span<const std::uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  out.reserve(2 * bytes.size());
  for (std::uint8_t b : bytes) {
    out.push_back(kDigits[b >> 4]);
    out.push_back(kDigits[b & 15]);
  }
  return out;
}

std::string RandomHex(std::size_t count) {
  std::vector<std::uint8_t> bytes(count);
  if (RAND_bytes(bytes.data(), int(bytes.size())) != 1)
    throw Error("the random source (OpenSSL RAND_bytes) failed");
  return HexEncode(bytes);
}

std::string NewKeyHex() { return RandomHex(kKeyBytes); }

Sha256::Sha256() : context_(EVP_MD_CTX_new()) {
  if (context_ == nullptr ||
      EVP_DigestInit_ex(static_cast<EVP_MD_CTX*>(context_), EVP_sha256(), nullptr) != 1)
    throw Error("SHA-256: OpenSSL could not start a digest");
}

Sha256::~Sha256() { EVP_MD_CTX_free(static_cast<EVP_MD_CTX*>(context_)); }

void Sha256::update(const void* data, std::size_t size) {
  EVP_DigestUpdate(static_cast<EVP_MD_CTX*>(context_), data, size);
}

std::string Sha256::hex() {
  std::uint8_t digest[EVP_MAX_MD_SIZE];
  unsigned size = 0;
  EVP_DigestFinal_ex(static_cast<EVP_MD_CTX*>(context_), digest, &size);
  return HexEncode({digest, size});
}

std::string Sha256Hex(std::string_view bytes) {
  Sha256 sha;
  sha.update(bytes.data(), bytes.size());
  return sha.hex();
}

std::string Sha256OfFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("{}: cannot open", path.string()));
  Sha256 sha;
  std::vector<char> buffer(1 << 16);
  while (in) {
    in.read(buffer.data(), std::streamsize(buffer.size()));
    sha.update(buffer.data(), std::size_t(in.gcount()));
  }
  if (in.bad()) throw Error(fmt::format("{}: read error", path.string()));
  return sha.hex();
}

std::string SigningText(std::string_view method, std::string_view target, std::int64_t timestamp_ms,
                        std::string_view nonce, std::string_view body) {
  return fmt::format("{}\n{}\n{}\n{}\n{}", method, target, timestamp_ms, nonce, Sha256Hex(body));
}

std::string SignRequest(const SharedKey& key, std::string_view method, std::string_view target,
                        std::int64_t timestamp_ms, std::string_view nonce, std::string_view body) {
  const std::string text = SigningText(method, target, timestamp_ms, nonce, body);
  std::uint8_t mac[EVP_MAX_MD_SIZE];
  unsigned size = 0;
  if (HMAC(EVP_sha256(), key.data(), int(key.size()),
           reinterpret_cast<const unsigned char*>(text.data()), text.size(), mac, &size) == nullptr)
    throw Error("HMAC-SHA-256: OpenSSL failed");
  return HexEncode({mac, size});
}

RequestSignature SignNow(const SharedKey& key, std::string_view method, std::string_view target,
                         std::string_view body) {
  const std::int64_t now = std::chrono::duration_cast<std::chrono::milliseconds>(
                               std::chrono::system_clock::now().time_since_epoch())
                               .count();
  RequestSignature s{std::to_string(now), RandomHex(16), {}};
  s.signature = SignRequest(key, method, target, now, s.nonce, body);
  return s;
}

RequestVerifier::RequestVerifier(SharedKey key, std::chrono::milliseconds window)
    : key_(std::move(key)), window_(window) {}

std::optional<std::string> RequestVerifier::Verify(std::string_view method, std::string_view target,
                                                   std::string_view timestamp,
                                                   std::string_view nonce,
                                                   std::string_view signature,
                                                   std::string_view body, std::int64_t now_ms) {
  if (timestamp.empty() || nonce.empty() || signature.empty())
    return fmt::format("unsigned request: {}, {} and {} are required", kTimestampHeader,
                       kNonceHeader, kSignatureHeader);
  std::int64_t ts = 0;
  const auto [end, ec] = std::from_chars(timestamp.data(), timestamp.data() + timestamp.size(), ts);
  if (ec != std::errc() || end != timestamp.data() + timestamp.size())
    return fmt::format("{} is not a number of milliseconds", kTimestampHeader);
  if (nonce.size() < 16 || nonce.size() > 64 || !IsHex(nonce))
    return fmt::format("{} must be 16 to 64 hex digits", kNonceHeader);
  if (signature.size() != 64 || !IsHex(signature))
    return fmt::format("{} must be 64 hex digits", kSignatureHeader);
  const std::string expected = SignRequest(key_, method, target, ts, nonce, body);
  std::string given(signature);
  std::transform(given.begin(), given.end(), given.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (CRYPTO_memcmp(expected.data(), given.data(), expected.size()) != 0)
    return std::string("wrong signature (is the host using this node's key?)");
  const std::int64_t window = window_.count();
  if (ts < now_ms - window || ts > now_ms + window)
    return fmt::format(
        "stale request: its timestamp is {:.1f} s from the node's clock (window "
        "{:.1f} s)",
        double(ts - now_ms) / 1000.0, double(window) / 1000.0);
  std::lock_guard lock(mutex_);
  for (auto it = nonces_.begin(); it != nonces_.end();)
    it = it->second < now_ms ? nonces_.erase(it) : std::next(it);
  if (nonces_.size() >= 1'000'000) return std::string("too many requests in the window");
  if (!nonces_.emplace(std::string(nonce), ts + window).second)
    return std::string("replayed request: its nonce was used before");
  return std::nullopt;
}

}  // namespace lfcam
