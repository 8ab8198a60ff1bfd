#include "lfcam/render/prefilter_cache.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string>

#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/prefilter_memory.h"
#include "lfcam/render/quadrilinear_limit.h"
#include "lfcam/render/render_test_cases.h"
#include "lfcam/sim/test_paper_lightfield.h"

namespace lfcam {
namespace {

RenderResult Limit(const LightField& lf, const VirtualCameraParams& p, PrefilterCache* cache,
                   PrefilterMemory* memory = nullptr) {
  CpuRenderOptions o;
  o.integrator = Integrator::kCamerasQuadrilinear;
  o.prefilter_cache = cache;
  o.prefilter_memory = memory;
  return RenderLightFieldCpu(lf, VirtualCamera(p), o);
}

// "kept every M x N" of a limit frame's path.
std::string Strides(const RenderResult& r) {
  const std::size_t at = r.path.find("kept every");
  return at == std::string::npos ? "" : r.path.substr(at, r.path.find(')', at) - at);
}

// A frame rendered from the kept copy is the frame rendered from its own copy, byte for byte:
// again at the same view (nothing filtered), with the eye moved and the view turned at the same
// focus (only what the kept copy lacks filtered), and at another focus or from another light
// field (a fresh copy).
TEST(PrefilterCache, FiltersOnlyWhatEarlierFramesDidNotAndRendersTheSameFrames) {
  const LightField lf = testing::SharedPaperLightField();
  PrefilterCache cache;
  VirtualCameraParams p =
      render_test::ConvergenceCamera{"far focus", {300, 275, 3600}, {300, 275, 0}, 500, 9000, 192,
                                     true}
          .Params(64);
  const auto same_as_alone = [&](const VirtualCameraParams& q) {
    const RenderResult kept = Limit(lf, q, &cache), alone = Limit(lf, q, nullptr);
    EXPECT_EQ(cv::norm(kept.image, alone.image, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(kept.hit_mask, alone.hit_mask, cv::NORM_INF), 0.0);
    return kept;
  };
  RenderResult first = same_as_alone(p);
  const long long whole = cache.last_filtered_samples();
  EXPECT_GT(whole, 0);
  EXPECT_EQ(first.path.find("from the last frame"), std::string::npos) << first.path;
  EXPECT_NE(first.path.find("kept every"), std::string::npos) << first.path;

  const RenderResult again = same_as_alone(p);
  EXPECT_EQ(cache.last_filtered_samples(), 0);
  EXPECT_NE(again.path.find("from the last frame"), std::string::npos) << again.path;

  // The eye 30 mm across and the view following it: a little more of each view.
  p.eye += Vec3(30, 0, 0);
  p.look_at += Vec3(30, 0, 0);
  same_as_alone(p);
  EXPECT_GT(cache.last_filtered_samples(), 0);
  EXPECT_LT(cache.last_filtered_samples(), whole / 4);
  // Back where it was: all kept.
  p.eye -= Vec3(30, 0, 0);
  p.look_at -= Vec3(30, 0, 0);
  same_as_alone(p);
  EXPECT_EQ(cache.last_filtered_samples(), 0);

  // Another focus: another tent, a fresh copy.
  p.focus_distance_mm = 7000;
  same_as_alone(p);
  EXPECT_GT(cache.last_filtered_samples(), whole / 2);

  // The same samples in views of windows of their own (a copy sharing the buffer): a fresh copy,
  // laid out for them.
  LightField windows = lf;
  ASSERT_EQ(windows.samples_serial(), lf.samples_serial());
  std::vector<StOffset> offsets;
  for (int v = 0; v < int(lf.dims().view_count()); ++v) offsets.push_back({v % 3 - 1, v % 2});
  windows.set_st_offsets(offsets);
  const RenderResult in_windows = Limit(windows, p, &cache);
  EXPECT_GT(cache.last_filtered_samples(), whole / 2);
  EXPECT_EQ(cv::norm(in_windows.image, Limit(windows, p, nullptr).image, cv::NORM_INF), 0.0);
  Limit(lf, p, &cache);  // and back
  EXPECT_GT(cache.last_filtered_samples(), whole / 2);

  // Another light field with the same layout (another buffer): a fresh copy.
  const LightField other = testing::SharedPaperLightField();
  ASSERT_NE(other.samples_serial(), lf.samples_serial());
  Limit(other, p, &cache);
  EXPECT_GT(cache.last_filtered_samples(), whole / 2);
}

// Frames whose filtered copies are made in memory an earlier frame left
// (render/prefilter_memory.h) are the frames rendered in fresh memory, byte for byte: a frame
// reads only what it filtered. The memory starts out holding a pattern no filtered view holds, so
// that a read of anything else would show; frames of several foci (several strides) and eyes
// follow one another in it, in views of a shared window and of windows of their own.
TEST(PrefilterMemory, FramesInAnEarlierFramesMemoryAreTheFramesRenderedAlone) {
  const LightField shared = testing::SharedPaperLightField();
  LightField windows = shared;
  std::vector<StOffset> offsets;
  for (int v = 0; v < int(shared.dims().view_count()); ++v) offsets.push_back({v % 3 - 1, v % 2});
  windows.set_st_offsets(offsets);
  const std::size_t bytes = PrefilteredCopyBytes(windows, 1, 1) + 4096;
  SampleBuffer pattern = SampleBuffer::Allocate(bytes);
  std::memset(pattern.mutable_data(), 0xA5, bytes);
  const std::uint8_t* const pattern_data = pattern.data();
  PrefilterMemory memory;
  memory.Give(std::move(pattern));
  std::set<std::string> strides;
  for (const LightField* lf : {&shared, static_cast<const LightField*>(&windows)}) {
    for (const double focus : {9000.0, 2000.0, 5200.0, 3000.0}) {
      for (const double across : {0.0, 140.0}) {
        VirtualCameraParams p =
            render_test::ConvergenceCamera{
                "a frame", {300 + across, 275, 3600}, {300 + across, 275, 0}, 500, focus, 240, true}
                .Params(64);
        const RenderResult in_memory = Limit(*lf, p, nullptr, &memory);
        const RenderResult alone = Limit(*lf, p, nullptr);
        EXPECT_EQ(cv::norm(in_memory.image, alone.image, cv::NORM_INF), 0.0) << in_memory.path;
        EXPECT_EQ(cv::norm(in_memory.hit_mask, alone.hit_mask, cv::NORM_INF), 0.0);
        strides.insert(Strides(in_memory));
      }
    }
  }
  EXPECT_GE(strides.size(), 3u) << fmt::format("{}", fmt::join(strides, "; "));
  // The memory came back after every frame, and is held.
  EXPECT_EQ(memory.Take().data(), pattern_data);

  // Memory too small for a frame is replaced by the frame's own, which is then held.
  memory.Give(SampleBuffer::Allocate(16));
  const VirtualCameraParams p =
      render_test::ConvergenceCamera{"far", {300, 275, 3600}, {300, 275, 0}, 500, 9000, 192, true}
          .Params(64);
  Limit(shared, p, nullptr, &memory);
  const SampleBuffer held = memory.Take();
  EXPECT_GT(held.size(), 16u);
  // While a frame has it, another frame (on another thread) gets fresh memory.
  EXPECT_EQ(memory.Take().size(), 0u);
}

}  // namespace
}  // namespace lfcam
