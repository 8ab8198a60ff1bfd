#pragma once
// The separable frame: the common case where a frame is a weighted sum of resized views.
//
// When the eye is on the array's plane and the camera looks along the array's normal (the
// paper's Tables 1 and 2, and most renders), the pieces of every pixel's estimate do not vary
// from pixel to pixel: each lens sample lies on the uv-plane, so its rays meet the uv-plane at
// the lens sample itself and read the same four cameras with the same weights everywhere, and
// the cameras integrator's footprint is the lens itself. What varies is only where each camera
// is read on the st-plane, and with the plane of focus parallel to the st-plane and the axes
// aligned, the sample column k depends on the pixel column alone and the sample row l on the
// pixel row alone. Every term of the estimate is then a view resized by a bilinear filter
// whose taps are separable: each needed sample row is decoded once, resampled along the row,
// and blended into the output rows, with no per-pixel gathers from the whole light field
// (render/separable_kernels.cpp).
//
// With the eye off the array's plane, still looking along its normal, the maps stay separable
// (the plane of focus is still parallel to the st-plane) and only the cameras integrator's
// weights vary from pixel to pixel: its terms are then every camera some pixel weighs, each
// weighing each pixel by that pixel's own footprint (SeparableFrame::pixel_weights). So does a
// camera turned about the array's vertical axis (an orbit sideways): the plane of focus then
// leans along the pixel rows, k still follows the pixel column alone, and l changes along each
// row as well, which the pixels' own blend of sample rows follows.
//
// A calibrated light field is separable only nearly: its st-plane (the world board) is turned
// a little against the array, so k also drifts with the pixel row and l with the column, by a
// few hundredths of a sample across the frame. Each pixel then still reads its own l (the
// blend across sample rows is per pixel), and each sample row is resampled along k once, as
// the pixel row that reads it at the middle column needs it; the other rows that read it lie
// within 1 / |dl/dj| of that one (farther by how much l changes along a row from its middle, for
// a camera also turned sideways), so their k is off by at most the drift over that many rows. Where
// that exceeds kSeparableTolerance samples (a camera turned up or down: k then drifts by a few
// thousandths of a sample a row), each band decodes its sample rows once and resamples each again
// for every few pixel rows that read it (SeparableFrame::resample_every), as long as a pixel row's
// reads cross few sample rows; beyond, the frame is rendered row by row.
#include <optional>
#include <vector>

#include "lfcam/core/lightfield.h"
#include "lfcam/render/camera_integrator.h"
#include "lfcam/render/cpu_renderer.h"
#include "lfcam/render/ray_setup.h"
#include "lfcam/render/virtual_camera.h"

namespace lfcam {

// The most (in samples) a resampled row's k may stray from a pixel's own: well inside one 8-bit
// step (1/255 = 0.0039 of the range a sample apart can span).
inline constexpr double kSeparableTolerance = 2e-3;

// view * weight, read along the lines from origin `read`, counted where the lines from origin
// `mask` meet the st domain.
struct SeparableTerm {
  int view = 0;  // row-major camera index
  int read = 0, mask = 0;
  float weight = 0;
};

struct SeparableFrame {
  // The line origins (lens samples, camera centres, the eye) against the st-plane, and p_o.
  std::vector<OriginConstants> origins;
  PlaneAffines st;
  std::vector<SeparableTerm> terms;
  // Lens samples: the pixel is the mean over these origins (each a lens sample whose rays meet
  // the array window) of their terms, counted where each meets the st domain. The cameras
  // integrator: empty, `eye` set, and every term masked by its own camera's line (a camera counts
  // where its line through p_o meets the domain, or with a taper, RaySetup::taper, by the share
  // of its tent inside its view's window; the counted weights are renormalised).
  std::vector<int> hit_origins;
  int eye = -1;
  int reads_per_pixel = 0;  // the cameras integrator: its cameras (those a pixel can read)
  // The cameras integrator with the eye off the array's plane (looking along its normal, so the
  // maps stay separable): each pixel weighs the cameras by its own footprint, and these give the
  // weights row by row (CameraIntegratorFrame::RowWeights); the terms' `weight` is then 1. It
  // must outlive the frame.
  const CameraIntegratorFrame* pixel_weights = nullptr;
  int width = 0, height = 0;
  int band_rows = 32;    // pixel rows rendered together (a task)
  double map_error = 0;  // samples: the most a resampled row's k strays from a pixel's own
  // 0: each sample row is resampled once a band, for the pixel row nearest where l crosses it.
  // n > 0: k drifts with the pixel row too fast for that, and each sample row is resampled for
  // each group of n pixel rows that reads it (n = 1 + 2 floor(tolerance / the drift a row)), at
  // the group's middle row; the band decodes each of its sample rows once.
  int resample_every = 0;
};

// The separable form of the frame, or nothing when the frame is not separable (lens samples off
// the array's plane, a turned camera, an st-plane turned too far) or the light field cannot be
// read by the fast kernels. `cameras`, when given, is the cameras integrator's frame for `camera`
// on a light field of `lf`'s slab and grid (its weights are then not worked out again); the
// cameras integrator with the eye off the array's plane is separable only with it (the frame
// keeps a pointer to it).
std::optional<SeparableFrame> MakeSeparableFrame(const LightField& lf, const VirtualCamera& camera,
                                                 const CpuRenderOptions& options,
                                                 const CameraIntegratorFrame* cameras = nullptr);

}  // namespace lfcam
