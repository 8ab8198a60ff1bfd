#include "lfcam/render/prefilter_cache.h"

#include <cmath>

namespace lfcam {
namespace {

bool SameFilter(const StPrefilter& a, const StPrefilter& b) {
  // The focus point is computed anew each frame: the same focus may differ in its last bits.
  const auto same = [](double x, double y) { return std::abs(x - y) <= 1e-9 * (1 + std::abs(x)); };
  return same(a.h_s, b.h_s) && same(a.h_t, b.h_t) && a.stride_s == b.stride_s &&
         a.stride_t == b.stride_t;
}

// What of `wanted` lies outside `held`, as up to four rectangles within their bounding
// rectangle (above, below, and left and right of `held`), and that bounding rectangle.
std::vector<cv::Rect> Missing(const cv::Rect& held, const cv::Rect& wanted, cv::Rect* grown) {
  if (held.empty()) {
    *grown = wanted;
    return {wanted};
  }
  if ((wanted & held) == wanted) {
    *grown = held;
    return {};
  }
  const cv::Rect u = held | wanted;
  *grown = u;
  std::vector<cv::Rect> parts = {
      cv::Rect(u.x, u.y, u.width, held.y - u.y),                          // above
      cv::Rect(u.x, held.br().y, u.width, u.br().y - held.br().y),        // below
      cv::Rect(u.x, held.y, held.x - u.x, held.height),                   // left
      cv::Rect(held.br().x, held.y, u.br().x - held.br().x, held.height)  // right
  };
  std::erase_if(parts, [](const cv::Rect& r) { return r.width <= 0 || r.height <= 0; });
  return parts;
}

}  // namespace

const LightField& PrefilterCache::Filtered(const LightField& lf, const StPrefilter& prefilter,
                                           const VirtualCamera& camera,
                                           const std::vector<bool>& views) {
  const std::lock_guard<std::mutex> lock(mutex_);
  // The same samples (a buffer), seen through the same layout (a copy of a light field may
  // share its buffer and differ in its windows or its slab).
  const StDomain& domain = lf.slab().st_domain;
  const bool same_light_field = serial_ == lf.samples_serial() && dims_ == lf.dims() &&
                                offsets_ == lf.st_offsets() && domain_.s0 == domain.s0 &&
                                domain_.t0 == domain.t0 && domain_.s1 == domain.s1 &&
                                domain_.t1 == domain.t1;
  if (!same_light_field || !SameFilter(prefilter_, prefilter)) {
    serial_ = 0;
    // The new copy in the old one's memory where it fits (pages already mapped and cleared),
    // else the old memory back before the new is taken.
    const std::size_t bytes = PrefilteredCopyBytes(lf, prefilter.stride_s, prefilter.stride_t);
    copy_ = LightField();
    if (memory_.size() < bytes) memory_ = SampleBuffer();
    copy_ = PrefilteredCopy(lf, prefilter.stride_s, prefilter.stride_t, memory_);
    if (memory_.size() < bytes) memory_ = copy_.samples();
    serial_ = lf.samples_serial();
    dims_ = lf.dims();
    offsets_ = lf.st_offsets();
    domain_ = domain;
    prefilter_ = prefilter;
    filtered_.assign(lf.dims().view_count(), cv::Rect());
  }
  const std::vector<cv::Rect> wanted = ViewRegionsRead(copy_, camera, views);
  // Each view's missing parts, filtered in rounds of one part a view.
  std::vector<std::vector<cv::Rect>> parts(wanted.size());
  std::vector<cv::Rect> grown = filtered_;
  std::size_t rounds = 0;
  last_filtered_samples_ = 0;
  for (std::size_t v = 0; v < wanted.size(); ++v) {
    if (wanted[v].empty()) continue;
    parts[v] = Missing(filtered_[v], wanted[v], &grown[v]);
    rounds = std::max(rounds, parts[v].size());
    for (const cv::Rect& r : parts[v]) last_filtered_samples_ += r.area();
  }
  try {
    for (std::size_t round = 0; round < rounds; ++round) {
      std::vector<cv::Rect> regions(wanted.size());
      for (std::size_t v = 0; v < wanted.size(); ++v)
        if (round < parts[v].size()) regions[v] = parts[v][round];
      PrefilterViews(lf, prefilter, regions, &copy_);
    }
  } catch (...) {
    serial_ = 0;  // what the copy holds is no longer known: the next frame starts afresh
    throw;
  }
  filtered_ = std::move(grown);
  return copy_;
}

}  // namespace lfcam
