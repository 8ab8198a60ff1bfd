#include "lfcam/node/request_signature.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

SharedKey Key(std::uint8_t fill) { return SharedKey(kKeyBytes, fill); }

TEST(RequestSignature, Sha256MatchesTheStandardVectors) {
  EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(RequestSignature, SignsTheMethodTargetTimeNonceAndBodyDigest) {
  EXPECT_EQ(SigningText("GET", "/", 0, "n", ""),
            "GET\n/\n0\nn\ne3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  // HMAC-SHA-256 (RFC 4231 test case 2: key "Jefe") over that text, computed independently with
  // `printf 'GET\n/\n0\nn\ne3b0...b855' | openssl dgst -sha256 -hmac Jefe`.
  const SharedKey jefe = {'J', 'e', 'f', 'e'};
  EXPECT_EQ(SignRequest(jefe, "GET", "/", 0, "n", ""),
            "59feee48b67b004e90bc27425680ee86d53d424e31b4536ad3d0f3b76c1bc7b9");
  EXPECT_NE(SignRequest(Key(1), "GET", "/", 0, "n", ""),
            SignRequest(Key(2), "GET", "/", 0, "n", ""));
}

TEST(RequestSignature, VerifiesAndRefusesWhatIsWrong) {
  RequestVerifier verifier(Key(7), std::chrono::milliseconds(30'000));
  const std::int64_t now = 1'800'000'000'000;
  const std::string nonce = "00112233445566778899aabbccddeeff";
  const std::string good = SignRequest(Key(7), "POST", "/v1/capture", now, nonce, "{}");
  auto verify = [&](std::string_view method, std::string_view target, std::int64_t ts,
                    std::string_view n, std::string_view sig, std::string_view body,
                    std::int64_t at) {
    return verifier.Verify(method, target, std::to_string(ts), n, sig, body, at);
  };
  EXPECT_FALSE(verify("POST", "/v1/capture", now, nonce, good, "{}", now + 1000));
  // Replayed.
  EXPECT_NE(verify("POST", "/v1/capture", now, nonce, good, "{}", now + 1000)->find("replayed"),
            std::string::npos);
  const std::string n2 = "ffeeddccbbaa99887766554433221100";
  const std::string sig2 = SignRequest(Key(7), "POST", "/v1/capture", now, n2, "{}");
  // Another method, target or body than signed; another key.
  EXPECT_TRUE(verify("GET", "/v1/capture", now, n2, sig2, "{}", now));
  EXPECT_TRUE(verify("POST", "/v1/captures", now, n2, sig2, "{}", now));
  EXPECT_TRUE(verify("POST", "/v1/capture", now, n2, sig2, "{ }", now));
  EXPECT_TRUE(verify("POST", "/v1/capture", now, n2,
                     SignRequest(Key(8), "POST", "/v1/capture", now, n2, "{}"), "{}", now));
  // Stale either way.
  EXPECT_NE(verify("POST", "/v1/capture", now, n2, sig2, "{}", now + 31'000)->find("stale"),
            std::string::npos);
  EXPECT_TRUE(verify("POST", "/v1/capture", now, n2, sig2, "{}", now - 31'000));
  // Malformed headers.
  EXPECT_NE(verifier.Verify("GET", "/", "", "", "", "", now)->find("unsigned"), std::string::npos);
  EXPECT_TRUE(verifier.Verify("GET", "/", "12x", n2, sig2, "", now));
  EXPECT_TRUE(verifier.Verify("GET", "/", std::to_string(now), "short", sig2, "", now));
  EXPECT_TRUE(verifier.Verify("GET", "/", std::to_string(now), n2, "zz", "", now));
  // The signature passes in either case of hex digits.
  std::string upper = sig2;
  for (char& c : upper) c = char(std::toupper(static_cast<unsigned char>(c)));
  EXPECT_FALSE(verify("POST", "/v1/capture", now, n2, upper, "{}", now));
}

TEST(RequestSignature, KeyFilesAreCheckedAndNamed) {
  const fs::path dir = fs::temp_directory_path() / ("lfcam_key_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path good = dir / "good.key";
  std::ofstream(good) << "  " << NewKeyHex() << "\n";
  fs::permissions(good, fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_EQ(ReadKeyFile(good).size(), kKeyBytes);
  fs::permissions(good, fs::perms::group_read, fs::perm_options::add);
  try {
    ReadKeyFile(good);
    ADD_FAILURE() << "a key readable by others was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("chmod 600"), std::string::npos) << e.what();
  }
  for (const std::string& bad : {std::string(), std::string("abc"), std::string(63, 'a'),
                                 std::string(64, 'g'), std::string(66, 'a')}) {
    const fs::path path = dir / "bad.key";
    std::ofstream(path) << bad;
    fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write);
    try {
      ReadKeyFile(path);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos);
    }
  }
  EXPECT_THROW(ReadKeyFile(dir / "missing.key"), Error);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lfcam
