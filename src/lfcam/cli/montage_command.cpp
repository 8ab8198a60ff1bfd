// `lfcam montage`: a labelled contact sheet of images (the demo's sequences).
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "lfcam/cli/commands.h"
#include "lfcam/core/contact_sheet.h"
#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/limits.h"

namespace lfcam::cli {

void AddMontageCommand(CLI::App& app) {
  auto* montage = app.add_subcommand("montage", "Lay images out on a labelled contact sheet");
  struct Flags {
    std::vector<std::string> images;
    std::string out, labels, title;
    int columns = 0, tile_width = 256;
  };
  auto flags = std::make_shared<Flags>();
  montage->add_option("images", flags->images, "Images, in order")->required();
  montage->add_option("--out", flags->out, "Image to write (.png or .jpg)")->required();
  montage->add_option("--labels", flags->labels, "Labels separated by ';'");
  montage->add_option("--title", flags->title, "Title above the sheet");
  montage->add_option("--columns", flags->columns, "Images per row (0 = up to 6)")
      ->check(CLI::Range(0, 1000));
  montage
      ->add_option("--tile-width", flags->tile_width,
                   fmt::format("Width of each image on the sheet (16..{})", kMaxImageSide))
      ->capture_default_str()
      ->check(CLI::Range(16, kMaxImageSide));
  montage->callback([flags] {
    // The sheet's width is known before any image is read; its height is checked once they are.
    const int n = int(flags->images.size());
    const int columns = flags->columns > 0 ? std::min(flags->columns, n) : std::min(n, 6);
    const double width = double(columns) * (flags->tile_width + 8) + 8;
    if (width > kMaxImageSide)
      throw UsageError(fmt::format(
          "--tile-width {} with {} columns makes a sheet {:.0f} pixels wide, more than the limit "
          "of {}",
          flags->tile_width, columns, width, kMaxImageSide));
    RequireImageOutput(flags->out, "--out");
    // Each image is shrunk to its tile as soon as it is read: memory stays bounded by the sheet,
    // however many images there are.
    std::vector<cv::Mat> images;
    for (const auto& path : flags->images) {
      const cv::Mat image = ReadImageSrgb8(path);
      const double height = std::round(double(image.rows) * flags->tile_width / image.cols);
      if (height > kMaxImageSide)
        throw UsageError(
            fmt::format("{}: a {}x{} image is {:.0f} pixels tall at --tile-width {}, "
                        "more than the limit of {}",
                        path, image.cols, image.rows, height, flags->tile_width, kMaxImageSide));
      cv::Mat tile;
      cv::resize(image, tile, {flags->tile_width, std::max(1, int(height))}, 0, 0, cv::INTER_AREA);
      images.push_back(tile);
    }
    std::vector<std::string> labels;
    std::stringstream stream(flags->labels);
    for (std::string label; std::getline(stream, label, ';');) labels.push_back(label);
    WriteImage(flags->out,
               MakeContactSheet(images, labels, {flags->columns, flags->tile_width, flags->title}));
    fmt::print("wrote {}: {} images\n", flags->out, images.size());
  });
}

}  // namespace lfcam::cli
