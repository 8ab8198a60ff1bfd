// `lfcam montage`: a labelled contact sheet of images (the demo's sequences).
#include <fmt/core.h>

#include <memory>
#include <sstream>

#include "lfcam/cli/commands.h"
#include "lfcam/core/contact_sheet.h"
#include "lfcam/core/image_io.h"

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
  montage->add_option("--out", flags->out, "PNG to write")->required();
  montage->add_option("--labels", flags->labels, "Labels separated by ';'");
  montage->add_option("--title", flags->title, "Title above the sheet");
  montage->add_option("--columns", flags->columns, "Images per row (0 = up to 6)");
  montage->add_option("--tile-width", flags->tile_width, "Width of each image on the sheet")
      ->capture_default_str();
  montage->callback([flags] {
    std::vector<cv::Mat> images;
    for (const auto& path : flags->images) images.push_back(ReadImageSrgb8(path));
    std::vector<std::string> labels;
    std::stringstream stream(flags->labels);
    for (std::string label; std::getline(stream, label, ';');) labels.push_back(label);
    WriteImage(flags->out,
               MakeContactSheet(images, labels, {flags->columns, flags->tile_width, flags->title}));
    fmt::print("wrote {}: {} images\n", flags->out, images.size());
  });
}

}  // namespace lfcam::cli
