#include "lfcam/core/atomic_file.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>

#include "lfcam/core/error.h"
#include "lfcam/core/image_io.h"
#include "lfcam/core/signal_cleanup.h"
#include "lfcam/core/test_support.h"

namespace lfcam {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::MakeScratchDir("lfcam_atomic_test"); }
  void TearDown() override { fs::remove_all(dir_); }
  int FilesIn(const fs::path& d) const {
    int n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(d)) ++n;
    return n;
  }
  fs::path dir_;
};

// A pid that certainly belongs to no running process: a child that has exited and been reaped.
long DeadPid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

TEST_F(AtomicFileTest, InterruptedWriteLeavesNoTemporary) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const fs::path target = dir_ / "out.lf";
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    EXPECT_EXIT(
        {
          InstallSignalCleanup();
          AtomicFileWriter writer(target);
          writer.write("half of it", 10);
          ::raise(signal_number);
          std::_Exit(0);  // not reached
        },
        ::testing::KilledBySignal(signal_number), "");
    EXPECT_EQ(FilesIn(dir_), 0) << "signal " << signal_number;
  }
}

TEST_F(AtomicFileTest, StaleTemporaryOfADeadWriterIsRemovedByTheNextWrite) {
  const fs::path target = dir_ / "image.png";
  const long dead = DeadPid();
  const fs::path stale = dir_ / ("image.png.tmp-" + std::to_string(dead));
  const fs::path live = dir_ / ("image.png.tmp-" + std::to_string(::getppid()));
  const fs::path other = dir_ / ("other.png.tmp-" + std::to_string(dead));
  for (const auto& p : {stale, live, other}) std::ofstream(p) << "partial";
  EXPECT_EQ(TemporaryOwner(stale.filename().string(), "image.png"), dead);
  EXPECT_EQ(TemporaryOwner("image.png.tmp-12x", "image.png"), std::nullopt);
  const std::uint8_t bytes[] = {1, 2, 3};
  WriteFileAtomically(target, bytes);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));   // its writer still runs
  EXPECT_TRUE(fs::exists(other));  // a temporary of another file
  EXPECT_EQ(fs::file_size(target), 3u);
}

TEST_F(AtomicFileTest, UnwritableOutputsAreNamedBeforeAnyWork) {
  const auto message = [](const fs::path& p) -> std::string {
    try {
      RequireWritableOutput(p, "--out");
    } catch (const UsageError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message(dir_ / "missing" / "x.png").find("does not exist"), std::string::npos);
  EXPECT_NE(message(dir_).find("is a directory"), std::string::npos);
  EXPECT_NE(message("/proc/lfcam.png").find("--out /proc/lfcam.png: cannot write in /proc"),
            std::string::npos)
      << message("/proc/lfcam.png");
  EXPECT_EQ(message(dir_ / "fine.png"), "");
  EXPECT_EQ(FilesIn(dir_), 0);  // the probe leaves nothing
  try {
    RequireImageOutput(dir_ / "x.tiff", "--out");
    ADD_FAILURE() << "a .tiff output was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find(".tiff"), std::string::npos);
  }
  // A write that fails still says why (never "Success").
  try {
    WriteFileAtomically("/proc/lfcam.png", {});
    ADD_FAILURE() << "wrote into /proc";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find("Success"), std::string::npos) << e.what();
  }
}

TEST_F(AtomicFileTest, TwoOutputsAreWrittenBothOrNeither) {
  const cv::Mat image(4, 4, CV_8UC3, cv::Scalar::all(7));
  EXPECT_THROW(WriteImages({{dir_ / "a.png", image}, {dir_ / "missing" / "b.png", image}}), Error);
  EXPECT_EQ(FilesIn(dir_), 0);
  EXPECT_THROW(WriteImages({{dir_ / "a.png", image}, {dir_ / "b.bmp", image}}), Error);
  EXPECT_EQ(FilesIn(dir_), 0);
  WriteImages({{dir_ / "a.png", image}, {dir_ / "b.jpg", image}});
  EXPECT_TRUE(fs::exists(dir_ / "a.png"));
  EXPECT_TRUE(fs::exists(dir_ / "b.jpg"));
  EXPECT_EQ(FilesIn(dir_), 2);
}

}  // namespace
}  // namespace lfcam
