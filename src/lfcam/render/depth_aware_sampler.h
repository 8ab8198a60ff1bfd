#pragma once
// Depth-aware lookup (`--interpolation depth`): a ray is read from the cameras around where it
// crosses the uv-plane, as the paper's lookup does, but each camera is read where the scene point
// that the ray hits projects into it, found from the views' depth maps (depth/depth_set.h), and
// a camera whose depth map disagrees with that point (it sees something in front of it) does not
// contribute. Pinhole views between cameras then show no ghosts, and the lens samples of an
// aperture each see the scene point they would really see, so the blur is right at every depth.
//
// Finding the point: each of the (up to four) cameras marches along the ray from the near end
// of the depth range to the far end, in steps of inverse depth small enough that the point's
// projection into that camera moves at most half a sample, and stops where the ray passes from
// in front of the surface it sees to behind it without a jump in that surface's depth (a jump
// means the ray passed behind an occluding edge). Each camera's hit is then put to the others:
// the hit most of the cameras' weight agrees with wins (the nearest on a tie; the cameras march
// heaviest first, and a hit all of them agree with ends the search), and the cameras
// that agree, each read at the hit's projection (bilinearly, or with a cubic kernel for frames at
// the views' resolution or finer: an 8-bit view's codes interpolated, LightFieldSampler::
// AccumulateAtCubic), are blended in linear light with their bilinear weights renormalised, and
// by default mixed with the agreeing cameras within two steps (DepthBlend below). A ray no
// camera finds a hit for falls back to the paper's lookup.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/depth/depth_set.h"
#include "lfcam/render/lightfield_sampler.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

// The views a frame through `camera` can read (row-major): the cameras around where its rays
// cross the uv-plane, traced for a lattice of pixels (every 8th, and the last row and column)
// and every lens sample, grown by one camera each way. The depth maps to make for it.
std::vector<bool> DepthViewsNeeded(const LightField& lf, const VirtualCamera& camera);

// Whether the depth lookup reads the views with Keys' cubic for this frame: where a pixel spans
// no more than kCubicFootprint samples at the frame's centre (a frame at the views' own
// resolution or finer: bilinear reads would blur it by up to half a sample; the held-out
// photographs of docs/fidelity.md +0.36 dB), not where pixels are coarser (there the views'
// detail beyond the frame's sampling aliases, and a sharper kernel keeps more of it: the paper
// scene's 128 x 128 frames of its 416 x 384 views 3 dB worse with cubic reads).
inline constexpr double kCubicFootprint = 1.25;

// How the cameras that see a ray's scene point are blended (`render --depth-blend`):
// - kFourCameras: the (up to four) cameras around where the ray crosses the uv-plane, by their
//   bilinear weights (the paper's lookup's cameras);
// - kAgreeing: also every camera within kAgreeingReach grid steps that sees the point, weighted
//   by a tent of its distance and by how well its colour agrees with the four's (a Gaussian of
//   the difference, its width the four's own spread about their blend and kAgreementFloor), so
//   that the photographs' independent noise and compression errors average down while a camera
//   the depth misplaces (its colour off) counts for little. Its share grows from nothing at a
//   camera (whose render is its own photograph) to all of it half a step away.
enum class DepthBlend { kFourCameras, kAgreeing };
inline constexpr double kAgreeingReach = 2.0;     // grid steps
inline constexpr double kAgreementFloor = 0.004;  // linear light (about one 8-bit level at grey)
// The agreeing blend's share at grid position (u, v) (columns, rows; cameras at integers):
// twice the distance to the nearest camera, at most 1.
float AgreeingShare(double u, double v);
std::string ToString(DepthBlend blend);
DepthBlend DepthBlendFromString(const std::string& name);  // throws lfcam::Error
bool DepthLookupReadsCubic(const VirtualCamera& camera, const LightFieldSampler& sampler);

class DepthAwareSampler {
 public:
  // `lf`, `depth` and `colour` must outlive the sampler; `depth` must hold a map for every
  // camera a ray can be read from (DepthViewsNeeded).
  DepthAwareSampler(const LightField& lf, const DepthSet& depth, const LightFieldSampler& colour);

  // Radiance along the line (origin, direction); false when it misses the slab.
  bool Sample(const Vec3& origin, const Vec3& direction, float rgb[3]) const;
  // Read the views with a cubic kernel instead of bilinearly (for frames at the views' own
  // resolution or finer; CpuRenderer decides).
  void set_cubic_reads(bool cubic) { cubic_reads_ = cubic; }
  void set_blend(DepthBlend blend) { blend_ = blend; }

  // The inverse-depth tolerance of the occlusion test (1/mm) at inverse depth q.
  double tolerance(double q) const;
  // The march's ends (inverse depth, 1/mm: the depth range widened a little) and the inverse
  // depth that moves a point one sample between neighbouring cameras (the GL renderer's too).
  double q_near() const { return q_near_; }
  double q_far() const { return q_far_; }
  double unit_q() const { return unit_q_; }
  // Whether camera (row, col) is read at all: it has a map and was photographed, not filled from
  // its neighbours (the GL renderer's per-view flags are these).
  bool reads(int row, int col) const {
    return cameras_[std::size_t(row * cols_ + col)].depth != nullptr;
  }

 private:
  struct Camera {
    const float* depth = nullptr;  // the view's map, row l, column k
    std::size_t stride = 0;        // floats per row
    StOffset window;               // the view's st window (its depth map's too)
    Vec3 center;
  };
  // Continuous sample coordinates of world point p in camera c's view; false when its line runs
  // parallel to the st-plane.
  bool Project(int c, const Vec3& p, double& k, double& l) const;
  // Camera c's depth (mm) at the nearest sample to (k, l); NaN outside the view or unknown.
  // (inline: the march's every step)
  float DepthAt(int c, double k, double l) const {
    const Camera& camera = cameras_[std::size_t(c)];
    if (!camera.depth) return NAN;
    k -= camera.window.k;  // the view's own samples
    l -= camera.window.l;
    if (!(k >= -0.5 && k < n_s_ - 0.5 && l >= -0.5 && l < n_t_ - 0.5)) return NAN;
    // Nearest sample (k, l >= -0.5 here: rounding half up is lround's after the clamp).
    const int ki = std::min(int(std::floor(k + 0.5)), n_s_ - 1);
    const int li = std::min(int(std::floor(l + 0.5)), n_t_ - 1);
    return camera.depth[std::size_t(li) * camera.stride + std::size_t(ki)];
  }
  // Whether camera c sees point p (inverse depth q), not something in front of or behind it (the
  // depth of the sample nearest to p's projection). If so, and `acc` is given, acc += w times
  // the view read there (bilinearly, or with Keys' cubic when set_cubic_reads).
  bool Read(int c, const Vec3& p, double q, float w, float acc[3]) const;
  // The inverse depth where the ray (origin, direction) hits the surface camera c sees, or a
  // negative number when it hits none.
  double March(int c, const Vec3& origin, const Vec3& direction) const;
  struct Neighbour {
    int index;
    float weight;
  };
  // DepthBlend::kAgreeing: rgb = the four cameras' blend at point p (inverse depth q) mixed with
  // the agreeing cameras' around grid position (u, v), every camera read once; false (rgb
  // untouched) when none of the four sees p.
  bool BlendAgreeing(const Vec3& p, double q, double u, double v, const Neighbour* around,
                     int count, float rgb[3]) const;

  const LightFieldSampler& colour_;
  bool cubic_reads_ = false;
  DepthBlend blend_ = DepthBlend::kAgreeing;
  Slab slab_;  // LightField::sampled_slab(): its st domain the union of the views' windows
  int rows_, cols_, n_s_, n_t_;
  std::vector<Camera> cameras_;  // row-major
  double q_near_, q_far_;        // the depth range's ends, widened a little
  double unit_q_;                // inverse depth that moves a point one sample between neighbours
};

}  // namespace lfcam
