#pragma once
// `lfcam capture record` (issue 24): every node records video from one scheduled start time
// with the array's locked settings (libcamera's software sync on, one node the server, unless
// asked otherwise), the host waits for the recordings to end, learns each camera's frames and
// their wall-clock times from its node, writes them into the manifest as a "video" shot
// (session/session.h), and fetches the streams as `fetch` fetches images: verified, resumable.
// A node that cannot be reached when the recording ends stays "captured": `lfcam capture fetch`
// asks it again and completes the recording when it is back.
#include <filesystem>
#include <string>
#include <vector>

#include "lfcam/capture/array_file.h"
#include "lfcam/capture/capture_session.h"
#include "lfcam/capture/node_client.h"
#include "lfcam/core/progress.h"
#include "lfcam/session/session.h"

namespace lfcam {

struct RecordOptions {
  double seconds = 10, fps = 30;
  int width = 648, height = 486;  // the video's sensor mode (the Pi v1.3's 4x4-binned one)
  bool sync = true;               // libcamera's software sync; off: free-running, a shared start
  // High-speed mode (Wilburn et al. 2004): the array in this many groups whose frame starts are
  // 1 / (stagger * fps) apart, so that together they sample time `stagger` times as often. The
  // groups are the array file's, or interleaved ((row + col) mod stagger) when it has none.
  int stagger = 1;
  double margin_s = 1.0;  // the start is this far ahead (at least 3 round trips)
  // After the recording's end, how long the array may go without any node delivering a new frame
  // before the host stops waiting for the nodes still recording (simulated nodes render their
  // frames slower than real time: they are waited for as long as the array makes progress).
  double finish_timeout_s = 30;
  bool fetch = true;
  FetchOptions fetch_options;
  ProgressCallback progress;  // frames recorded, over the array
};

// Records into a new "video" shot (rec_KK) of `session` (created, or extended when it holds a
// session of the same grid and stills' sensor mode) and (by default) fetches it.
SessionReport RecordSession(const ArrayConfig& array, const SharedKey& key,
                            const std::filesystem::path& session, const RecordOptions& options);

// What a node says of one of its recordings.
struct NodeRecording {
  std::string status;  // the node's: recording, complete, truncated or failed
  std::string reason;  // why truncated or failed
  std::uint64_t size = 0;
  std::string sha256;
  std::int64_t frame_count = 0;
  std::vector<FrameTime> frames;  // with_frames only
};
// Asks the node (GET /v1/recordings/ID). Throws NodeError, or lfcam::Error for an answer that
// does not hold together (frames beyond the stream, times that go back).
NodeRecording AskRecording(NodeClient& client, const std::string& id, bool with_frames = true);
// Writes what the node said into a camera of a video shot: the frames, and in its capture
// record the stream's size and checksum, the node's status and reason.
void ApplyRecording(ShotImage& image, const NodeRecording& recording);

}  // namespace lfcam
