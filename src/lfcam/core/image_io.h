#pragma once
// Images in memory are cv::Mat CV_32FC3 in linear light, channels R, G, B, row 0 at the top
// (as PNG stores them). Files are sRGB-encoded PNGs, written atomically.
#include <filesystem>
#include <opencv2/core.hpp>

namespace lfcam {

// Reads an 8- or 16-bit PNG/JPEG as linear RGB float. Throws lfcam::Error naming the file.
cv::Mat ReadImageLinear(const std::filesystem::path& path);
// Reads an image as 8-bit sRGB, channels R, G, B (CV_8UC3).
cv::Mat ReadImageSrgb8(const std::filesystem::path& path);
// Reads a mask (any channels; nonzero = inside) as CV_8UC1 of 0/255.
cv::Mat ReadMask(const std::filesystem::path& path);

cv::Mat LinearToSrgb8Image(const cv::Mat& linear_rgb);  // CV_32FC3 -> CV_8UC3
cv::Mat Srgb8ToLinearImage(const cv::Mat& srgb8_rgb);   // CV_8UC3 -> CV_32FC3

// Writes an sRGB 8-bit RGB image (CV_8UC3) or a linear float one (CV_32FC3, encoded first).
void WriteImage(const std::filesystem::path& path, const cv::Mat& rgb);

}  // namespace lfcam
