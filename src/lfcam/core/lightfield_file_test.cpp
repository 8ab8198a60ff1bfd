#include "lfcam/core/lightfield_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>
#include <xxhash.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <future>
#include <iterator>
#include <random>
#include <thread>

#include "lfcam/core/error.h"
#include "lfcam/core/signal_cleanup.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

class LightFieldFileTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::MakeScratchDir("lfcam_file_test"); }
  void TearDown() override { fs::remove_all(dir_); }

  static LightField MakeLightField(SampleType type) {
    Slab slab;
    slab.uv.rows = 3;
    slab.uv.cols = 4;
    slab.uv.p_ca = Vec3(1, 2, 3000);
    slab.st_domain = {-0.2, -0.2, 1.2, 1.2};
    LightField lf({3, 4, 37, 21}, type, slab);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> uniform(0, 1);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        for (int l = 0; l < 21; ++l)
          for (int k = 0; k < 37; ++k)
            lf.set_linear_rgb(r, c, k, l, {uniform(rng), uniform(rng), float(k) / 37});
    lf.metadata() = {{"source", "test"}, {"note", "round trip"}};
    return lf;
  }

  static std::string Bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  static void Save(const fs::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
  }
  // The error message ReadLightField gives for `path`, or "" if it reads.
  static std::string ReadError(const fs::path& p) {
    try {
      ReadLightField(p);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
  // Rewrites the JSON header through `edit`, fixing up its size and checksum (a "lying" file).
  template <typename Edit>
  void RewriteHeader(const fs::path& p, Edit edit) {
    std::string bytes = Bytes(p);
    std::uint64_t header_bytes = 0, data_offset = 0;
    std::memcpy(&header_bytes, &bytes[16], 8);
    std::memcpy(&data_offset, &bytes[32], 8);
    auto header = nlohmann::json::parse(bytes.substr(40, header_bytes));
    edit(header);
    const std::string text = header.dump();
    ASSERT_LE(40 + text.size(), data_offset);
    bytes.replace(40, data_offset - 40, std::string(data_offset - 40, '\0'));
    bytes.replace(40, text.size(), text);
    const std::uint64_t size = text.size(), hash = XXH3_64bits(text.data(), text.size());
    std::memcpy(&bytes[16], &size, 8);
    std::memcpy(&bytes[24], &hash, 8);
    Save(p, bytes);
  }

  // Replaces the JSON header text (which may grow) and moves the data section to fit.
  void RewriteHeaderText(const fs::path& p, const std::function<void(std::string&)>& edit) {
    std::string bytes = Bytes(p);
    std::uint64_t header_bytes = 0, data_offset = 0;
    std::memcpy(&header_bytes, &bytes[16], 8);
    std::memcpy(&data_offset, &bytes[32], 8);
    std::string text = bytes.substr(40, header_bytes);
    const std::string data = bytes.substr(data_offset);
    edit(text);
    const std::uint64_t size = text.size(), hash = XXH3_64bits(text.data(), text.size());
    const std::uint64_t offset = (40 + size + 4095) / 4096 * 4096;
    std::string out = bytes.substr(0, 40) + text + std::string(offset - 40 - size, '\0') + data;
    std::memcpy(&out[16], &size, 8);
    std::memcpy(&out[24], &hash, 8);
    std::memcpy(&out[32], &offset, 8);
    Save(p, out);
  }

  fs::path dir_;
};

using testing::ScopedEnv;

TEST_F(LightFieldFileTest, RoundTripsEveryTypeAndCompression) {
  for (const SampleType type : {SampleType::kSrgb8, SampleType::kLinearF16})
    for (const Compression compression : {Compression::kNone, Compression::kZstd})
      for (const bool map : {true, false}) {
        const LightField lf = MakeLightField(type);
        const fs::path p = dir_ / "rt.lf";
        WriteLightField(lf, p, {compression, 3});
        const LightField back = ReadLightField(p, {true, map});
        ASSERT_EQ(back.dims(), lf.dims());
        EXPECT_EQ(back.sample_type(), type);
        EXPECT_EQ(0, std::memcmp(back.data(), lf.data(), lf.total_bytes()));
        EXPECT_EQ(back.metadata(), lf.metadata());
        EXPECT_TRUE(back.slab().uv.p_ca.isApprox(lf.slab().uv.p_ca));
        EXPECT_DOUBLE_EQ(back.slab().st_domain.s0, -0.2);
        const auto header = ReadLightFieldHeader(p);
        EXPECT_EQ(header.dims, lf.dims());
        EXPECT_EQ(header.compression, compression);
      }
}

TEST_F(LightFieldFileTest, UncompressedSamplesAreAlignedForMapping) {
  const fs::path p = dir_ / "a.lf";
  WriteLightField(MakeLightField(SampleType::kSrgb8), p);
  const LightField lf = ReadLightField(p);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(lf.data()) % 4096, 0u);
  EXPECT_EQ(fs::file_size(p) % 4096, (4ull * 3 * 37 * 21 * 3) % 4096);
}

TEST_F(LightFieldFileTest, CorruptViewIsNamed) {
  for (const Compression compression : {Compression::kNone, Compression::kZstd}) {
    const fs::path p = dir_ / "c.lf";
    WriteLightField(MakeLightField(SampleType::kSrgb8), p, {compression, 3});
    const auto header = ReadLightFieldHeader(p);
    std::string bytes = Bytes(p);
    // Flip one byte in the last view (row 2, col 3).
    bytes[bytes.size() - 5] ^= 0x40;
    Save(p, bytes);
    const std::string error = ReadError(p);
    EXPECT_NE(error.find("row 2, col 3"), std::string::npos) << error;
    EXPECT_NE(error.find("c.lf"), std::string::npos) << error;
    (void)header;
  }
}

TEST_F(LightFieldFileTest, TruncationIsDetected) {
  const fs::path p = dir_ / "t.lf";
  WriteLightField(MakeLightField(SampleType::kSrgb8), p);
  const std::string bytes = Bytes(p);
  for (const std::size_t keep :
       {std::size_t(0), std::size_t(20), std::size_t(200), std::size_t(5000), bytes.size() - 1}) {
    Save(p, bytes.substr(0, keep));
    const std::string error = ReadError(p);
    EXPECT_FALSE(error.empty()) << "kept " << keep;
    EXPECT_NE(error.find("t.lf"), std::string::npos) << error;
  }
}

TEST_F(LightFieldFileTest, BadMagicVersionAndHeaderChecksumAreRejected) {
  const fs::path p = dir_ / "m.lf";
  WriteLightField(MakeLightField(SampleType::kSrgb8), p);
  const std::string good = Bytes(p);
  std::string bad = good;
  bad[1] = 'X';
  Save(p, bad);
  EXPECT_NE(ReadError(p).find("magic"), std::string::npos);
  bad = good;
  bad[8] = 9;  // version
  Save(p, bad);
  EXPECT_NE(ReadError(p).find("version 9"), std::string::npos) << ReadError(p);
  bad = good;
  bad[60] ^= 1;  // inside the JSON header
  Save(p, bad);
  EXPECT_NE(ReadError(p).find("header checksum"), std::string::npos) << ReadError(p);
  Save(p, "not a light field at all, just some text that is long enough");
  EXPECT_NE(ReadError(p).find("magic"), std::string::npos);
  EXPECT_NE(ReadError(dir_ / "missing.lf").find("cannot open"), std::string::npos);
}

TEST_F(LightFieldFileTest, LyingHeadersAreRejectedWithoutHugeAllocations) {
  const fs::path p = dir_ / "l.lf";
  struct Case {
    const char* what;
    std::function<void(nlohmann::json&)> edit;
    const char* expect;
    Compression compression = Compression::kNone;
  };
  const std::vector<Case> cases = {
      {"absurd dims", [](auto& h) { h["dims"]["n_s"] = 2000000000; }, "outside 1..65536"},
      {"huge but in range",
       [](auto& h) {
         h["dims"]["n_s"] = 60000;
         h["dims"]["n_t"] = 60000;
       },
       "absurd"},
      {"negative", [](auto& h) { h["dims"]["rows"] = -3; }, "outside 1..4096"},
      {"wrapped", [](auto& h) { h["dims"]["n_t"] = (std::uint64_t(1) << 32) + 21; },
       "outside 1..65536"},
      {"fractional", [](auto& h) { h["dims"]["n_s"] = 37.4; }, "whole number"},
      {"fractional slab grid", [](auto& h) { h["slab"]["cols"] = 4.0; }, "whole number"},
      {"channels wrapped", [](auto& h) { h["dims"]["channels"] = (std::uint64_t(1) << 32) + 3; },
       "outside"},
      {"negative offset", [](auto& h) { h["views"][2]["offset"] = -8; }, "negative"},
      {"views out of order", [](auto& h) { std::swap(h["views"][1], h["views"][2]); },
       "out of order"},
      {"metadata not an object", [](auto& h) { h["metadata"] = 7; }, "metadata"},
      {"deep metadata",
       [](auto& h) {
         nlohmann::json deep = 1;
         for (int i = 0; i < 100; ++i) deep = nlohmann::json::array({deep});
         h["metadata"]["deep"] = deep;
       },
       "nests"},
      {"nan in slab", [](auto& h) { h["slab"]["pitch_mm"] = "NaN"; }, "must be a number"},
      {"sizes do not add up", [](auto& h) { h["dims"]["n_t"] = 22; }, "expected"},
      {"view past the end", [](auto& h) { h["views"][11]["offset"] = 1u << 30; }, "does not fit",
       Compression::kZstd},
      {"missing views", [](auto& h) { h["views"].erase(3); }, "view table"},
      {"wrong grid", [](auto& h) { h["slab"]["rows"] = 2; }, "grid"},
      {"bad type", [](auto& h) { h["sample_type"] = "float64"; }, "sample type"},
      {"bad checksum text", [](auto& h) { h["views"][0]["xxh3"] = "zz"; }, "hex"},
      {"not an object", [](auto& h) { h["dims"] = "big"; }, "expected a JSON object"},
  };
  for (const auto& c : cases) {
    WriteLightField(MakeLightField(SampleType::kSrgb8), p, {c.compression, 3});
    RewriteHeader(p, c.edit);
    const std::string error = ReadError(p);
    EXPECT_NE(error.find(c.expect), std::string::npos) << c.what << ": " << error;
    EXPECT_NE(error.find("l.lf"), std::string::npos) << c.what << ": " << error;
  }
}

TEST_F(LightFieldFileTest, FailedWritesLeaveNothingBehind) {
  const LightField lf = MakeLightField(SampleType::kSrgb8);
  EXPECT_THROW(WriteLightField(lf, dir_ / "no" / "such" / "dir.lf"), Error);
  // An existing file is replaced only when the new one is complete.
  const fs::path p = dir_ / "keep.lf";
  WriteLightField(lf, p);
  WriteLightField(lf, p, {Compression::kZstd, 1});
  EXPECT_EQ(ReadLightFieldHeader(p).compression, Compression::kZstd);
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++files;
  EXPECT_EQ(files, 1);  // no temporary left over
}

}  // namespace
}  // namespace lfcam

namespace lfcam {
namespace {

TEST_F(LightFieldFileTest, DeeplyNestedJsonIsRefusedBeforeParsing) {
  const fs::path p = dir_ / "deep.lf";
  WriteLightField(MakeLightField(SampleType::kSrgb8), p);
  RewriteHeaderText(p, [](std::string& text) {
    const std::size_t at = text.find("\"metadata\"");
    ASSERT_NE(at, std::string::npos);
    text.insert(at, "\"deep\":" + std::string(100000, '[') + std::string(100000, ']') + ",");
  });
  const std::string error = ReadError(p);
  EXPECT_NE(error.find("nests 100001 levels deep"), std::string::npos) << error;
  EXPECT_NE(error.find("deep.lf"), std::string::npos) << error;
}

TEST_F(LightFieldFileTest, ZstdBombIsRefusedBeforeDecoding) {
  // 2 views of 2048 x 1024 zeros: 12.6 MB of samples in a file of a few kB.
  Slab slab;
  slab.uv.rows = 1;
  slab.uv.cols = 2;
  slab.uv.p_ca = Vec3(1, 2, 3000);
  const LightField lf({1, 2, 2048, 1024}, SampleType::kSrgb8, slab);
  const fs::path bomb = dir_ / "bomb.lf", flat = dir_ / "flat.lf";
  WriteLightField(lf, bomb, {Compression::kZstd, 3});
  WriteLightField(lf, flat);
  ASSERT_LT(fs::file_size(bomb), 100000u);
  const ScopedEnv limit("LFCAM_MEMORY_LIMIT", "8M");
  const std::string error = ReadError(bomb);
  EXPECT_NE(error.find("memory limit"), std::string::npos) << error;
  EXPECT_NE(error.find("bomb.lf"), std::string::npos) << error;
  // An uncompressed file is mapped, not allocated: the limit does not apply...
  EXPECT_EQ(ReadError(flat), "");
  // ...unless it is read into memory.
  EXPECT_THROW(ReadLightField(flat, {true, false}), Error);
}

TEST_F(LightFieldFileTest, SpecialFilesAreRefusedWithoutBlocking) {
  const fs::path fifo = dir_ / "pipe.lf";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // A blocking open of a FIFO with no writer would never return: run it aside and time it.
  auto promise = std::make_shared<std::promise<std::string>>();
  auto result = promise->get_future();
  std::thread([promise, fifo] { promise->set_value(ReadError(fifo)); }).detach();
  ASSERT_EQ(result.wait_for(std::chrono::seconds(10)), std::future_status::ready)
      << "reading a FIFO blocked";
  const std::string error = result.get();
  EXPECT_NE(error.find("FIFO"), std::string::npos) << error;
  EXPECT_NE(ReadError(dir_).find("directory"), std::string::npos);
  EXPECT_NE(ReadError("/dev/null").find("device"), std::string::npos);
}

TEST_F(LightFieldFileTest, FileTruncatedWhileMappedEndsInAClearError) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const fs::path p = dir_ / "shrinks.lf";
  WriteLightField(MakeLightField(SampleType::kSrgb8), p);
  EXPECT_EXIT(
      {
        InstallSignalCleanup();
        const LightField lf = ReadLightField(p);
        ::truncate(p.c_str(), 4096);  // another process rewrites the file in place
        volatile std::uint8_t sum = 0;
        for (std::size_t i = 0; i < lf.total_bytes(); ++i) sum = sum + lf.data()[i];
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(1), "shrinks.lf: the file changed on disk");
}

// The generator of corrupt files: random byte flips, truncations, insertions and header edits of
// valid files of both compressions. Every one must be read or refused with lfcam::Error: no
// crash, no other exception, no sanitizer report (this test runs under the asan preset too).
TEST_F(LightFieldFileTest, RandomlyCorruptedFilesAreReadOrRefusedCleanly) {
  std::mt19937_64 rng(2026);
  const fs::path p = dir_ / "mutant.lf";
  int refused = 0, read = 0;
  for (const Compression compression : {Compression::kNone, Compression::kZstd}) {
    WriteLightField(MakeLightField(SampleType::kSrgb8), p, {compression, 3});
    const std::string good = Bytes(p);
    for (int trial = 0; trial < 400; ++trial) {
      std::string bad = good;
      const int edits = 1 + int(rng() % 4);
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = rng() % bad.size();
        switch (rng() % 4) {
          case 0:
            bad[at] = char(rng());
            break;
          case 1:
            bad.resize(at);
            break;
          case 2:
            bad = bad.substr(0, at) + std::string(1 + rng() % 64, char(rng())) + bad.substr(at);
            break;
          default:
            bad[at % std::min<std::size_t>(bad.size(), 4096)] ^= char(1 << (rng() % 8));
        }
        if (bad.empty()) bad.push_back('x');
      }
      Save(p, bad);
      for (const bool map : {true, false}) {
        try {
          ReadLightField(p, {true, map});
          ++read;
        } catch (const Error&) {
          ++refused;
        }
      }
    }
  }
  EXPECT_GT(refused, 1000);
  // Checksums cover every byte that matters: a read file is one whose edits missed them.
  EXPECT_LT(read, refused);
}

}  // namespace
}  // namespace lfcam

namespace lfcam {
namespace {

// Format version 2: each view's measured camera pose round-trips; version 1 files (no poses)
// still read; poses on some views only, or in a version 1 file, are refused.
TEST_F(LightFieldFileTest, MeasuredPosesRoundTripAndVersionOneStillReads) {
  LightField lf = MakeLightField(SampleType::kSrgb8);
  std::vector<ViewPose> poses;
  for (int i = 0; i < 12; ++i)
    poses.push_back({Vec3(10.0 * i, 5.0, 3600.0 + i),
                     Eigen::AngleAxisd(0.01 * i, Vec3::UnitZ()).toRotationMatrix(), std::nullopt});
  lf.set_measured_poses(poses);
  const fs::path p = dir_ / "poses.lf";
  WriteLightField(lf, p);
  const LightField back = ReadLightField(p);
  ASSERT_EQ(back.measured_poses().size(), 12u);
  EXPECT_EQ(back.camera_center(2, 3), poses[11].center);
  EXPECT_NEAR((back.measured_poses()[7].orientation - poses[7].orientation).norm(), 0, 1e-12);
  EXPECT_EQ(ReadLightFieldHeader(p).version, 2u);
  EXPECT_THROW(lf.set_measured_poses({poses[0]}), Error);

  // A version 1 file: the same bytes with the preamble's version set to 1 (the preamble is not
  // covered by the header checksum). Without poses it reads; with them it is refused.
  const fs::path plain = dir_ / "plain.lf";
  WriteLightField(MakeLightField(SampleType::kSrgb8), plain);
  std::string bytes = Bytes(plain);
  bytes[8] = 1;
  Save(plain, bytes);
  const LightField old = ReadLightField(plain);
  EXPECT_TRUE(old.measured_poses().empty());
  EXPECT_EQ(old.camera_center(1, 2), old.slab().uv.camera_center(1, 2));
  bytes = Bytes(p);
  bytes[8] = 1;
  Save(p, bytes);
  EXPECT_NE(ReadError(p).find("version 1 file has no measured"), std::string::npos) << ReadError(p);
}

// Format version 3: the camera that recorded each view (its pinhole intrinsics) round-trips and
// makes the file version 3; a version 2 file that claims them, or intrinsics on some views only,
// are refused.
TEST_F(LightFieldFileTest, ViewIntrinsicsRoundTripAsVersionThree) {
  LightField lf = MakeLightField(SampleType::kSrgb8);
  std::vector<ViewPose> poses;
  for (int i = 0; i < 12; ++i)
    poses.push_back({Vec3(10.0 * i, 5.0, 3600.0), Mat3::Identity(),
                     CameraIntrinsics{64, 48, 80.0, 80.0, 31.5 + 0.25 * i, 23.5 - 0.5 * i, {}}});
  lf.set_measured_poses(poses);
  const fs::path p = dir_ / "cameras.lf";
  WriteLightField(lf, p);
  EXPECT_EQ(ReadLightFieldHeader(p).version, 3u);
  const LightField back = ReadLightField(p);
  ASSERT_TRUE(back.has_view_cameras());
  EXPECT_EQ(back.measured_poses()[5].intrinsics->cx, 31.5 + 0.25 * 5);
  EXPECT_EQ(back.measured_poses()[11].intrinsics->cy, 23.5 - 0.5 * 11);
  EXPECT_EQ(back.measured_poses()[3].intrinsics->width, 64);
  std::string bytes = Bytes(p);
  bytes[8] = 2;
  Save(p, bytes);
  EXPECT_NE(ReadError(p).find("version 2 file has no view intrinsics"), std::string::npos)
      << ReadError(p);
  poses[4].intrinsics.reset();
  EXPECT_THROW(lf.set_measured_poses(poses), Error);
}

// Format version 4: each view's own st window (its offset from the reference grid in whole
// samples) round-trips and makes the file version 4; a version 3 file that claims windows,
// windows on some views only, offsets that are not whole numbers or out of range are refused
// naming the view; all-zero offsets are the shared grid (version 2 or 3).
TEST_F(LightFieldFileTest, ViewWindowsRoundTripAsVersionFour) {
  LightField lf = MakeLightField(SampleType::kSrgb8);
  std::vector<StOffset> offsets;
  for (int i = 0; i < 12; ++i) offsets.push_back({3 * (i % 4) - 4, -2 * (i / 4)});
  lf.set_st_offsets(offsets);
  const fs::path p = dir_ / "windows.lf";
  WriteLightField(lf, p);
  EXPECT_EQ(ReadLightFieldHeader(p).version, 4u);
  const LightField back = ReadLightField(p);
  ASSERT_TRUE(back.has_view_windows());
  EXPECT_EQ(back.st_offsets(), offsets);
  EXPECT_EQ(back.st_offset(2, 3), (StOffset{5, -4}));
  // The union of the windows, in reference samples and in window units.
  const LightField::SampleRange all = back.st_union_samples();
  EXPECT_EQ(all.k0, -4);
  EXPECT_EQ(all.k1, 5 + 36);
  EXPECT_EQ(all.l0, -4);
  EXPECT_EQ(all.l1, 20);
  const double ds = 1.4 / 37;
  EXPECT_NEAR(back.st_union().s0, -0.2 - 4 * ds, 1e-12);
  EXPECT_NEAR(back.st_union().s1, 1.2 + 5 * ds, 1e-12);
  EXPECT_NEAR(back.st_sampling(2, 3).s_of(0), back.st_sampling().s_of(5), 1e-12);

  const fs::path bad = dir_ / "bad.lf";
  const auto refused = [&](const std::function<void(nlohmann::json&)>& edit) {
    fs::copy_file(p, bad, fs::copy_options::overwrite_existing);
    RewriteHeader(bad, edit);
    return ReadError(bad);
  };
  std::string bytes = Bytes(p);
  bytes[8] = 3;
  Save(bad, bytes);
  EXPECT_NE(ReadError(bad).find("version 3 file has no view st windows"), std::string::npos)
      << ReadError(bad);
  std::string e = refused([](nlohmann::json& h) { h["views"][5].erase("st_offset"); });
  EXPECT_NE(e.find("view (row 1, col 1)"), std::string::npos) << e;
  EXPECT_NE(e.find("every view or none"), std::string::npos) << e;
  e = refused([](nlohmann::json& h) { h["views"][0]["st_offset"] = {0.5, 1}; });
  EXPECT_NE(e.find("st_offset must be [k, l]"), std::string::npos) << e;
  e = refused([](nlohmann::json& h) { h["views"][0]["st_offset"] = {1 << 24, 0}; });
  EXPECT_NE(e.find("out of range"), std::string::npos) << e;
  EXPECT_THROW(lf.set_st_offsets({{1, 1}}), Error);  // not one per view

  // No windows (all zero): the shared grid, written as before.
  lf.set_st_offsets(std::vector<StOffset>(12));
  EXPECT_FALSE(lf.has_view_windows());
  WriteLightField(lf, p);
  EXPECT_EQ(ReadLightFieldHeader(p).version, 2u);
}

}  // namespace
}  // namespace lfcam
