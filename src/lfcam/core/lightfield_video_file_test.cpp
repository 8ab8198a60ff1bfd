#include "lfcam/core/lightfield_video_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <random>

#include "lfcam/core/error.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

// A small light field whose samples say which frame it is.
LightField Frame(int k) {
  Slab slab;
  slab.uv.rows = 2;
  slab.uv.cols = 3;
  slab.uv.p_ca = Vec3(1, 2, 3000);
  LightField lf({2, 3, 17, 11}, SampleType::kSrgb8, slab);
  std::mt19937 rng(std::uint32_t(k + 1));
  std::uniform_int_distribution<int> byte(0, 255);
  std::uint8_t* p = lf.mutable_view_data(0, 0);
  for (std::size_t i = 0; i < lf.total_bytes(); ++i) p[i] = std::uint8_t(byte(rng));
  lf.metadata() = {{"frame", k}};
  return lf;
}

std::string Bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

bool SameSamples(const LightField& a, const LightField& b) {
  return a.total_bytes() == b.total_bytes() &&
         std::memcmp(a.data(), b.data(), a.total_bytes()) == 0;
}

LightFieldVideoHeader Header() {
  LightFieldVideoHeader h;
  h.fps = 30;
  h.frames_planned = 3;
  h.start_unix_ns = 1'800'000'000'000'000'000;
  h.metadata = {{"recording", "rec_00"}};
  return h;
}

VideoFrameInfo Info(int k) {
  return {k, 1'800'000'000'000'000'000 + k * 33'333'333,
          k == 1 ? std::nullopt : std::optional<std::int64_t>(40'000 + k), 0, 0};
}

TEST(LightFieldVideoFile, FramesReadBackInAnyOrderAndWhileTheFileIsWritten) {
  const fs::path dir = testing::MakeScratchDir("lfcam_video_file");
  const fs::path path = dir / "v.lfv";
  {
    LightFieldVideoWriter writer(path, Header());
    writer.Append(Frame(0), Info(0));
    writer.Append(Frame(1), Info(1));
    // Readable now: two frames, not complete.
    LightFieldVideo early(path);
    EXPECT_TRUE(early.is_video());
    EXPECT_FALSE(early.complete());
    ASSERT_EQ(early.frame_count(), 2u);
    EXPECT_TRUE(SameSamples(early.ReadFrame(1), Frame(1)));
    EXPECT_THROW(early.ReadFrame(2), Error);
    writer.Append(Frame(2), Info(2));
    early.Refresh();
    EXPECT_EQ(early.frame_count(), 3u);
    EXPECT_THROW(writer.Append(Frame(4), Info(4)), Error);  // out of order
    writer.Finish();
  }
  const LightFieldVideo video(path);
  EXPECT_TRUE(video.complete());
  EXPECT_EQ(video.header().fps, 30);
  EXPECT_EQ(video.header().metadata["recording"], "rec_00");
  ASSERT_EQ(video.frame_count(), 3u);
  for (const int k : {2, 0, 1}) {
    const LightField lf = video.ReadFrame(std::size_t(k));
    EXPECT_TRUE(SameSamples(lf, Frame(k))) << k;
    EXPECT_EQ(lf.metadata()["frame"], k);
    EXPECT_EQ(video.frame(std::size_t(k)).time_ns, Info(k).time_ns);
  }
  EXPECT_FALSE(video.frame(1).spread_ns);
  EXPECT_EQ(video.frame(2).spread_ns.value_or(0), 40'002);
  EXPECT_EQ(video.FrameHeader(2).dims.n_s, 17);
  EXPECT_TRUE(IsLightFieldVideo(path));

  // A still light field is a video of one frame.
  WriteLightField(Frame(5), dir / "still.lf");
  const LightFieldVideo still(dir / "still.lf");
  EXPECT_FALSE(still.is_video());
  ASSERT_EQ(still.frame_count(), 1u);
  EXPECT_TRUE(SameSamples(still.ReadFrame(0), Frame(5)));
  EXPECT_FALSE(IsLightFieldVideo(dir / "still.lf"));
  fs::remove_all(dir);
}

TEST(LightFieldVideoFile, DamageIsNamedAndAnUnfinishedWriterLeavesNothing) {
  const fs::path dir = testing::MakeScratchDir("lfcam_video_damage");
  const fs::path path = dir / "v.lfv";
  {
    LightFieldVideoWriter writer(path, Header());
    writer.Append(Frame(0), Info(0));
    writer.Append(Frame(1), Info(1));
    writer.Finish();
  }
  const std::string good = Bytes(path);
  const LightFieldVideo video(path);
  const auto write = [&](const std::string& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  };
  const auto refused = [&](const std::string& bytes) -> std::string {
    write(bytes);
    try {
      LightFieldVideo v(path);
      for (std::size_t k = 0; k < v.frame_count(); ++k) (void)v.ReadFrame(k);
    } catch (const Error& e) {
      return e.what();
    }
    return "accepted";
  };
  // A view's byte flipped in frame 1: that frame's view, named.
  std::string bad = good;
  bad[video.frame(1).offset + video.frame(1).bytes - 10] ^= 0x40;
  EXPECT_NE(refused(bad).find("frame 1"), std::string::npos) << refused(bad);
  // Frame 1's record damaged in a complete file.
  bad = good;
  bad[video.frame(1).offset - 64 + 10] ^= 1;
  EXPECT_NE(refused(bad).find("frame 1's record"), std::string::npos) << refused(bad);
  // Cut inside frame 1, complete flag still set: refused, the frame named.
  EXPECT_NE(refused(good.substr(0, video.frame(1).offset + 100)).find("frame 1"),
            std::string::npos);
  // The header's checksum.
  bad = good;
  bad[80] ^= 1;
  EXPECT_NE(refused(bad).find("header checksum"), std::string::npos);
  write(good);

  // An unfinished writer: its file is removed.
  {
    LightFieldVideoWriter writer(dir / "gone.lfv", Header());
    writer.Append(Frame(0), Info(0));
  }
  EXPECT_FALSE(fs::exists(dir / "gone.lfv"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lfcam
