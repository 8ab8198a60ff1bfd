#include "lfcam/core/lightfield_file.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <xxhash.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>

#include "lfcam/core/error.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

class LightFieldFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lfcam_file_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
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

  fs::path dir_;
};

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
      {"absurd dims", [](auto& h) { h["dims"]["n_s"] = 2000000000; }, "absurd"},
      {"huge but in range",
       [](auto& h) {
         h["dims"]["n_s"] = 60000;
         h["dims"]["n_t"] = 60000;
       },
       "absurd"},
      {"negative", [](auto& h) { h["dims"]["rows"] = -3; }, "absurd"},
      {"sizes do not add up", [](auto& h) { h["dims"]["n_t"] = 22; }, "expected"},
      {"view past the end", [](auto& h) { h["views"][11]["offset"] = 1u << 30; }, "does not fit",
       Compression::kZstd},
      {"missing views", [](auto& h) { h["views"].erase(3); }, "view table"},
      {"wrong grid", [](auto& h) { h["slab"]["rows"] = 2; }, "grid"},
      {"bad type", [](auto& h) { h["sample_type"] = "float64"; }, "sample type"},
      {"bad checksum text", [](auto& h) { h["views"][0]["xxh3"] = "zz"; }, "hex"},
      {"not an object", [](auto& h) { h["dims"] = "big"; }, "malformed"},
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
