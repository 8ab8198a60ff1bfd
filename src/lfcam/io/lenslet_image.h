#pragma once
// A plenoptic camera's photograph as one lenslet-interleaved image (the ESLF layout of the
// Stanford Lytro archive and of the light field toolboxes): every block of N x N pixels is one
// microlens's samples of the main lens's aperture, so the pixel (y, x) belongs to the view
// (y mod N, x mod N), at that view's sample (y / N, x / N). `lfcam import FILE` splits it into its
// N x N views (docs/format.md, "A lenslet image").
#include <filesystem>
#include <opencv2/core.hpp>
#include <vector>

namespace lfcam {

struct LensletPeriod {
  int views_per_side = 0;  // N; 0 where no period stands out
  // How strongly the mean brightness of the blocks' N x N positions varies (its standard
  // deviation over its mean): the main lens vignetting every microlens's image alike. Near 0
  // for an image with no such period.
  double strength = 0;
};

// The N (from 3 to 32, dividing both sides of `rgb8`, CV_8UC3) at which the blocks' positions
// differ most in mean brightness; of N and its multiples, which repeat the same pattern, the
// smallest that shows at least 0.9 of the strongest. `views_per_side` is 0 where no N divides
// both sides or the strongest pattern is under kLensletStrength.
inline constexpr double kLensletStrength = 0.05;
LensletPeriod DetectLensletPeriod(const cv::Mat& rgb8);

// The N x N views of a lenslet image whose sides N divides, row-major: view (a, b) (a from the top
// of each block, b from its left) holds the pixels (a + N i, b + N j). Throws lfcam::Error
// otherwise.
std::vector<cv::Mat> SplitLensletImage(const cv::Mat& image, int views_per_side);

// The views of `rgb8` (CV_8UC3) written into `folder` as a plenoptic camera's are named,
// view_RR_CC.png (RR = a + 1, CC = b + 1: row 01 at the top). Throws lfcam::Error naming the
// folder where a view cannot be written.
void WriteLensletViews(const cv::Mat& rgb8, int views_per_side,
                       const std::filesystem::path& folder);

}  // namespace lfcam
