#include "lfcam/depth/depth_map.h"

#include <fmt/format.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_codec.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/limits.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

constexpr char kTextKey[] = "lfcam-depth";
constexpr std::size_t kPngSignatureBytes = 8;

std::uint32_t ReadBigEndian32(const std::uint8_t* p) {
  return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3];
}

void AppendBigEndian32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(char((v >> shift) & 0xFF));
}

// A PNG tEXt chunk (keyword, NUL, Latin-1 text) with its CRC.
std::string TextChunk(const std::string& key, const std::string& text) {
  std::string body = "tEXt" + key + '\0' + text;
  std::string chunk;
  AppendBigEndian32(chunk, std::uint32_t(body.size() - 4));
  chunk += body;
  AppendBigEndian32(chunk, std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()),
                                               uInt(body.size()))));
  return chunk;
}

// Inserts chunks right after the IHDR chunk of an encoded PNG.
std::string InsertAfterHeader(const std::vector<std::uint8_t>& png, const std::string& chunks) {
  const std::size_t ihdr_end = kPngSignatureBytes + 8 + 13 + 4;
  CV_Assert(png.size() > ihdr_end);
  std::string out(png.begin(), png.begin() + std::ptrdiff_t(ihdr_end));
  out += chunks;
  out.append(png.begin() + std::ptrdiff_t(ihdr_end), png.end());
  return out;
}

// The tEXt chunks of a PNG, keyword -> text (malformed chunks end the walk).
std::map<std::string, std::string> TextChunks(std::span<const std::uint8_t> png) {
  std::map<std::string, std::string> texts;
  std::size_t at = kPngSignatureBytes;
  while (at + 12 <= png.size()) {
    const std::uint32_t length = ReadBigEndian32(&png[at]);
    if (length > png.size() - at - 12) break;
    const char* type = reinterpret_cast<const char*>(&png[at + 4]);
    const char* data = reinterpret_cast<const char*>(&png[at + 8]);
    if (std::memcmp(type, "tEXt", 4) == 0) {
      const std::string body(data, length);
      const std::size_t nul = body.find('\0');
      if (nul != std::string::npos) texts[body.substr(0, nul)] = body.substr(nul + 1);
    }
    if (std::memcmp(type, "IEND", 4) == 0) break;
    at += 12 + std::size_t(length);
  }
  return texts;
}

fs::path WithSuffix(const fs::path& path, const std::string& suffix) {
  fs::path out = path;
  out.replace_extension();
  out += suffix;
  return out;
}

}  // namespace

fs::path ConfidencePathFor(const fs::path& depth_png) {
  return WithSuffix(depth_png, ".confidence.png");
}
fs::path PreviewPathFor(const fs::path& depth_png) { return WithSuffix(depth_png, ".preview.png"); }

std::string EncodeDepthPng(const DepthMap& map, const std::string& extra_json) {
  if (!map.range.valid())
    throw Error(fmt::format("depth map of view ({}, {}): invalid range {} .. {} mm", map.row,
                            map.col, map.range.near_mm, map.range.far_mm));
  CV_Assert(map.depth.type() == CV_32FC1);
  const double near = map.range.near_mm, span = map.range.far_mm - map.range.near_mm;
  cv::Mat coded(map.depth.size(), CV_16UC1);
  for (int l = 0; l < map.n_t(); ++l) {
    const float* d = map.depth.ptr<float>(l);
    std::uint16_t* out = coded.ptr<std::uint16_t>(map.n_t() - 1 - l);  // upright
    for (int k = 0; k < map.n_s(); ++k) {
      if (!std::isfinite(d[k])) {
        out[k] = 0;
        continue;
      }
      const double x = std::clamp((d[k] - near) / span, 0.0, 1.0);
      out[k] = std::uint16_t(1 + std::lround(x * 65534.0));
    }
  }
  std::vector<std::uint8_t> png = EncodePngBytes(coded);
  nlohmann::json meta = nlohmann::json::parse(extra_json);
  meta["format"] = "lfcam-depth";
  meta["version"] = 1;
  meta["quantity"] = "distance from the camera array's plane along the viewing direction (mm)";
  meta["encoding"] = "0 unknown; 1..65535 linear from near_mm to far_mm";
  meta["near_mm"] = near;
  meta["far_mm"] = map.range.far_mm;
  meta["view"] = {map.row, map.col};
  meta["n_s"] = map.n_s();
  meta["n_t"] = map.n_t();
  const std::string chunks = TextChunk(kTextKey, meta.dump()) +
                             TextChunk("depth_near_mm", fmt::format("{}", near)) +
                             TextChunk("depth_far_mm", fmt::format("{}", map.range.far_mm));
  return InsertAfterHeader(png, chunks);
}

DepthMap ReadDepthPng(const fs::path& path) {
  return DecodeDepthPng(ReadFileBytes(path, kMaxEncodedImageBytes, "depth map"), path.string());
}

DepthMap DecodeDepthPng(std::span<const std::uint8_t> bytes, const std::string& where) {
  const auto texts = TextChunks(bytes);
  const auto it = texts.find(kTextKey);
  if (it == texts.end())
    throw Error(fmt::format("{}: not an lfcam depth map (no \"{}\" text chunk in the PNG)", where,
                            kTextKey));
  const nlohmann::json meta = ParseJsonBounded(it->second, where + " (depth metadata)");
  DepthMap map;
  map.range = {JsonNumber(meta, "near_mm", where), JsonNumber(meta, "far_mm", where)};
  const nlohmann::json& view = JsonField(meta, "view", where);
  if (!view.is_array() || view.size() != 2)
    throw Error(fmt::format("{}: \"view\" must be [row, col]", where));
  map.row = int(JsonInteger(view[0], "", 0, kMaxViewsPerSide - 1, where + ": view row"));
  map.col = int(JsonInteger(view[1], "", 0, kMaxViewsPerSide - 1, where + ": view col"));
  if (!map.range.valid())
    throw Error(fmt::format("{}: invalid depth range {} .. {} mm", where, map.range.near_mm,
                            map.range.far_mm));
  const cv::Mat coded = DecodeImageBytes(bytes, where);
  if (coded.type() != CV_16UC1)
    throw Error(fmt::format("{}: a depth map must be a 16-bit grey PNG", where));
  const double near = map.range.near_mm;
  const double step = (map.range.far_mm - map.range.near_mm) / 65534.0;  // a code's depth
  map.depth.create(coded.size(), CV_32FC1);
  for (int l = 0; l < map.n_t(); ++l) {
    const std::uint16_t* in = coded.ptr<std::uint16_t>(map.n_t() - 1 - l);
    float* d = map.depth.ptr<float>(l);
    for (int k = 0; k < map.n_s(); ++k) d[k] = in[k] == 0 ? NAN : float(near + (in[k] - 1) * step);
  }
  return map;
}

std::string EncodeConfidencePng(const DepthMap& map) {
  cv::Mat coded(map.depth.size(), CV_8UC1, cv::Scalar(0));
  if (!map.confidence.empty()) {
    CV_Assert(map.confidence.size() == map.depth.size() && map.confidence.type() == CV_32FC1);
    cv::Mat upright;
    cv::flip(map.confidence, upright, 0);
    upright.convertTo(coded, CV_8U, 255.0);
  }
  const std::vector<std::uint8_t> png = EncodePngBytes(coded);
  return {png.begin(), png.end()};
}

void ReadConfidencePng(const fs::path& path, DepthMap& map) {
  const auto bytes = ReadFileBytes(path, kMaxEncodedImageBytes, "confidence map");
  const cv::Mat coded = DecodeImageBytes(bytes, path.string());
  if (coded.type() != CV_8UC1 || coded.size() != map.depth.size())
    throw Error(fmt::format("{}: a confidence map must be an 8-bit grey PNG of {}x{}",
                            path.string(), map.n_s(), map.n_t()));
  cv::Mat upright;
  cv::flip(coded, upright, 0);
  upright.convertTo(map.confidence, CV_32F, 1.0 / 255.0);
}

cv::Mat DepthPreview(const DepthMap& map, const std::string& length_unit) {
  const int w = map.n_s(), h = map.n_t();
  // A depth's label: metres where lengths are mm, else the light field's own numbers.
  const bool metric = length_unit == "mm";
  // Inverse depth spreads the colours where a light field resolves depth best (near); the scale
  // bar is laid out the same way, so that each of its colours sits beside its own depth.
  const double q_near = 1.0 / map.range.near_mm, q_far = 1.0 / map.range.far_mm;
  const auto label = [&](int i) {  // the scale's i-th of five labels, near (0) to far (4)
    const double depth = 1.0 / (q_near + (q_far - q_near) * i / 4.0);
    const double shown = metric ? depth / 1000.0 : depth;
    const int decimals = shown >= 100 ? 0 : shown >= 10 ? 1 : 2;
    return fmt::format("{:.{}f} {}", shown, decimals, metric ? "m" : length_unit);
  };
  cv::Mat index(h, w, CV_8UC1), unknown(h, w, CV_8UC1);
  for (int l = 0; l < h; ++l) {
    const float* d = map.depth.ptr<float>(l);
    std::uint8_t* out = index.ptr<std::uint8_t>(h - 1 - l);
    std::uint8_t* none = unknown.ptr<std::uint8_t>(h - 1 - l);
    for (int k = 0; k < w; ++k) {
      none[k] = std::isfinite(d[k]) ? 0 : 255;
      const double x = std::isfinite(d[k]) ? (1.0 / d[k] - q_far) / (q_near - q_far) : 0.0;
      out[k] = std::uint8_t(std::lround(255.0 * std::clamp(x, 0.0, 1.0)));
    }
  }
  cv::Mat colour;
  cv::applyColorMap(index, colour, cv::COLORMAP_TURBO);  // BGR
  colour.setTo(cv::Scalar::all(0), unknown);
  // The scale bar: a strip of the colour map from near (top) to far (bottom), labelled.
  const double scale = std::clamp(h / 600.0, 0.35, 1.0);
  int baseline = 0;
  cv::Size text;
  for (int i = 0; i <= 4; ++i) {  // the widest label
    const cv::Size size = cv::getTextSize(label(i), cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
    text = {std::max(text.width, size.width), std::max(text.height, size.height)};
  }
  const int bar_w = std::max(12, w / 40), label_w = text.width + 8, margin = bar_w / 2;
  cv::Mat sheet(h, w + margin + bar_w + label_w, CV_8UC3, cv::Scalar::all(255));
  colour.copyTo(sheet(cv::Rect(0, 0, w, h)));
  cv::Mat ramp(h, 1, CV_8UC1);
  for (int y = 0; y < h; ++y) {
    // Row y shows the depth at fraction y / (h - 1) of the way from near to far in 1/D, as the
    // map's colours run: the labels' depths at rows 0, (h - 1) / 4, ... h - 1.
    const double x = h > 1 ? 1.0 - y / (h - 1.0) : 1.0;
    ramp.at<std::uint8_t>(y) = std::uint8_t(std::lround(255.0 * x));
  }
  cv::Mat ramp_colour;
  cv::applyColorMap(ramp, ramp_colour, cv::COLORMAP_TURBO);
  cv::resize(ramp_colour, sheet(cv::Rect(w + margin, 0, bar_w, h)), {bar_w, h}, 0, 0,
             cv::INTER_NEAREST);
  const int x_text = w + margin + bar_w + 4;
  for (int i = 0; i <= 4; ++i) {
    const int y = std::clamp(int(std::lround((h - 1) * i / 4.0 + text.height / 2.0)),
                             text.height + 2, h - baseline - 1);
    cv::putText(sheet, label(i), {x_text, y}, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar::all(0),
                1, cv::LINE_AA);
  }
  cv::cvtColor(sheet, sheet, cv::COLOR_BGR2RGB);
  return sheet;
}

void WriteDepthFiles(const fs::path& path, const DepthMap& map, const std::string& extra_json,
                     const std::string& length_unit) {
  nlohmann::json extra = nlohmann::json::parse(extra_json);
  extra["length_unit"] = length_unit;  // what near_mm and far_mm are in
  const std::string depth = EncodeDepthPng(map, extra.dump());
  const std::string confidence = EncodeConfidencePng(map);
  cv::Mat bgr;
  cv::cvtColor(DepthPreview(map, length_unit), bgr, cv::COLOR_RGB2BGR);
  const std::vector<std::uint8_t> preview = EncodePngBytes(bgr);
  std::vector<std::unique_ptr<AtomicFileWriter>> writers;
  const auto add = [&](const fs::path& p, const void* data, std::size_t size) {
    writers.push_back(std::make_unique<AtomicFileWriter>(p));
    writers.back()->write(data, size);
  };
  add(path, depth.data(), depth.size());
  add(ConfidencePathFor(path), confidence.data(), confidence.size());
  add(PreviewPathFor(path), preview.data(), preview.size());
  CommitAll(writers);
}

}  // namespace lfcam
