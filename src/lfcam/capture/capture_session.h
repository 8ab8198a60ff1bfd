#pragma once
// `lfcam capture shoot` and `fetch`: one scheduled trigger time for the whole array, then the
// images brought home into the session layout (docs/capture-layout.md) with bounded concurrency,
// checksums verified, each written under a temporary name and renamed, retried with backoff.
// The manifest records every camera's node, requested and actual trigger time, settings, size,
// SHA-256 and status, and is rewritten (atomically) as each image arrives, so a host that dies
// mid-fetch loses nothing: `fetch` resumes from it, partial files included.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/capture/array_file.h"
#include "lfcam/core/progress.h"
#include "lfcam/node/request_signature.h"
#include "lfcam/session/session.h"

namespace lfcam {

struct FetchOptions {
  int concurrency = 8;        // downloads at once
  int retries = 3;            // per image, after the first try, with backoff 0.25 s, 0.5 s, ...
  ProgressCallback progress;  // bytes downloaded
};

struct ShootOptions {
  ShotKind kind = ShotKind::kScene;
  double margin_s = 0.5;           // the trigger time is this far ahead (at least 3 round trips)
  int groups = 1;                  // > 1: staggered like the paper's two groups
  double group_delay_s = 0.5;      // between groups
  double capture_timeout_s = 120;  // for a node to take and store its image after T
  bool fetch = true;               // download right away (else `lfcam capture fetch` later)
  FetchOptions fetch_options;
};

struct CameraProblem {
  int row = 0, col = 0;
  std::string shot, status, reason;
};

struct SessionReport {
  std::string shot;               // the shot taken (shoot and record only)
  bool video = false;             // a recording's
  int cameras = 0;                // in the array file
  int fired = 0;                  // took the image
  std::optional<double> skew_ms;  // latest minus earliest actual trigger time, per group
  double trigger_wait_s = 0, capture_s = 0, fetch_s = 0;
  std::uint64_t bytes = 0;              // downloaded
  int images_ok = 0;                    // in the session, verified (all shots)
  std::vector<CameraProblem> problems;  // every image not in the session, and why
};

// Takes one shot of `options.kind` with every ready node and (by default) fetches it. The
// session directory is created, or extended when it holds a session of the same grid.
SessionReport ShootSession(const ArrayConfig& array, const SharedKey& key,
                           const std::filesystem::path& session, const ShootOptions& options);

// Downloads every image the manifest lists as captured and not yet here.
SessionReport FetchSession(const ArrayConfig& array, const SharedKey& key,
                           const std::filesystem::path& session, const FetchOptions& options);

nlohmann::json SessionReportToJson(const SessionReport& report);

// What shoot and record share. The session's manifest to add a shot to: read, or new for
// `array` (the folder created); refused when its grid or sensor mode differs from the array's.
CaptureManifest OpenSessionManifest(const ArrayConfig& array, const std::filesystem::path& session);
// The next free name for a shot of `kind`: "scene", "world", "shot_KK", "rec_KK".
std::string NextShotName(const CaptureManifest& manifest, ShotKind kind);
// Where a shot's files go in the session: "scene", "calib/intrinsics/shot_03", "video/rec_00".
std::string ShotFolder(ShotKind kind, const std::string& name);
// The report's problems and images_ok, from the manifest.
void CollectProblems(const CaptureManifest& manifest, SessionReport& report);
// A node's group among `groups` (the paper's trigger groups, a recording's stagger groups): the
// array file's, else interleaved like a checkerboard, (row + col) mod groups.
int NodeGroup(const ArrayConfig& array, const ArrayNode& node, int groups);
// Adds the cameras of the grid that have no node in the array file (missing, with that reason,
// their file named by `file_name`), then sorts the images by (row, col).
void AddCamerasWithoutNodes(const ArrayConfig& array,
                            const std::function<std::string(int, int)>& file_name,
                            std::vector<ShotImage>& images);

}  // namespace lfcam
