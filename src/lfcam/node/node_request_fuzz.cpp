// libFuzzer target: what reaches lfcam-node from the network before and after its signature is
// checked: the signature headers, the settings of a configure or capture request, a capture
// record, a record request's video, and the chrony line it reads about its own clock.
#include <cstdint>
#include <string>
#include <string_view>

#include "lfcam/core/error.h"
#include "lfcam/core/json_input.h"
#include "lfcam/node/capture_settings.h"
#include "lfcam/node/capture_store.h"
#include "lfcam/node/request_signature.h"
#include "lfcam/node/system_status.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static lfcam::RequestVerifier verifier(lfcam::SharedKey(lfcam::kKeyBytes, 1),
                                         std::chrono::milliseconds(30'000));
  // Split into header fields at newlines: timestamp, nonce, signature, then the body.
  std::string_view parts[4];
  std::string_view rest = text;
  for (int i = 0; i < 3; ++i) {
    const auto nl = rest.find('\n');
    parts[i] = rest.substr(0, nl);
    rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
  }
  parts[3] = rest;
  (void)verifier.Verify("POST", "/v1/capture", parts[0], parts[1], parts[2], parts[3], 0);
  (void)lfcam::IsValidCaptureId(parts[0]);
  try {
    const auto j = lfcam::ParseJsonBounded(text, "fuzz");
    try {
      (void)lfcam::SettingsToJson(lfcam::SettingsFromJson(j, "fuzz"));
    } catch (const lfcam::Error&) {
    }
    try {
      (void)lfcam::RecordToJson(lfcam::RecordFromJson(j, "fuzz"));
    } catch (const lfcam::Error&) {
    }
    try {
      (void)lfcam::VideoInfoToJson(lfcam::VideoInfoFromJson(j, "fuzz"));
    } catch (const lfcam::Error&) {
    }
  } catch (const lfcam::Error&) {
  }
  (void)lfcam::ParseChronyTracking(std::string(text.substr(0, 512)));
  return 0;
}
