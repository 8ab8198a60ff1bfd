#include "lfcam/core/view_filling.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <climits>
#include <cstdio>
#include <opencv2/core.hpp>

#include "lfcam/core/color.h"
#include "lfcam/core/error.h"

namespace lfcam {

std::vector<std::pair<int, int>> NearestPresentViews(int rows, int cols,
                                                     const std::vector<bool>& present, int row,
                                                     int col) {
  std::vector<std::pair<int, int>> from;
  int best = INT_MAX;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      if (!present[std::size_t(r) * cols + c]) continue;
      const int d2 = (r - row) * (r - row) + (c - col) * (c - col);
      if (d2 < best) from.clear();
      if (d2 <= best) {
        best = d2;
        from.push_back({r, c});
      }
    }
  return from;
}

void FillViewWithMean(LightField& lf, int row, int col,
                      const std::vector<std::pair<int, int>>& from) {
  if (lf.sample_type() != SampleType::kSrgb8 || from.empty())
    throw Error("a view is filled from at least one view of an srgb8 light field");
  const auto& lut = SrgbDecodeTable();
  std::uint8_t* out = lf.mutable_view_data(row, col);
  if (!lf.has_view_windows()) {
    const std::size_t n = lf.view_bytes();
    for (std::size_t b = 0; b < n; ++b) {
      float sum = 0;
      for (const auto& [r, c] : from) sum += lut[lf.view_data(r, c)[b]];
      out[b] = LinearToSrgb8Table(sum / float(from.size()));
    }
    return;
  }
  // Views with their own windows: each sample of the filled view's window from the same st
  // sample of every view `from` (the nearest sample of its window where the point lies outside).
  const int n_s = lf.dims().n_s, n_t = lf.dims().n_t;
  const StOffset to = lf.st_offset(row, col);
  for (int l = 0; l < n_t; ++l)
    for (int k = 0; k < n_s; ++k)
      for (int ch = 0; ch < 3; ++ch) {
        float sum = 0;
        for (const auto& [r, c] : from) {
          const StOffset o = lf.st_offset(r, c);
          const int kk = std::clamp(k + to.k - o.k, 0, n_s - 1);
          const int ll = std::clamp(l + to.l - o.l, 0, n_t - 1);
          sum += lut[lf.view_data(r, c)[(std::size_t(ll) * n_s + std::size_t(kk)) * 3 + ch]];
        }
        out[(std::size_t(l) * n_s + std::size_t(k)) * 3 + ch] =
            LinearToSrgb8Table(sum / float(from.size()));
      }
}

std::string FilledViewLabel(int row, int col, const std::vector<std::pair<int, int>>& from) {
  std::vector<std::string> names;
  for (const auto& [r, c] : from) names.push_back(fmt::format("({}, {})", r, c));
  return fmt::format("camera ({}, {}) from {}", row, col, fmt::join(names, ", "));
}

std::vector<std::pair<int, int>> DarkViews(const LightField& lf, const std::vector<bool>& read) {
  const auto& d = lf.dims();
  const int w = d.n_s, h = d.n_t, views = d.rows * d.cols;
  if (lf.sample_type() != SampleType::kSrgb8 || int(read.size()) != views)
    throw Error("DarkViews: an srgb8 light field and a flag for each of its views");
  const cv::Rect middle(w / 8, h / 8, w - w / 4, h - h / 4);
  std::vector<double> brightness(std::size_t(views), -1);
  tbb::parallel_for(0, views, [&](int i) {
    if (!read[std::size_t(i)]) return;
    const cv::Mat view(h, w, CV_8UC3,
                       const_cast<std::uint8_t*>(lf.view_data(i / d.cols, i % d.cols)));
    const cv::Scalar mean = cv::mean(view(middle));
    brightness[std::size_t(i)] = mean[0] + mean[1] + mean[2];
  });
  std::vector<double> measured;
  for (double b : brightness)
    if (b >= 0) measured.push_back(b);
  std::vector<std::pair<int, int>> dark;
  if (measured.empty()) return dark;
  std::nth_element(measured.begin(), measured.begin() + long(measured.size() / 2), measured.end());
  const double median = measured[measured.size() / 2];
  if (!(median > 1.0)) return dark;  // black, all of it: nothing to tell the views apart by
  for (int i = 0; i < views; ++i)
    if (brightness[std::size_t(i)] >= 0 && brightness[std::size_t(i)] < kDarkViewShare * median)
      dark.emplace_back(i / d.cols, i % d.cols);
  return dark;
}

std::string DarkViewsNote(const std::vector<std::string>& labels) {
  return fmt::format(
      "{} view{} black or nearly (darker than 1/{:g} of the median view: no photograph of the "
      "scene), filled from {} neighbours as a missing view is (--keep-dark-views keeps them): {}",
      labels.size(), labels.size() == 1 ? "" : "s", 1 / kDarkViewShare,
      labels.size() == 1 ? "its" : "their", fmt::join(labels, ", "));
}

std::vector<std::pair<int, int>> FilledViews(const LightField& lf) {
  return FilledViews(lf.metadata(), lf.dims().rows, lf.dims().cols);
}

std::vector<std::pair<int, int>> FilledViews(const nlohmann::json& m, int rows, int cols) {
  const nlohmann::json* list = nullptr;
  if (m.contains("filled_views"))
    list = &m["filled_views"];
  else if (m.contains("import") && m["import"].is_object() && m["import"].contains("filled_views"))
    list = &m["import"]["filled_views"];
  std::vector<std::pair<int, int>> filled;
  if (!list || !list->is_array()) return filled;
  for (const nlohmann::json& entry : *list) {
    int row = -1, col = -1;
    if (entry.is_object() && entry.contains("row") && entry["row"].is_number_integer() &&
        entry.contains("col") && entry["col"].is_number_integer()) {
      row = entry["row"].get<int>(), col = entry["col"].get<int>();
    } else if (entry.is_string() &&
               std::sscanf(entry.get<std::string>().c_str(), "camera (%d, %d)", &row, &col) != 2) {
      continue;
    }
    if (row >= 0 && row < rows && col >= 0 && col < cols) filled.emplace_back(row, col);
  }
  return filled;
}

std::vector<bool> PhotographedViews(const LightField& lf) {
  std::vector<bool> photographed(lf.dims().view_count(), true);
  for (const auto& [r, c] : FilledViews(lf))
    photographed[std::size_t(r) * std::size_t(lf.dims().cols) + std::size_t(c)] = false;
  return photographed;
}

}  // namespace lfcam
