// The names' axes against the views' own parallax: a synthetic rectified rig of two depths (a
// textured wall behind the zero-disparity plane, a textured card in front of it), named by
// indices the right way, with its rows (columns, both) counted the other way, with rows and
// columns exchanged, and of a single depth, as rectified and as parallel cameras; then `lfcam
// import` acting on what it finds, and the real data sets in
// ../shared/data when present (each agrees with its names).
#include "lfcam/io/parallax_axes.h"

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lfcam/cli/cli_test_support.h"
#include "lfcam/core/error.h"
#include "lfcam/io/grid_import.h"
#include "lfcam/io/parallel_import.h"
#include "lfcam/io/rectified_import.h"

namespace lfcam::parallax_axes_test {
namespace {

namespace fs = std::filesystem;

constexpr int kN = 5;  // cameras a side
constexpr int kWidth = 200, kHeight = 160;
// Disparities, px between neighbours: a rectified rig's wall behind its zero-disparity plane and
// card in front of it; a parallel rig's both in front of infinity.
struct Depths {
  double wall = -1.0, card = 1.5;
};
constexpr Depths kParallelDepths{1.0, 2.5};

enum class Naming {
  kRight,
  kRowsCountingUp,
  kColumnsCountingLeft,
  kBothCountingBack,
  kRowsAndColumnsExchanged
};

// Texture: smoothed noise, the same for a seed.
cv::Mat Texture(int seed) {
  cv::Mat t(kHeight + 80, kWidth + 80, CV_8UC3);
  cv::RNG rng{std::uint64_t(seed)};
  rng.fill(t, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(t, t, {5, 5}, 1.5);
  return t;
}

// The view of the camera at grid offset (dx right, dy up) from the centre: a point of
// disparity d appears at (x - d dx, y + d dy) of where the centre camera sees it.
cv::Mat View(const cv::Mat& wall, const cv::Mat& card, int dx, int dy, bool with_card,
             Depths depths) {
  const auto shifted = [&](const cv::Mat& t, double d) {
    const cv::Matx23d m(1, 0, -40 - d * dx, 0, 1, -40 + d * dy);
    cv::Mat out;
    cv::warpAffine(t, out, m, {kWidth, kHeight}, cv::INTER_CUBIC, cv::BORDER_REFLECT);
    return out;
  };
  cv::Mat view = shifted(wall, with_card ? depths.wall : 0.0);
  if (with_card) {
    const cv::Mat front = shifted(card, depths.card);
    const cv::Rect rect(int(std::lround(60 - depths.card * dx)),
                        int(std::lround(40 + depths.card * dy)), 80, 70);
    front(rect).copyTo(view(rect));
  }
  return view;
}

// Writes the rig into a fresh folder as NAME_RR_CC.png (row 01 at the top when named right).
fs::path WriteRig(const std::string& name, Naming naming, bool with_card = true,
                  Depths depths = {}) {
  const fs::path dir = fs::temp_directory_path() / (name + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const cv::Mat wall = Texture(1), card = Texture(2);
  for (int top = 0; top < kN; ++top)  // rows from the top
    for (int c = 0; c < kN; ++c) {
      const int dx = c - kN / 2, dy = kN / 2 - top;
      int rr = top + 1, cc = c + 1;
      if (naming == Naming::kRowsCountingUp || naming == Naming::kBothCountingBack) rr = kN - top;
      if (naming == Naming::kColumnsCountingLeft || naming == Naming::kBothCountingBack)
        cc = kN - c;
      if (naming == Naming::kRowsAndColumnsExchanged) std::swap(rr, cc);
      cv::imwrite((dir / fmt::format("card_{:02d}_{:02d}.png", rr, cc)).string(),
                  View(wall, card, dx, dy, with_card, depths));
    }
  return dir;
}

// The grid's centre row (`row`) or centre column alone, as a 1 x kN (kN x 1) grid. `across`:
// the centre column's views laid out where the centre row's cameras stand (a column named as a
// row), or the other way round.
ImportedGrid Line(const ImportedGrid& g, bool row, bool across = false) {
  ImportedGrid line = g;
  const bool as_row = row != across;
  line.rows = as_row ? 1 : kN;
  line.cols = as_row ? kN : 1;
  line.views.clear();
  line.missing.clear();
  for (int i = 0; i < kN; ++i) {
    const GridView& place = as_row ? g.view(kN / 2, i) : g.view(i, kN / 2);
    GridView v = row ? g.view(kN / 2, i) : g.view(i, kN / 2);
    v.row = as_row ? 0 : i;
    v.col = as_row ? i : 0;
    v.x_mm = place.x_mm;
    v.y_mm = place.y_mm;
    line.views.push_back(v);
  }
  return line;
}

TEST(ParallaxAxes, TheViewsSayWhetherTheNamesRowsRunTheWayItsColumnsDo) {
  const fs::path right = WriteRig("lfcam_axes_right_", Naming::kRight);
  const ParallaxAxes agree = MeasureParallaxAxes(right, ScanGridFolder(right, false));
  EXPECT_EQ(agree.verdict, AxesVerdict::kAgree) << Describe(agree);
  EXPECT_GT(agree.correlation, 0.9);
  EXPECT_GE(agree.points, 100);

  const fs::path up = WriteRig("lfcam_axes_up_", Naming::kRowsCountingUp);
  const ImportedGrid named = ScanGridFolder(up, false);
  const ParallaxAxes reversed = MeasureParallaxAxes(up, named);
  EXPECT_EQ(reversed.verdict, AxesVerdict::kRowsReversed) << Describe(reversed);
  EXPECT_LT(reversed.correlation, -0.9);
  // Reversed, the rows agree; so do both axes reversed (near and far exchanged: what the views
  // cannot tell), and not the columns alone.
  const ImportedGrid flipped = WithAxesReversed(named, true, false);
  EXPECT_EQ(MeasureParallaxAxes(up, flipped).verdict, AxesVerdict::kAgree);
  EXPECT_EQ(flipped.view(kN - 1, 0).file, "card_05_01.png");  // the top row, named counting up
  EXPECT_EQ(flipped.view(0, 0).y_mm, -named.view(kN - 1, 0).y_mm);
  EXPECT_EQ(MeasureParallaxAxes(up, WithAxesReversed(named, false, true)).verdict,
            AxesVerdict::kAgree);
  EXPECT_EQ(MeasureParallaxAxes(right, WithAxesReversed(named, true, true)).verdict,
            AxesVerdict::kAgree);
  EXPECT_EQ(MeasureParallaxAxes(right, WithAxesReversed(ScanGridFolder(right, false), false, true))
                .verdict,
            AxesVerdict::kRowsReversed);

  const fs::path exchanged = WriteRig("lfcam_axes_exchanged_", Naming::kRowsAndColumnsExchanged);
  const ParallaxAxes swapped = MeasureParallaxAxes(exchanged, ScanGridFolder(exchanged, false));
  EXPECT_EQ(swapped.verdict, AxesVerdict::kSwapped) << Describe(swapped);
  EXPECT_NE(Describe(swapped).find("exchanged"), std::string::npos);
  // Swapped back (the names' two indices exchanged), they agree.
  EXPECT_EQ(
      MeasureParallaxAxes(exchanged, WithAxesSwapped(ScanGridFolder(exchanged, false))).verdict,
      AxesVerdict::kAgree);

  // One depth: nothing to tell the axes by, and said so.
  const fs::path flat = WriteRig("lfcam_axes_flat_", Naming::kRight, false);
  const ParallaxAxes undecided = MeasureParallaxAxes(flat, ScanGridFolder(flat, false));
  EXPECT_EQ(undecided.verdict, AxesVerdict::kUndecided);
  EXPECT_NE(Describe(undecided).find("depth moves its points by"), std::string::npos)
      << Describe(undecided);
  // A single row or column of a rectified rig: nothing to check its one axis against, and said;
  // its largest parallax is measured all the same (the card's 1.5 px a step). Its centre column
  // named as a row moves across it: swapped.
  const ImportedGrid grid = ScanGridFolder(right, false);
  for (const bool is_row : {true, false}) {
    const ParallaxAxes line = MeasureParallaxAxes(right, Line(grid, is_row));
    EXPECT_EQ(line.verdict, AxesVerdict::kUndecided);
    EXPECT_TRUE(line.single_line);
    EXPECT_NE(Describe(line).find(is_row ? "a single row" : "a single column"), std::string::npos)
        << Describe(line);
    EXPECT_NEAR(line.largest_px_per_step, 1.5, 0.15) << Describe(line);
    const ParallaxAxes crossed = MeasureParallaxAxes(right, Line(grid, is_row, true));
    EXPECT_EQ(crossed.verdict, AxesVerdict::kSwapped) << Describe(crossed);
    EXPECT_NE(Describe(crossed).find("move across it"), std::string::npos) << Describe(crossed);
    // Swapped back, the line is one of the other kind.
    EXPECT_EQ(MeasureParallaxAxes(right, WithAxesSwapped(Line(grid, is_row, true))).verdict,
              AxesVerdict::kUndecided);
  }
  // A missing view: not checked, and why.
  ImportedGrid holed = ScanGridFolder(right, false);
  holed.views[std::size_t(2 * kN + 4)].file.clear();  // the centre row's right end
  EXPECT_NE(Describe(MeasureParallaxAxes(right, holed)).find("missing"), std::string::npos);
  for (const fs::path& dir : {right, up, exchanged, flat}) fs::remove_all(dir);
}

TEST(ParallaxAxes, ParallelCamerasTellEachAxisOnItsOwn) {
  // Every point moves against its camera: an axis along which they move with it is reversed.
  const std::pair<Naming, AxesVerdict> cases[] = {
      {Naming::kRight, AxesVerdict::kAgree},
      {Naming::kRowsCountingUp, AxesVerdict::kRowsReversed},
      {Naming::kColumnsCountingLeft, AxesVerdict::kColsReversed},
      {Naming::kBothCountingBack, AxesVerdict::kBothReversed}};
  for (const auto& [naming, verdict] : cases) {
    const fs::path dir = WriteRig("lfcam_axes_parallel_", naming, true, kParallelDepths);
    ImportedGrid grid = ScanGridFolder(dir, false);
    grid.rig = RigModel::kParallel;
    const ParallaxAxes axes = MeasureParallaxAxes(dir, grid);
    EXPECT_EQ(axes.verdict, verdict) << int(naming) << ": " << Describe(axes);
    // A single row (column) tells its own axis: reversed where the grid's columns (rows) are.
    const bool rows_reversed =
        verdict == AxesVerdict::kRowsReversed || verdict == AxesVerdict::kBothReversed;
    const bool cols_reversed =
        verdict == AxesVerdict::kColsReversed || verdict == AxesVerdict::kBothReversed;
    const ParallaxAxes row = MeasureParallaxAxes(dir, Line(grid, true));
    EXPECT_EQ(row.verdict, cols_reversed ? AxesVerdict::kColsReversed : AxesVerdict::kAgree)
        << int(naming) << ": " << Describe(row);
    const ParallaxAxes column = MeasureParallaxAxes(dir, Line(grid, false));
    EXPECT_EQ(column.verdict, rows_reversed ? AxesVerdict::kRowsReversed : AxesVerdict::kAgree)
        << int(naming) << ": " << Describe(column);
    // A rectified rig's views of the same tell only whether the two axes agree.
    grid.rig = RigModel::kRectified;
    EXPECT_EQ(MeasureParallaxAxes(dir, grid).verdict,
              naming == Naming::kRight || naming == Naming::kBothCountingBack
                  ? AxesVerdict::kAgree
                  : AxesVerdict::kRowsReversed)
        << int(naming);
    fs::remove_all(dir);
  }
}

TEST(ParallaxAxes, ImportTakesTheAxesTheWayTheViewsSayAndSaysIt) {
  const fs::path up = WriteRig("lfcam_axes_import_up_", Naming::kRowsCountingUp);
  const std::string lf = (up / "out.lf").string();
  auto run = testing::Lfcam(fmt::format("import {} --out {} --quiet", up.string(), lf));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("the rows are taken in reverse"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("--flip-cols"), std::string::npos) << run.output;
  run = testing::Lfcam(fmt::format("import {} --out {} --json", up.string(), lf));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto summary = nlohmann::json::parse(run.output);
  EXPECT_EQ(summary["axes"]["verdict"], "rows-reversed");
  EXPECT_EQ(summary["axes"]["flip_rows"], true);
  // The file named row 01 (counting up: the bottom row) is lfcam's row 0 once reversed.
  for (const auto& v : summary["views"]) {
    if (v["row"] == 0 && v["col"] == 0) {
      EXPECT_EQ(v["file"], "card_01_01.png");
    }
  }
  // Told, it keeps the names' axes (and says what the views say); told to flip, it does.
  run = testing::Lfcam(fmt::format("import {} --out {} --json --keep-axes", up.string(), lf));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(nlohmann::json::parse(run.output)["axes"]["flip_rows"], false);
  run = testing::Lfcam(fmt::format("import {} --out {} --json --flip-rows", up.string(), lf));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(nlohmann::json::parse(run.output)["axes"]["verdict"], "agree");

  // Rows and columns exchanged in the names: taken the other way round, and said.
  const fs::path exchanged =
      WriteRig("lfcam_axes_import_exchanged_", Naming::kRowsAndColumnsExchanged);
  const std::string swapped = (exchanged / "out.lf").string();
  run = testing::Lfcam(fmt::format("import {} --out {} --quiet", exchanged.string(), swapped));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("taken as columns"), std::string::npos) << run.output;
  run = testing::Lfcam(fmt::format("import {} --out {} --json", exchanged.string(), swapped));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto exchanged_summary = nlohmann::json::parse(run.output);
  EXPECT_EQ(exchanged_summary["axes"]["verdict"], "swapped");
  EXPECT_EQ(exchanged_summary["axes"]["swap_axes"], true);
  EXPECT_EQ(exchanged_summary["axes"]["flip_rows"], false);
  // The bottom-left camera (top row kN - 1 from the top, column 0) was named card_01_05.
  for (const auto& v : exchanged_summary["views"]) {
    if (v["row"] == 0 && v["col"] == 0) {
      EXPECT_EQ(v["file"], "card_01_05.png");
    }
  }
  run = testing::Lfcam(
      fmt::format("import {} --out {} --json --keep-axes", exchanged.string(), swapped));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(nlohmann::json::parse(run.output)["axes"]["swap_axes"], false);

  // A column of cameras named as a row (the centre column's views, top to bottom, as
  // card_01_01 ... card_01_05): its views move across the row, so it is taken as a column, the
  // first named at the top, and its parallax along it measured.
  const fs::path right = WriteRig("lfcam_axes_import_right_", Naming::kRight);
  const fs::path column =
      fs::temp_directory_path() / ("lfcam_axes_import_column_" + std::to_string(::getpid()));
  fs::remove_all(column);
  fs::create_directories(column);
  for (int top = 1; top <= kN; ++top)
    fs::copy_file(right / fmt::format("card_{:02d}_{:02d}.png", top, kN / 2 + 1),
                  column / fmt::format("card_01_{:02d}.png", top));
  run = testing::Lfcam(
      fmt::format("import {} --out {} --json", column.string(), (column / "out.lf").string()));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto column_summary = nlohmann::json::parse(run.output);
  EXPECT_EQ(column_summary["axes"]["verdict"], "swapped");
  EXPECT_EQ(column_summary["axes"]["swap_axes"], true);
  EXPECT_NEAR(column_summary["axes"]["largest_px_per_step"].get<double>(), 1.5, 0.15);
  EXPECT_EQ(column_summary["rows"], kN);
  EXPECT_EQ(column_summary["cols"], 1);
  for (const auto& v : column_summary["views"]) {
    if (v["row"] == kN - 1) {
      EXPECT_EQ(v["file"], "card_01_01.png");  // the top camera
    }
  }
  for (const fs::path& dir : {up, exchanged, right, column}) fs::remove_all(dir);
}

// Views named otherwise than NAME_RR_CC: indices alone (RR_CC), indices with dashes, and one
// numbered sequence (row by row from the top left, as the HCI benchmark numbers its cameras,
// from any first number) become the same grid; a sequence numbered column by column is taken
// row by row, and the views' parallax says the axes are exchanged. Names that are no sequence
// are refused with the reason.
TEST(ParallaxAxes, ViewsNamedByIndicesAloneOrInOneSequenceFormTheirGrid) {
  const fs::path named = WriteRig("lfcam_axes_named_", Naming::kRight);
  const ImportedGrid truth = ScanGridFolder(named, false);
  // Copies of the rig's files under other names: `rename(top, col)` (top: rows from the top).
  const auto renamed = [&](const std::string& name, const auto& rename) {
    const fs::path dir = fs::temp_directory_path() / (name + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::map<std::string, std::string> original;  // new name -> the rig's
    for (int top = 0; top < kN; ++top)
      for (int c = 0; c < kN; ++c) {
        const std::string from = fmt::format("card_{:02d}_{:02d}.png", top + 1, c + 1);
        const std::string to = rename(top, c);
        fs::copy_file(named / from, dir / to);
        original[to] = from;
      }
    return std::pair{dir, original};
  };
  // Every view of the grid read from the file that holds the rig's view at the same place.
  const auto same_grid = [&](const ImportedGrid& g, const std::map<std::string, std::string>& o) {
    ASSERT_EQ(g.rows, kN);
    ASSERT_EQ(g.cols, kN);
    for (int r = 0; r < kN; ++r)
      for (int c = 0; c < kN; ++c)
        EXPECT_EQ(o.at(g.view(r, c).file), truth.view(r, c).file) << r << "," << c;
  };
  std::vector<fs::path> dirs{named};
  for (const auto& [label, pattern] :
       {std::pair{"indices", "{:02d}_{:02d}.png"}, std::pair{"dashes", "card-{}-{}.png"},
        // Indices tagged with their axes, in either order, apart or joined.
        std::pair{"tagged", "card_r{:02d}_c{:02d}.png"},
        std::pair{"x before y", "view_x{1}_y{0}.png"}, std::pair{"joined", "R{}C{}.png"},
        std::pair{"u and v", "lf-v{}-u{}.png"}, std::pair{"row and col", "row{}_col{}.png"}}) {
    const std::string format = pattern;
    const auto [dir, original] = renamed(fmt::format("lfcam_axes_{}_", label), [&](int t, int c) {
      return fmt::format(fmt::runtime(format), t + 1, c + 1);
    });
    dirs.push_back(dir);
    const ImportedGrid g = ScanGridFolder(dir, false);
    EXPECT_EQ(g.naming, GridNaming::kUnitGrid) << label;
    same_grid(g, original);
  }
  // A row's and a column's index run together (0101.png ..): no sequence (it has gaps), but a
  // whole grid once each number is split in half, and said so.
  {
    const auto [dir, original] = renamed("lfcam_axes_joined_", [](int top, int c) {
      return fmt::format("{:02d}{:02d}.png", top + 1, c + 1);
    });
    dirs.push_back(dir);
    const ImportedGrid g = ScanGridFolder(dir, false);
    EXPECT_EQ(g.naming, GridNaming::kUnitGrid);
    EXPECT_EQ(g.joined_digits, 2);
    same_grid(g, original);
    ASSERT_EQ(NamingNotes(g).size(), 1u);
    EXPECT_NE(NamingNotes(g).front().find("run together, 2 digits each"), std::string::npos);
    // Forced to be a sequence, it is one with gaps.
    EXPECT_THROW(ScanGridFolder(dir, false, GridNaming::kSequence), Error);
    // Numbers without gaps are a sequence, not split: 20 views numbered 00 .. 19 are no 2 x 10
    // grid (and, not square, no grid at all).
    const fs::path run = dir.parent_path() / (dir.filename().string() + "run");
    fs::create_directories(run);
    dirs.push_back(run);
    for (int i = 0; i < 20; ++i)
      fs::copy_file(named / fmt::format("card_{:02d}_{:02d}.png", i / kN + 1, i % kN + 1),
                    run / fmt::format("{:02d}.png", i));
    try {
      ScanGridFolder(run, false);
      ADD_FAILURE() << "accepted " << run;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("sequence: 20 views are not a square grid"),
                std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("--grid ROWSxCOLS says it"), std::string::npos)
          << e.what();
    }
    // Given their shape (`import --grid 4x5`), they are the rig's top four rows, row by row.
    const ImportedGrid four = ScanGridFolder(run, false, std::nullopt, GridShape{4, 5});
    EXPECT_EQ(four.naming, GridNaming::kSequence);
    ASSERT_EQ(four.rows, 4);
    ASSERT_EQ(four.cols, 5);
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < kN; ++c)
        EXPECT_EQ(four.view(r, c).file, fmt::format("{:02d}.png", (3 - r) * kN + c)) << r << c;
    // A shape too small for the numbers, one the names already give otherwise, or a described
    // folder: refused, saying why.
    const auto refused = [](const fs::path& folder, GridShape shape, const std::string& why) {
      try {
        ScanGridFolder(folder, false, std::nullopt, shape);
        ADD_FAILURE() << "accepted " << folder;
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
      }
    };
    refused(run, {3, 5}, "sequence: 15.png: camera 15 is outside the 3x5 grid");
    // A grid mostly of holes is refused before it is made (4096 x 4096 took 28 s and 3 GB to
    // list its 16 million missing cameras); a grid with holes lists a dozen and counts the rest.
    refused(run, {4096, 4096}, "a 4096x4096 grid holds 16777216 cameras, and 20 views are named");
    refused(run, {2, 20},
            "the 2x20 grid is incomplete: camera (0, 0), camera (0, 1), camera (0, 2), camera (0, "
            "3), camera (0, 4), camera (0, 5), camera (0, 6), camera (0, 7), camera (0, 8), camera "
            "(0, 9), camera (0, 10), camera (0, 11) and 8 more are missing");
    refused(named, {1, 25}, "the names (unit-grid) give a 5x5 grid, not the 1x25 of --grid");
    // Through the command.
    const std::string lf = (run.parent_path() / (run.filename().string() + ".lf")).string();
    auto cli =
        testing::Lfcam(fmt::format("import {} --grid 4x5 --out {} --quiet", run.string(), lf));
    EXPECT_EQ(cli.status, 0) << cli.output;
    EXPECT_NE(cli.output.find("imported 4x5 views"), std::string::npos) << cli.output;
    fs::remove(lf);
    cli = testing::Lfcam(fmt::format("import {} --grid 0x5 --out {} --quiet", run.string(), lf));
    EXPECT_EQ(cli.status, 2) << cli.output;
    EXPECT_NE(cli.output.find("--grid"), std::string::npos) << cli.output;
    EXPECT_FALSE(fs::exists(lf));
  }
  const auto [rows, by_rows] = renamed("lfcam_axes_sequence_", [](int top, int c) {
    return fmt::format("view{:04d}.png", 100 + top * kN + c);
  });
  dirs.push_back(rows);
  const ImportedGrid sequence = ScanGridFolder(rows, false);
  EXPECT_EQ(sequence.naming, GridNaming::kSequence);
  EXPECT_EQ(sequence.rig, RigModel::kRectified);
  EXPECT_FALSE(sequence.positions_known);
  same_grid(sequence, by_rows);
  EXPECT_EQ(MeasureParallaxAxes(rows, sequence).verdict, AxesVerdict::kAgree);
  EXPECT_EQ(ScanGridFolder(rows, false, GridNaming::kSequence).naming, GridNaming::kSequence);
  // The sequence's order is said.
  const RectifiedGeometry geometry = ResolveRectifiedGeometry(sequence, {});
  ASSERT_EQ(geometry.notes.size(), 1u);
  EXPECT_NE(geometry.notes.front().find("row by row from the top left"), std::string::npos);
  EXPECT_TRUE(NamingNotes(truth).empty());
  // Imported as a parallel rig (--rig parallel), the file's import.notes say it too.
  ImportedGrid parallel = sequence;
  parallel.rig = RigModel::kParallel;
  ImportOptions focal;
  focal.focal_px = 100;
  EXPECT_EQ(MakeImportedSession(rows, parallel, focal).calibration.summary["import"]["notes"],
            nlohmann::json(geometry.notes));
  for (const std::string rig : {"rectified", "parallel"}) {
    const std::string lf = (rows.parent_path() / (rows.filename().string() + rig + ".lf")).string();
    const auto run = testing::Lfcam("import " + rows.string() + " --out " + lf + " --rig " + rig +
                                    " --focal-px 100 --quiet");
    fs::remove(lf);
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("  note: the views taken in the order of their files' numbers"),
              std::string::npos)
        << rig << ": " << run.output;
  }

  const auto [columns, by_columns] = renamed("lfcam_axes_sequence_columns_", [](int top, int c) {
    return fmt::format("{:03d}.png", c * kN + top);
  });
  dirs.push_back(columns);
  const ImportedGrid transposed = ScanGridFolder(columns, false);
  EXPECT_EQ(transposed.naming, GridNaming::kSequence);
  const ParallaxAxes swapped = MeasureParallaxAxes(columns, transposed);
  EXPECT_EQ(swapped.verdict, AxesVerdict::kSwapped) << Describe(swapped);
  same_grid(WithAxesSwapped(transposed), by_columns);

  // Not a sequence: a gap in the numbers, a file of another name; a name whose stem carries a
  // number is still read as the more specific naming it fits (here the rig's NAME_RR_CC).
  const auto refused = [&](const fs::path& dir, const std::string& what) {
    try {
      ScanGridFolder(dir, false);
      ADD_FAILURE() << "accepted " << dir;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  fs::rename(rows / "view0124.png", rows / "view0200.png");
  refused(rows, "sequence: the numbers run from 100 to 200 with gaps (25 files)");
  fs::rename(rows / "view0200.png", rows / "frame0124.png");
  refused(rows, "are not named alike (one name, then the number)");
  fs::remove(rows / "frame0124.png");
  refused(rows, "sequence: 24 views are not a square grid, and numbered names say nothing of its");
  EXPECT_EQ(truth.naming, GridNaming::kUnitGrid);

  // A real plenoptic camera's views (../shared/data/lytro-2067, NAME_RR_CC), linked under one
  // numbered sequence: the same grid, and its parallax agrees with that order.
  const fs::path lytro = fs::path(LFCAM_SOURCE_DIR) / "../shared/data/lytro-2067";
  if (fs::is_directory(lytro)) {
    const ImportedGrid as_named = ScanGridFolder(lytro, false);
    const fs::path linked =
        fs::temp_directory_path() / ("lfcam_axes_lytro_sequence_" + std::to_string(::getpid()));
    fs::remove_all(linked);
    fs::create_directories(linked);
    dirs.push_back(linked);
    std::map<std::string, std::string> original;
    for (int top = 0; top < as_named.rows; ++top)
      for (int c = 0; c < as_named.cols; ++c) {
        const std::string from = as_named.view(as_named.rows - 1 - top, c).file;
        const std::string to = fmt::format("lytro_{}.png", 1 + top * as_named.cols + c);
        fs::create_symlink(lytro / from, linked / to);
        original[to] = from;
      }
    const ImportedGrid g = ScanGridFolder(linked, false);
    EXPECT_EQ(g.naming, GridNaming::kSequence);
    ASSERT_EQ(g.rows, as_named.rows);
    for (int r = 0; r < g.rows; ++r)
      for (int c = 0; c < g.cols; ++c)
        EXPECT_EQ(original.at(g.view(r, c).file), as_named.view(r, c).file);
    const ParallaxAxes axes = MeasureParallaxAxes(linked, g);
    EXPECT_EQ(axes.verdict, AxesVerdict::kAgree) << Describe(axes);
  } else {
    std::cout << "[parallax axes] the Lytro views as a sequence skipped: " << lytro
              << " is not here\n";
  }
  for (const fs::path& dir : dirs) fs::remove_all(dir);
}

TEST(ParallaxAxes, TheRealDataSetsAgreeWithTheirNames) {
  const fs::path data = fs::path(LFCAM_SOURCE_DIR) / "../shared/data";
  int checked = 0;
  for (const char* set : {"hci-antinous", "lytro-2067", "shop-center-9x9"}) {
    if (!fs::is_directory(data / set)) continue;
    const ParallaxAxes axes = MeasureParallaxAxes(data / set, ScanGridFolder(data / set, false));
    EXPECT_EQ(axes.verdict, AxesVerdict::kAgree) << set << ": " << Describe(axes);
    EXPECT_GT(axes.correlation, 0.8) << set;
    ++checked;
  }
  if (checked == 0) GTEST_SKIP() << data << " is not here";
}

}  // namespace
}  // namespace lfcam::parallax_axes_test
