#include "lfcam/node/recording.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "lfcam/core/error.h"
#include "lfcam/node/capture_settings.h"
#include "lfcam/node/capture_store.h"
#include "lfcam/node/request_signature.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

VideoFrameEntry Frame(std::int64_t sequence, std::uint64_t offset, std::uint64_t size,
                      std::int64_t wall) {
  return {sequence, offset, size, wall, wall + 1000};
}

TEST(FrameIndex, ListsFramesBackToBackAndStopsWhereTheWriterDied) {
  const std::string text = FrameIndexLine(Frame(0, 0, 10, 100)) +
                           FrameIndexLine(Frame(2, 10, 20, 200)) +  // frame 1 dropped
                           FrameIndexLine(Frame(3, 30, 5, 300));
  const auto all = ParseFrameIndex(text, 35, "index");
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[1].sequence, 2);
  EXPECT_EQ(all[2].offset, 30u);
  // The last frame's bytes not all in the stream, or its line cut short: the frames before.
  EXPECT_EQ(ParseFrameIndex(text, 34, "index").size(), 2u);
  EXPECT_EQ(ParseFrameIndex(text.substr(0, text.size() - 3), 35, "index").size(), 2u);
  // Anything else is refused, the line named.
  const auto refused = [](const std::string& bad) {
    try {
      ParseFrameIndex(bad, 1000, "index");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refused(FrameIndexLine(Frame(0, 0, 10, 100)) + FrameIndexLine(Frame(1, 11, 10, 200)))
                .find("line 2"),
            std::string::npos);
  EXPECT_NE(refused(FrameIndexLine(Frame(4, 0, 10, 100)) + FrameIndexLine(Frame(4, 10, 10, 200)))
                .find("follows"),
            std::string::npos);
  EXPECT_NE(refused(FrameIndexLine(Frame(0, 0, 10, 300)) + FrameIndexLine(Frame(1, 10, 10, 200)))
                .find("wall-clock"),
            std::string::npos);
  EXPECT_NE(refused("{\"sequence\": -1}\n").find("line 1"), std::string::npos);
  EXPECT_NE(refused("not json\n").find("line 1"), std::string::npos);
}

CaptureRecord VideoRecord(const std::string& id) {
  CaptureRecord r;
  r.id = id;
  r.kind = "video";
  r.shot = "rec_00";
  r.requested_unix_ns = 1000;
  r.settings = SettingsToJson(CaptureSettings{});
  r.video = VideoRecordInfo{};
  r.video->seconds = 1;
  r.video->width = 64;
  r.video->height = 48;
  return r;
}

TEST(CaptureStore, ARecordingIsAStreamAndAnIndexAndIsOfferedWhenFinished) {
  const fs::path dir = fs::temp_directory_path() / ("lfcam_rec_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  CaptureStore store(dir);
  auto writer = store.BeginRecording(VideoRecord("s-rec_00"));
  auto held = store.Find("s-rec_00");
  ASSERT_TRUE(held);
  EXPECT_EQ(held->video->status, "recording");
  writer->Append({0, 0, 0, 5000, 1}, "frame-zero");
  writer->Append({1, 0, 0, 6000, 2}, "frame-one!!");
  EXPECT_EQ(store.Frames(*store.Find("s-rec_00")).size(), 2u);  // readable while recording
  const CaptureRecord done = writer->Finish("complete", "");
  EXPECT_EQ(done.size, 21u);
  EXPECT_EQ(done.sha256, Sha256Hex("frame-zeroframe-one!!"));
  held = store.Find("s-rec_00");
  ASSERT_TRUE(held);
  EXPECT_EQ(held->video->status, "complete");
  EXPECT_EQ(held->video->frames, 2);
  EXPECT_EQ(store.DataPath(*held).extension(), ".mjpeg");
  const auto frames = store.Frames(*held);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1].offset, 10u);
  EXPECT_EQ(frames[1].size, 11u);
  EXPECT_EQ(frames[1].wall_clock_ns, 6000);
  EXPECT_EQ(store.List().size(), 1u);
  EXPECT_TRUE(store.Remove("s-rec_00"));
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST(CaptureStore, ARecordingADeadNodeLeftOpenIsClosedWithTheFramesOnDisk) {
  const fs::path dir = fs::temp_directory_path() / ("lfcam_rec_dead_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  {
    CaptureStore store(dir);
    auto writer = store.BeginRecording(VideoRecord("s-rec_00"));
    writer->Append({0, 0, 0, 5000, 1}, "aaaa");
    writer->Append({1, 0, 0, 6000, 2}, "bbbb");
    // The node dies writing frame 2: some of its bytes, half its index line.
    std::ofstream(dir / "s-rec_00.mjpeg", std::ios::app) << "cc";
    std::ofstream(dir / "s-rec_00.frames.jsonl", std::ios::app) << "{\"sequence\": 2, \"off";
    auto nothing = store.BeginRecording(VideoRecord("s-rec_01"));  // no frame at all
  }  // the writers are dropped without Finish, as a killed process leaves them
  CaptureStore store(dir);
  const auto held = store.Find("s-rec_00");
  ASSERT_TRUE(held);
  EXPECT_EQ(held->video->status, "truncated");
  EXPECT_EQ(held->video->frames, 2);
  EXPECT_NE(held->video->reason.find("stopped mid-recording"), std::string::npos);
  EXPECT_EQ(held->size, 8u);
  EXPECT_EQ(held->sha256, Sha256Hex("aaaabbbb"));
  EXPECT_EQ(fs::file_size(store.DataPath(*held)), 8u);
  EXPECT_EQ(store.Find("s-rec_01")->video->status, "failed");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lfcam
