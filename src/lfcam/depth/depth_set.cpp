#include "lfcam/depth/depth_set.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "lfcam/core/atomic_file.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_codec.h"
#include "lfcam/core/input_file.h"
#include "lfcam/core/json_input.h"
#include "lfcam/core/limits.h"

namespace lfcam {

namespace fs = std::filesystem;

const DepthMap& DepthSet::at(int row, int col) const {
  if (row < 0 || row >= dims_.rows || col < 0 || col >= dims_.cols || !has(row, col))
    throw Error(fmt::format("no depth map for view ({}, {})", row, col));
  return *maps_[index(row, col)];
}

void DepthSet::set(DepthMap map) {
  if (map.row < 0 || map.row >= dims_.rows || map.col < 0 || map.col >= dims_.cols)
    throw Error(fmt::format("depth map of view ({}, {}) outside the {}x{} grid", map.row, map.col,
                            dims_.rows, dims_.cols));
  if (map.n_s() != dims_.n_s || map.n_t() != dims_.n_t)
    throw Error(
        fmt::format("depth map of view ({}, {}) is {}x{}; the light field's views are {}x{}",
                    map.row, map.col, map.n_s(), map.n_t(), dims_.n_s, dims_.n_t));
  const std::size_t i = index(map.row, map.col);
  maps_[i] = std::move(map);
}

int DepthSet::count() const {
  int n = 0;
  for (const auto& m : maps_) n += m.has_value();
  return n;
}

DepthRange DepthSet::range() const {
  DepthRange r{INFINITY, 0};
  for (const auto& m : maps_)
    if (m) r = {std::min(r.near_mm, m->range.near_mm), std::max(r.far_mm, m->range.far_mm)};
  return r.valid() ? r : DepthRange{};
}

std::string DepthFileName(int row, int col) {
  return fmt::format("depth_{:02d}_{:02d}.png", row, col);
}

void WriteDepthSet(const fs::path& dir, const DepthSet& set, const std::string& source_name,
                   const std::string& length_unit) {
  const auto& d = set.dims();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(fmt::format("{}: cannot create the folder ({})", dir.string(), ec.message()));
  const DepthRange range = set.range();
  nlohmann::json index = {{"format", "lfcam-depth-set"},
                          {"version", 1},
                          {"lightfield", source_name},
                          {"rows", d.rows},
                          {"cols", d.cols},
                          {"n_s", d.n_s},
                          {"n_t", d.n_t},
                          {"near_mm", range.near_mm},
                          {"far_mm", range.far_mm},
                          {"length_unit", length_unit},
                          {"views", nlohmann::json::array()}};
  const std::string extra = nlohmann::json{{"length_unit", length_unit}}.dump();
  std::vector<std::unique_ptr<AtomicFileWriter>> writers;
  const auto add = [&](const fs::path& p, const std::string& bytes) {
    writers.push_back(std::make_unique<AtomicFileWriter>(p));
    writers.back()->write(bytes.data(), bytes.size());
  };
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.cols; ++c) {
      if (!set.has(r, c)) continue;
      DepthMap map = set.at(r, c);
      map.range = range;  // one range for the set
      const fs::path file = dir / DepthFileName(r, c);
      add(file, EncodeDepthPng(map, extra));
      add(ConfidencePathFor(file), EncodeConfidencePng(map));
      index["views"].push_back({{"row", r}, {"col", c}, {"file", file.filename().string()}});
    }
  const int cr = (d.rows - 1) / 2, cc = (d.cols - 1) / 2;
  if (set.has(cr, cc)) {
    cv::Mat bgr;
    cv::cvtColor(DepthPreview(set.at(cr, cc), length_unit), bgr, cv::COLOR_RGB2BGR);
    const std::vector<std::uint8_t> png = EncodePngBytes(bgr);
    add(dir / "preview.png", std::string(png.begin(), png.end()));
  }
  add(dir / "depth.json", index.dump(2) + "\n");
  CommitAll(writers);
}

std::vector<DepthSetEntry> ParseDepthSetIndex(std::string_view text, const LightFieldDims& d,
                                              const std::string& where) {
  const nlohmann::json index = ParseJsonBounded(text, where);
  JsonFormatVersion(index, "lfcam-depth-set", 1, "depth set", where);
  const auto dim = [&](const char* key) {
    return int(JsonInteger(index, key, 1, kMaxStSamplesPerSide, where));
  };
  const int rows = dim("rows"), cols = dim("cols"), n_s = dim("n_s"), n_t = dim("n_t");
  if (rows != d.rows || cols != d.cols || n_s != d.n_s || n_t != d.n_t)
    throw Error(
        fmt::format("{}: made for a {}x{} grid of {}x{} views; this light field is {}x{} "
                    "of {}x{}",
                    where, rows, cols, n_s, n_t, d.rows, d.cols, d.n_s, d.n_t));
  const nlohmann::json& views = JsonField(index, "views", where);
  if (!views.is_array()) throw Error(fmt::format("{}: \"views\" must be an array", where));
  if (views.empty()) throw Error(fmt::format("{}: lists no views", where));
  std::vector<DepthSetEntry> entries;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const std::string at = fmt::format("{}: views[{}]", where, i);
    DepthSetEntry e;
    e.file = JsonString(views[i], "file", at);
    if (e.file.empty() || e.file.find('/') != std::string::npos || e.file.starts_with("."))
      throw Error(fmt::format("{}: file \"{}\" must be a plain name in the folder", at, e.file));
    e.row = int(JsonInteger(views[i], "row", 0, d.rows - 1, at));
    e.col = int(JsonInteger(views[i], "col", 0, d.cols - 1, at));
    entries.push_back(std::move(e));
  }
  return entries;
}

DepthSetRead DepthsForRendering(std::vector<bool> views) { return {false, std::move(views)}; }

DepthSet ReadDepthSet(const fs::path& dir, const LightField& lf, const DepthSetRead& what) {
  const fs::path index_path = dir / "depth.json";
  const std::string where = index_path.string();
  const auto bytes = ReadFileBytes(index_path, kMaxJsonBytes, "depth set index");
  const auto& d = lf.dims();
  std::vector<DepthSetEntry> entries = ParseDepthSetIndex(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), d, where);
  if (!what.views.empty()) {
    if (what.views.size() != d.view_count())
      throw Error(fmt::format("{}: internal: a choice of {} views for a grid of {}", where,
                              what.views.size(), d.view_count()));
    std::erase_if(entries, [&](const DepthSetEntry& e) {
      return !what.views[std::size_t(e.row) * d.cols + std::size_t(e.col)];
    });
  }
  // Each view's files on their own thread; a file's error is kept in its entry's place, so that
  // the one reported is the first in the index's order.
  std::vector<std::optional<DepthMap>> maps(entries.size());
  std::vector<std::string> errors(entries.size());
  tbb::parallel_for(std::size_t(0), entries.size(), [&](std::size_t i) {
    const DepthSetEntry& e = entries[i];
    const fs::path file = dir / e.file;
    try {
      DepthMap map = ReadDepthPng(file);
      if (map.row != e.row || map.col != e.col)
        throw Error(fmt::format("{}: holds view ({}, {}), the index says ({}, {})", file.string(),
                                map.row, map.col, e.row, e.col));
      if (map.n_s() != d.n_s || map.n_t() != d.n_t)
        throw Error(fmt::format("{}: is {}x{}, the light field's views are {}x{}", file.string(),
                                map.n_s(), map.n_t(), d.n_s, d.n_t));
      if (what.confidence && fs::exists(ConfidencePathFor(file)))
        ReadConfidencePng(ConfidencePathFor(file), map);
      maps[i] = std::move(map);
    } catch (const Error& error) {
      errors[i] = error.what();
    }
  });
  DepthSet set(d);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (!errors[i].empty()) throw Error(errors[i]);
    set.set(std::move(*maps[i]));
  }
  return set;
}

}  // namespace lfcam
