#pragma once
// What `rpicam-vid --codec mjpeg --output FILE --metadata META --metadata-format json` leaves
// behind (rpicam-apps 1.6 and later on Raspberry Pi OS bookworm; the `sync` flags need them too),
// read into a recording's frames: the stream's JPEGs (each from its SOI marker FF D8 to its EOI
// FF D9: libcamera's MJPEG frames carry no thumbnails, so no EOI comes early) paired in order
// with the metadata file's per-frame objects, whose `SensorTimestamp` and `FrameWallClock` are
// nanoseconds. The metadata holds no frame numbers: each frame's sequence number is its sensor
// time over the frame period from the first, so a frame the camera dropped leaves a gap.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lfcam {

struct RpicamFrameTime {
  std::int64_t sensor_ns = 0, wall_clock_ns = 0;
};

// The [offset, size) of every JPEG in a Motion-JPEG stream, in order; bytes between or after
// frames (a frame cut short by the end of the file) are left out. Throws lfcam::Error naming
// `where` for a stream with no whole JPEG.
std::vector<std::pair<std::size_t, std::size_t>> SplitMjpeg(std::string_view stream,
                                                            const std::string& where);

// The per-frame times of an rpicam-apps JSON metadata file: an array of objects (a last one cut
// short by a camera process that was stopped is left out). Throws lfcam::Error naming `where` and
// the frame for anything else: no array, a frame without its times, times that go back.
std::vector<RpicamFrameTime> ParseRpicamMetadata(std::string_view text, const std::string& where);

// Sequence numbers from sensor times: (t - t_0) / period, rounded.
std::vector<std::int64_t> SequenceFromSensorTimes(const std::vector<RpicamFrameTime>& times,
                                                  double fps);

}  // namespace lfcam
