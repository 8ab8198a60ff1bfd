#pragma once
// How well the array kept in step over a recording (`lfcam capture report`, and the end of
// `lfcam capture record`): the light field frames the cameras' frames make
// (session/frame_alignment.h), each frame's spread, and every camera frame missing or
// duplicated, named; as text, as JSON and as a picture (the spread over time above, each
// camera's offset from the array's times below, one row per camera, missing frames black).
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>

#include "lfcam/session/frame_alignment.h"
#include "lfcam/session/session.h"

namespace lfcam {

struct RecordingReport {
  std::string shot;
  VideoShot video;
  FrameAlignment alignment;
  SpreadSummary spread;
};

// The report of video shot `shot` of the manifest (empty: its last recording). Throws
// lfcam::Error when there is no such recording.
RecordingReport MakeRecordingReport(const CaptureManifest& manifest, const std::string& shot = "",
                                    const AlignmentOptions& options = {});

nlohmann::json RecordingReportToJson(const RecordingReport& report);
std::string RecordingReportText(const RecordingReport& report);
cv::Mat RecordingReportPicture(const RecordingReport& report);  // 8-bit RGB

// "3, 17-19, 240": frame numbers, runs joined.
std::string FrameRanges(const std::vector<std::int64_t>& frames);

}  // namespace lfcam
